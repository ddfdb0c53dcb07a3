"""The paper's hammer-mass and hammer-velocity studies on the coarse RC
column (prm/rc_column_impact/studies/*_coarse.prm, run by `anvil --study`).

Checks: every run ends (exit 0) with its energy balance closed (below 2 %
of the scale); the initial energy of each run is the hammer's 1/2 m v^2
(the study changed the entry it names); and the trend directions of the
seed's section 5.5.1-5.5.2: the peak displacement of the impact point
grows with the hammer mass and with its velocity. The sizes of the
increments are printed beside the paper's (doc/studies.md says why they
differ: the arching of the fixed ends, prm/rc_column_impact/README.md).
"""
import os
import subprocess
from anvil_test import Checker, arguments, read_csv

args = arguments()
c = Checker("column studies: hammer mass and velocity (coarse)")
studies = os.path.join(os.path.abspath(args.source_dir), "prm", "rc_column_impact", "studies")

for study, values, energy, paper in (
        ("hammer_mass_coarse", "mass_plot_value", lambda x: 0.5 * x * 2.0 ** 2, "+33 mm, then +27 mm"),
        ("hammer_velocity_coarse", "velocity_plot_value", lambda x: 0.5 * 270 * x ** 2,
         "+35.4 mm, then +97.6 mm")):
    r = subprocess.run([args.anvil, "--study", os.path.join(studies, study + ".prm"), "--jobs", "2"],
                       cwd=args.work_dir, capture_output=True, text=True)
    if not c.check_true(f"{study}: every run ends", r.returncode == 0, (r.stderr or r.stdout).strip()[-400:]):
        continue
    t = read_csv(os.path.join(args.work_dir, "output", study, "study.csv"))
    x, peak = t[values], t["peak_displacement_m"]
    for i in range(len(x)):
        c.check(f"{study} {x[i]:g}: initial energy against 1/2 m v^2", t["initial_energy_J"][i],
                energy(x[i]), 1e-9, relative=True)
        c.check_below(f"{study} {x[i]:g}: largest energy balance error", t["max_balance_error"][i], 0.02)
    order = sorted(range(len(x)), key=lambda i: x[i])
    grows = all(peak[order[k + 1]] > peak[order[k]] for k in range(len(order) - 1))
    steps = ", ".join(f"{1e3 * (peak[order[k + 1]] - peak[order[k]]):+.1f} mm" for k in range(len(order) - 1))
    c.check_true(f"{study}: peak displacement grows with the varied value",
                 grows, f"peaks {', '.join(f'{1e3 * peak[i]:.2f}' for i in order)} mm; increments {steps} "
                 f"(the paper: {paper})")
c.finish()
