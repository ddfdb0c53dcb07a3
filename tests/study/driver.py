"""The study driver (`anvil --study`) on the two colliding rods, and the
scene overrides it is built on (`anvil SCENE.prm --set PATH=VALUE`).

Physics through the study: the rods are linear elastic, so over a grid of
impact velocity v (0.5, 1, 2 m/s) and contact penalty factor (0.05, 0.1)
the peak contact force divided by v is one number per penalty factor, and
the contact lasts 2L/c = 0.2 s (bar theory) in every run; the peak force
itself is the bar-theory force rho c A v / 2 plus the overshoot of the
penalty spring. The driver: study.csv holds each run's own summary.csv, a
study started again skips the runs that finished (and reruns one whose
status was removed or whose value changed), bad input stops before any
run with one line, and a run on two processes gives the one-process
figures.
"""
import os
import shutil
import subprocess
from anvil_test import Checker, arguments, read_csv

args = arguments()
c = Checker("study driver")
rod = os.path.join(os.path.abspath(args.source_dir), "prm", "elastic_rod_impact", "elastic_rod_impact.prm")
work = args.work_dir
shutil.rmtree(os.path.join(work, "output"), ignore_errors=True)


def study_file(name, variables, extra=""):
    path = os.path.join(work, name + ".prm")
    with open(path, "w") as f:
        f.write(f"set Base scene = {rod}\n"
                "set Fixed entries = Simulation/Print wall times=false; Simulation/Output interval=0\n"
                "set History plot = contact_impact.csv:normal_force_x\n"
                "set History label = contact force (N)\n" + extra)
        f.write("set Variables = " + ", ".join(v[0] for v in variables) + "\n")
        for name_, entry, values in variables:
            # (A label with a quote: the plots' command line must carry it.)
            f.write(f"subsection Variable {name_}\n  set Entry = {entry}\n  set Values = {values}\n"
                    f"  set Label = rod A's {name_}\nend\n")
    return path


def study(path, jobs=2):
    r = subprocess.run([args.anvil, "--study", path, "--jobs", str(jobs)], cwd=work,
                       capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


grid = [("v", "Body rod_a/Initial velocity", "0.5, 0, 0; 1, 0, 0; 2, 0, 0"),
        ("penalty", "Contact pair impact/Penalty scale factor", "0.05; 0.1")]
path = study_file("rods", grid)
code, out, err = study(path)
c.check_true("study runs", code == 0, err.strip()[-300:])
table = read_csv(os.path.join(work, "output", "rods", "study.csv"))
c.check("runs in study.csv (grid 3 x 2)", len(table["run"]), 6, 0)
c.check_true("history.png and summary.png written",
             all(os.path.exists(os.path.join(work, "output", "rods", p))
                 for p in ("history.png", "summary.png")), out.strip().splitlines()[-1])

# study.csv carries each run's own summary.
worst = 0.0
for i, run in enumerate(table["run"]):
    s = read_csv(os.path.join(work, "output", "rods", run, "summary.csv"))
    own = dict(zip(s["quantity"], s["value"]))
    for q in ("peak_contact_force_N", "contact_duration_s", "max_balance_error"):
        worst = max(worst, abs(own[q] - table[q][i]) / max(abs(own[q]), 1e-300))
c.check_below("study.csv against the runs' summary.csv (relative)", worst, 1e-9)

# Linear elasticity: F_peak / v is one number per penalty factor.
rho, E, A, L = 0.01, 100.0, 1.0, 10.0
wave = (E / rho) ** 0.5
for penalty in (0.05, 0.1):
    rows = [i for i in range(6) if abs(table["penalty_plot_value"][i] - penalty) < 1e-12]
    ratios = [table["peak_contact_force_N"][i] / table["v_plot_value"][i] for i in rows]
    spread = (max(ratios) - min(ratios)) / min(ratios)
    c.check_below(f"penalty {penalty}: spread of F_peak / v over v = 0.5, 1, 2", spread, 0.01)
    c.check(f"penalty {penalty}: F_peak / v against rho c A / 2 (penalty overshoot)",
            ratios[1], rho * wave * A / 2, 0.15, relative=True)
# The penalty spring's compliance lengthens the contact: by about 3 % at
# the factor 0.1, 6 % at 0.05.
for i in range(6):
    c.check(f"{table['run'][i]}: contact duration against 2 L / c", table["contact_duration_s"][i],
            2 * L / wave, 0.08, relative=True)

# Started again: every run is skipped; a removed status or a changed value
# reruns just that run.
logs = {r: os.path.getmtime(os.path.join(work, "output", "rods", r, "run.log")) for r in table["run"]}
code, out, err = study(path)
c.check("runs skipped when started again", out.count("finished earlier: skipped"), 6, 0)
c.check_true("no run started again", "started" not in out and all(
    os.path.getmtime(os.path.join(work, "output", "rods", r, "run.log")) == t for r, t in logs.items()))
os.remove(os.path.join(work, "output", "rods", "run_03", "run.status"))
code, out, err = study(path)
c.check_true("a run without its status reruns, alone",
             out.count("started") == 1 and "run 3 of 6" in out.split("started")[0].splitlines()[-1], out)
grid_changed = [grid[0], ("penalty", grid[1][1], "0.05; 0.2")]
code, out, err = study(study_file("rods", grid_changed))
c.check("runs rerun after a value changed (0.1 -> 0.2)", out.count("started"), 3, 0)
c.check_true("the changed study still ends with exit 0", code == 0, err.strip())

# Bad input: one line, exit 2, no run directory made.
bad_cases = [
    ("unknown_path", [("v", "Body rod_a/Initial velocityy", "1, 0, 0")], "",
     ["Variable v", "Initial velocityy", "No entry"]),
    ("unknown_subsection", [("v", "Body rod_c/Initial velocity", "1, 0, 0")], "",
     ["Variable v", "rod_c", "line 1 of the override"]),
    ("bad_value", [("p", "Contact pair impact/Penalty scale factor", "0.1; abc")], "",
     ["Variable p", "abc", "Penalty scale factor"]),
    ("zip_lengths", [("v", "Body rod_a/Initial velocity", "1, 0, 0; 2, 0, 0"),
                     ("p", "Contact pair impact/Penalty scale factor", "0.1")], "set Combination = zip\n",
     ["zip", "'v' has 2", "'p' 1"]),
    ("unknown_study_entry", [("v", "Body rod_a/Initial velocity", "1, 0, 0")], "set Jobz = 2\n",
     ["unknown_study_entry.prm", "Jobz"]),
]
for name, variables, extra, words in bad_cases:
    code, out, err = study(study_file(name, variables, extra))
    lines = err.strip().splitlines()
    c.check_true(f"{name}: exit 2, one line naming {words}",
                 code == 2 and len(lines) == 1 and all(w in err for w in words), err.strip())
    c.check_true(f"{name}: nothing run", not os.path.exists(os.path.join(work, "output", name)))

# --set on a scene: the entry changes; a bad path is one line.
r = subprocess.run([args.anvil, rod, "--set", "Simulation/End time=0.05", "--set",
                    "Simulation/Name=short"], cwd=work, capture_output=True, text=True)
s = read_csv(os.path.join(work, "output", "short", "summary.csv"))
c.check("--set 'Simulation/End time=0.05': end time", dict(zip(s["quantity"], s["value"]))["end_time_s"],
        0.05, 1e-12)
# --print-cost: the steps it foresees are the steps the run takes (the
# rods' step hardly changes).
r = subprocess.run([args.anvil, "--print-cost", rod, "--set", "Simulation/End time=0.05", "--set",
                    "Simulation/Name=cost_only"], cwd=work,
                   capture_output=True, text=True)
import re  # noqa: E402
m = re.search(r"-> (\d+) steps", r.stdout)
c.check("--print-cost: steps foreseen against the steps of the run",
        float(m.group(1)) if m else 0.0, dict(zip(s["quantity"], s["value"]))["steps"], 0.03, relative=True)
c.check_true("--print-cost writes nothing", not os.path.exists(os.path.join(work, "output", "cost_only")))
r = subprocess.run([args.anvil, rod, "--set", "Simulation/End tim=0.05"], cwd=work, capture_output=True,
                   text=True)
c.check_true("--set with an unknown entry: exit 2, one line naming the override",
             r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and
             "override 'Simulation/End tim=0.05'" in r.stderr, r.stderr.strip())

# A run on two processes gives the one-process figures.
path = study_file("two_processes", [("v", "Body rod_a/Initial velocity", "1, 0, 0"),
                                    ("penalty", grid[1][1], "0.05")],
                  "set Processes per run = 2\nset MPI launcher = mpirun --oversubscribe -np\n")
code, out, err = study(path, jobs=1)
c.check_true("a study with 2 processes per run", code == 0, (err + out).strip()[-300:])
two = read_csv(os.path.join(work, "output", "two_processes", "study.csv"))
one = read_csv(os.path.join(work, "output", "rods", "study.csv"))
i = [k for k in range(6) if one["v_plot_value"][k] == 1.0 and one["penalty_plot_value"][k] == 0.05][0]
c.check("np = 2 against np = 1: peak contact force", two["peak_contact_force_N"][0],
        one["peak_contact_force_N"][i], 1e-8, relative=True)
c.check("np = 2 run reports 2 processes", two["processes"][0], 2, 0)
c.finish()
