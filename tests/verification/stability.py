"""Stability of the explicit step.

A block fixed on one face and thrown at (1, 0.5, 0) m/s rings for 10^4 steps
(tests/verification/stability.prm).
With the time step safety factor 0.9 the run must stay stable: it completes,
and the energy balance stays bounded (limit 5 % one-point, 10 % full
integration: the block is updated Lagrangian, whose Jaumann-rate
hypoelasticity is not hyperelastic and loses energy over 10^4 steps of
ringing: 6.5 % with full integration against 0.5 % for the same block in
total Lagrangian; an unstable run grows without bound).
The stable step min L_e / c_e is the exact limit for this mesh (factor 1.0:
the lumped-mass mesh's highest frequency is 2c/h), so a factor of 1.2 must
be detected and stopped with the one-line message naming time, step, element
and position and calling the step unstable (whether energy growth or the
inverted element it causes is seen first), exit status 3, and the last good
state on disk.

A collapsing element is stopped too: the block thrown at 30 m/s (0.3 of the
wave speed) into its fixed face, with 'Minimum time step ratio' = 0.8: its
first elements flatten, the stable step falls below 0.8 of the first one,
and the run stops with the same kind of line, naming the ratio.
"""
import os
import re
from anvil_test import Checker, arguments, run_anvil, test_scene, read_csv

args = arguments()
c = Checker("stability of the central difference step")
scene = "tests/verification/stability.prm"
for integration in ("one point", "full"):
    tag = integration.replace(" ", "_")
    prm = test_scene(args, scene, f"stable_{tag}", {"Body block/Integration": integration})
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    c.check_true(f"{integration}: factor 0.9 runs to the end", code == 0, err.strip())
    if code == 0:
        energy = read_csv(os.path.join(args.work_dir, f"output/stable_{tag}/energy.csv"))
        c.check_below(f"{integration}: number of steps >= 10^4", -len(energy["time"]), -10000)
        c.check_below(f"{integration}: largest energy balance error over the run", max(energy["balance_error"]),
                      0.05 if integration == "one point" else 0.10)

    prm = test_scene(args, scene, f"unstable_{tag}",
                     {"Body block/Integration": integration, "Simulation/Time step safety factor": 1.2})
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    lines = [l for l in err.splitlines() if l.strip()]
    c.check_true(f"{integration}: factor 1.2 stops with exit status 3", code == 3, f"exit {code}")
    message = lines[-1] if lines else ""
    print("    message:", message)
    c.check_true(f"{integration}: one error line naming time, step, element and position",
                 len([l for l in lines if l.startswith("anvil: error:")]) == 1
                 and all(k in message for k in ("numerical failure at t =", "step", "element", "near (", "unstable")))
    c.check_true(f"{integration}: last good state written",
                 os.path.exists(os.path.join(args.work_dir, f"output/unstable_{tag}/last_good.pvtu")))
    # The histories hold every step before the failure ('History interval'
    # 0: a row a step, from step 0): they are flushed before the run stops.
    failed = re.search(r"numerical failure at t = [0-9.e+-]+ s, step (\d+)", message)
    rows = read_csv(os.path.join(args.work_dir, f"output/unstable_{tag}/energy.csv"))["time"]
    c.check_true(f"{integration}: energy.csv holds a row for each step before the failing one",
                 failed is not None and len(rows) >= int(failed.group(1)),
                 f"{len(rows)} rows, failure at step {failed.group(1) if failed else '?'}")

prm = test_scene(args, scene, "collapse",
                 {"Body block/Initial velocity": "-30, 0, 0", "Simulation/Minimum time step ratio": 0.8})
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
lines = [l for l in err.splitlines() if l.strip()]
message = lines[-1] if lines else ""
print("    message:", message)
c.check_true("collapse: stops with exit status 3", code == 3, f"exit {code}")
c.check_true("collapse: one error line naming the step ratio, time, element and position",
             len([l for l in lines if l.startswith("anvil: error:")]) == 1
             and all(k in message for k in ("numerical failure at t =", "Minimum time step ratio", "element",
                                            "near (")))
c.check_true("collapse: last good state written",
             os.path.exists(os.path.join(args.work_dir, "output/collapse/last_good.pvtu")))
c.finish()
