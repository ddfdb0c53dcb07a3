"""Results that stay consistent on disk (tests/input/output_consistency.prm).

- A run deletes only files a run wrote: a user's files in the output
  directory survive a rerun with 'Overwrite existing output = true', and
  every file the run lists in anvil_files.txt exists.
- A finished run leaves no temporary file (everything is written to a
  temporary name and renamed when whole).
- A run killed (SIGKILL) mid-way leaves whole CSV rows (every row has the
  header's number of numbers), all histories cut at the same row, and a
  frame index (solution.pvd) whose every frame is on disk.
- Past a file-size limit the run stops with exit 4 and one line naming the
  file and the cause, instead of exit 0 with truncated histories.
- --check reports an output directory that is a file.
"""
import csv
import os
import re
import signal
import subprocess
import time
from anvil_test import Checker, arguments, test_scene

args = arguments()
c = Checker("results consistent on disk")
work = args.work_dir



def scene(name, end, output, n):
    return test_scene(args, "tests/input/output_consistency.prm", name,
                      {"Simulation/End time": end, "Simulation/Output interval": output,
                       "Body block/Mesh/Subdivisions": f"{n}, {n}, {n}"})


def run(prm, **kw):
    return subprocess.run([args.anvil, prm], cwd=work, capture_output=True, text=True, **kw)


# A user's files survive; the run's list names only files that exist.
prm = scene("keep", 0.2, 0.05, 3)
r = run(prm)
c.check_true("first run", r.returncode == 0, r.stderr.strip())
out = os.path.join(work, "output", "keep")
for name in ("my_notes.csv", "my_mesh.vtu", "my.pvd"):
    with open(os.path.join(out, name), "w") as f:
        f.write("mine\n")
r = run(prm)
c.check_true("rerun with 'Overwrite existing output = true'", r.returncode == 0, r.stderr.strip())
c.check_true("the user's .csv, .vtu and .pvd files survive",
             all(open(os.path.join(out, n)).read() == "mine\n" for n in ("my_notes.csv", "my_mesh.vtu", "my.pvd")))
listed = open(os.path.join(out, "anvil_files.txt")).read().split()
missing = [n for n in listed if not os.path.exists(os.path.join(out, n))]
c.check_true(f"anvil_files.txt lists {len(listed)} files, every one on disk", not missing and len(listed) > 5,
             ", ".join(missing))
c.check_true("the list names energy.csv, summary.csv, solution.pvd and the frames",
             all(n in listed for n in ("energy.csv", "summary.csv", "solution.pvd", "solution_0004.pvtu",
                                        "solution_0004.0.vtu")))
# Every file is written to a temporary name and renamed when whole: a
# finished run leaves none of those.
temporary = [n for n in os.listdir(out) if n.endswith(".tmp") or ".new" in n]
c.check_true("a finished run leaves no temporary file", not temporary, ", ".join(temporary))

# Killed mid-way: whole rows, histories cut together, a valid frame index.
prm = scene("killed", 1e3, 0.5, 8)
p = subprocess.Popen([args.anvil, prm], cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
time.sleep(4.0)
p.send_signal(signal.SIGKILL)
p.wait()
out = os.path.join(work, "output", "killed")
last_times, bad_rows = {}, []
for name in sorted(os.listdir(out)):
    if not name.endswith(".csv"):
        continue
    with open(os.path.join(out, name)) as f:
        rows = list(csv.reader(f))
    for k, row in enumerate(rows[1:], 2):
        if len(row) != len(rows[0]) or not all(re.fullmatch(r"[-+0-9.eE]+|nan|inf", x) for x in row):
            bad_rows.append(f"{name}:{k}")
    if len(rows) > 1:
        last_times[name] = rows[-1][0]
c.check_true(f"whole rows in {len(last_times)} histories", not bad_rows and len(last_times) >= 2,
             ", ".join(bad_rows[:5]))
c.check_true("every history ends at the same time",
             max(map(float, last_times.values())) - min(map(float, last_times.values())) <= 1e-9, str(last_times))
pvd = open(os.path.join(out, "solution.pvd")).read()
frames = re.findall(r'file="([^"]+)"', pvd)
pieces_ok = all(os.path.exists(os.path.join(out, f)) for f in frames) and all(
    os.path.exists(os.path.join(out, piece)) for f in frames
    for piece in re.findall(r'Source="([^"]+)"', open(os.path.join(out, f)).read()))
c.check_true(f"solution.pvd is whole and its {len(frames)} frames (and their pieces) are on disk",
             pvd.rstrip().endswith("</VTKFile>") and len(frames) >= 2 and pieces_ok)
# (A SIGKILL that lands while the index is being written leaves its
# temporary beside it, which no process can then remove; the index itself
# is the one of the last frame written whole, checked above.)

# A file-size limit: one line naming the file and the cause, exit 4.
prm = scene("limited", 20, 0, 2)
# (The limit applies to anvil alone: MPI's own start-up files must not meet it.)
r = subprocess.run(["mpirun", "-np", "1", "bash", "-c", f"ulimit -f 200 && exec '{args.anvil}' '{prm}'"],
                   cwd=work, capture_output=True, text=True)
lines = [l for l in r.stderr.splitlines() if l.startswith("anvil:")]
c.check_true("past a 200 kB file-size limit: exit 4, one line naming the file and 'File too large'",
             r.returncode == 4 and len(lines) == 1 and ".csv" in lines[0] and "File too large" in lines[0],
             f"exit {r.returncode}: {' '.join(lines)[:300]}")
with open(os.path.join(work, "output", "limited", "energy.csv")) as f:
    rows = list(csv.reader(f))
c.check_true(f"the history stops at a whole row ({len(rows)} rows)",
             all(len(row) == len(rows[0]) for row in rows) and len(rows) > 100)

# --check: an output directory that is a file.
os.makedirs(os.path.join(work, "output"), exist_ok=True)
with open(os.path.join(work, "output", "blocked"), "w") as f:
    f.write("a file\n")
prm = scene("blocked", 0.1, 0, 2)
r = subprocess.run([args.anvil, "--check", prm], cwd=work, capture_output=True, text=True)
c.check_true("--check: the output directory is a file: exit 2, one line",
             r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "is a file" in r.stderr,
             r.stderr.strip())
c.finish()
