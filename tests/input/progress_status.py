"""Following a long run: the progress line comes every 'Progress interval'
of wall time, and the file 'status' in the output directory says where the
run is, whole at every moment (written aside, then renamed).

- While the Taylor bar runs, status reads 'state: running' with a step and
  a fraction done between 0 and 1, and whole (every line 'key: value', the
  keys of the finished file);
- at the end: 'state: finished', fraction 1, the step count and the final
  energies of summary.csv;
- a run makes its PNG plots by default (one per history file);
- a run stopped by a numerical failure: 'state: stopped' and the message;
- the progress lines follow the wall clock: their count is printed against
  the wall time over the interval (not asserted: timing), and at least the
  first and the last are there."""
import os
import subprocess
import time
from anvil_test import Checker, arguments, read_csv, write_scene

args = arguments()
c = Checker("progress line and status file")
scene = os.path.join(args.source_dir, "prm/steel_bar_impact/steel_bar_impact.prm")


def read_status(path):
    """The status file as a dict, or None if absent."""
    try:
        with open(path) as f:
            text = f.read()
    except FileNotFoundError:
        return None
    return dict(line.split(": ", 1) for line in text.splitlines())


prm = write_scene(os.path.join(args.work_dir, "follow.prm"), include=scene, text="""
subsection Simulation
  set Output interval   = 0
  set End time          = 3e-4
  set Progress interval = 0.2
end
""")
status_file = os.path.join(args.work_dir, "output/follow/status")
# As a user runs it: without the suite's ANVIL_DEFAULT_PLOTS=false, so the
# run also makes its plots.
user_env = {k: v for k, v in os.environ.items() if k != "ANVIL_DEFAULT_PLOTS"}
run = subprocess.Popen([args.anvil, prm], cwd=args.work_dir, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, env=user_env)
seen, malformed = [], 0
while run.poll() is None:
    try:
        s = read_status(status_file)
    except ValueError:
        malformed += 1
        s = None
    if s:
        seen.append(s)
    time.sleep(0.05)
out, err = run.communicate()
c.check_true("the run exits 0", run.returncode == 0, err.strip())
running = [s for s in seen if s.get("state") == "running"]
c.check_true("status read 'running' during the run", len(running) > 0, f"{len(seen)} reads")
c.check_true("every read of status was whole ('key: value' lines)", malformed == 0,
             f"{malformed} malformed reads")
if running:
    fractions = [float(s["fraction_done"]) for s in running]
    c.check_true("fraction done between 0 and 1 and never falling",
                 all(0 <= f <= 1 for f in fractions) and fractions == sorted(fractions),
                 f"{fractions[0]:.3g} ... {fractions[-1]:.3g}")
final = read_status(status_file)
summary = dict(zip(*[read_csv(os.path.join(args.work_dir, "output/follow/summary.csv"))[k]
                     for k in ("quantity", "value")]))
if c.check_true("status at the end: finished", final is not None and final["state"] == "finished"):
    c.check("status: fraction done", float(final["fraction_done"]), 1.0, 0)
    c.check("status: steps against summary.csv", float(final["step"]), summary["steps"], 0)
    c.check("status: kinetic energy against summary.csv [J]", float(final["kinetic_energy_J"]),
            summary["final_kinetic_energy_J"], 1e-6, relative=True)
    if running:
        c.check_true("status while running has every key of the finished one but the message",
                     set(final) <= set(running[-1]) | {"wall_time_left_s"})
pngs = ("energy.png", "probe_front.png", "probe_rear.png", "contact_impact.png", "rigid_wall.png")
listed = open(os.path.join(args.work_dir, "output/follow/anvil_files.txt")).read().split()
c.check_true("a run makes its plots by default, one per history file, listed as its own",
             all(os.path.getsize(os.path.join(args.work_dir, "output/follow", p)) > 1000 and
                 p in listed for p in pngs),
             next((l.strip() for l in out.splitlines() if "plots" in l), "no plots line"))
lines = [l for l in out.splitlines() if l.strip().startswith("step ")]
wall = summary["wall_time_s"]
print(f"  progress lines: {len(lines)} in {wall:.2f} s of wall time at 0.2 s intervals "
      f"(about {1 + wall / 0.2:.0f} expected; not asserted)")
def line_time(line):
    return float(line.split("t =")[1].split()[0])


c.check_true("progress: the first (step 0) and the last (the end time) line are printed",
             len(lines) >= 2 and line_time(lines[0]) == 0 and
             abs(line_time(lines[-1]) - 3e-4) <= 1e-12, lines[-1] if lines else "none")

# A run that stops: the status names why.
prm = write_scene(os.path.join(args.work_dir, "stop.prm"), include=scene, text="""
subsection Simulation
  set Output interval         = 0
  set Maximum number of steps = 20
end
""")
r = subprocess.run([args.anvil, prm], cwd=args.work_dir, capture_output=True, text=True)
s = read_status(os.path.join(args.work_dir, "output/stop/status"))
c.check_true("a stopped run: exit 3", r.returncode == 3, r.stderr.strip())
c.check_true("a stopped run: status 'stopped' with the message",
             s is not None and s.get("state") == "stopped" and
             "Maximum number of steps" in s.get("message", ""), str(s))
c.finish()
