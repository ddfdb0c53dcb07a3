"""A quarter model and the full model of the same impact give the same
contact: the penalty of each slave node follows its tributary area.

The scenes are tests/contact/rod_pair.prm and quarter_rod.prm, after
prm/elastic_rod_impact (two elastic rods, 1 m x 1 m, 10 m long,
rod A at 1 m/s into rod B at rest; bar theory: 0.5 N for 0.2 s). The quarter
model keeps y, z in [0, 0.5] with 2 x 2 elements across (the full model has
4 x 4 over [-0.5, 0.5]) and symmetry conditions u_y = 0 on y = 0 and u_z = 0
on z = 0. Its nodes on the symmetry planes carry half (on the axis, a
quarter) of an interior node's area; with a penalty per node that ignored
this, those nodes were as stiff as interior ones and the quarter model's
contact lasted longer than the full model's (+3.5 % against +4.3 % in a rod
case where both should agree).

Checks (both models with the scene's penalty factor 0.1, and at 1.0):
- 4 x the quarter model's plateau force equals the full model's within
  0.5 %; the contact durations (time with force above half the plateau)
  agree within 0.5 %.
- The largest force of the whole history agrees within 0.5 % (the onset
  where the penalty springs matter most).
- np = 2 gives the quarter model's force history of np = 1 (relative
  difference below 1e-8).
"""
import os
from anvil_test import Checker, arguments, max_relative_difference, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("quarter and full rod models: equal contact force and duration")


def run(name, scene, factor, np=1):
    prm = test_scene(args, "tests/contact/" + scene, name, {"Contact pair impact/Penalty scale factor": factor})
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"{name}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    contact = read_csv(os.path.join(args.work_dir, "output", name, "contact_impact.csv"))
    return contact


def figures(contact, scale):
    t = contact["time"]
    force = [-scale * f for f in contact["normal_force_x"]]
    plateau = [f for ti, f in zip(t, force) if 0.03 <= ti <= 0.17]
    mean = sum(plateau) / len(plateau)
    above = [ti for ti, f in zip(t, force) if f >= 0.25]
    return mean, above[-1] - above[0], max(force)


for factor in (0.1, 1.0):
    full = figures(run(f"full_{factor}", "rod_pair.prm", factor), 1.0)
    quarter_contact = run(f"quarter_{factor}", "quarter_rod.prm", factor)
    quarter = figures(quarter_contact, 4.0)
    print(f"  f = {factor}: full model plateau {full[0]:.5f} N, duration {full[1]:.5f} s, "
          f"peak {full[2]:.5f} N; quarter x 4: {quarter[0]:.5f} N, {quarter[1]:.5f} s, "
          f"{quarter[2]:.5f} N")
    c.check(f"f = {factor}: 4 x quarter plateau force / full [N]", quarter[0], full[0], 0.005,
            relative=True)
    c.check(f"f = {factor}: quarter contact duration / full [s]", quarter[1], full[1], 0.005,
            relative=True)
    c.check(f"f = {factor}: 4 x quarter peak force / full [N]", quarter[2], full[2], 0.005,
            relative=True)
    if factor == 0.1:
        parallel = run("quarter_np2", "quarter_rod.prm", factor, np=2)
        c.check_below("quarter model, np = 2 against np = 1: largest relative difference",
                      max_relative_difference(quarter_contact, parallel), 1e-8)
c.finish()
