"""Failure and erosion of plastic-kinematic steel (Table 1, f_s = 0.12).

A quarter of a 100 mm steel bar (tests/material/steel_erosion.prm; 10 x 10
mm full section, symmetry planes y = 0 and z = 0) flies at 50 m/s along its axis and is held at x = 0 from
t = 0: a tensile plastic wave (rho c v = 2 GPa > sigma_0) runs from the
held end, where elements reach the failure strain and are eroded; the bar
then separates. (An initial velocity, not a pulled end: an impulsive
velocity boundary condition puts O(1) energy error in the first steps.)

Checks:
- some elements erode, and every eroded element had reached f_s (erosion.csv
  records its effective plastic strain at removal), while every element left
  has not (bodies.csv: the peak of the intact elements is below f_s):
  "exactly the elements past f_s";
- the energy balance, with the energy of the eroded elements in its own
  column, stays below 1 %, and that column equals the sum of the energies
  erosion.csv lists (to round-off);
- np = 2 erodes the same elements and gives the same energy history as
  np = 1 (largest relative difference below 1e-8).
"""
import os
from anvil_test import Checker, arguments, max_relative_difference, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("erosion of failed steel elements")
fs = 0.12
results = {}
for np in (1, 2):
    name = f"erosion_np{np}"
    prm = test_scene(args, "tests/material/steel_erosion.prm", name)
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    print(out[-600:])
    if not c.check_true(f"np = {np}: anvil exits 0", code == 0, err.strip()):
        c.finish()
    d = os.path.join(args.work_dir, "output", name)
    results[np] = (read_csv(os.path.join(d, "energy.csv")), os.path.join(d, "erosion.csv"),
                   os.path.join(d, "bodies.csv"))

energy, erosion_file, bodies_file = results[1]
if not c.check_true("erosion.csv written", os.path.exists(erosion_file)):
    c.finish()
erosion = read_csv(erosion_file) if os.path.getsize(erosion_file) > 0 else {}
n = len(erosion.get("element", []))
c.check_true("elements eroded", n > 0, f"{n} elements")
c.check_below("f_s - smallest effective plastic strain of an eroded element", fs - min(erosion["effective_plastic_strain"]), 0.0)
with open(bodies_file) as f:
    rows = f.read().splitlines()
fields = dict(zip(rows[0].split(","), rows[1].split(",")))
c.check_below("peak effective plastic strain of the intact elements - f_s",
              float(fields["peak_effective_plastic_strain_intact"]) - fs, -1e-12)
c.check("eroded count in bodies.csv", float(fields["eroded"]), n, 0)
c.check("eroded energy column / sum over erosion.csv", energy["eroded"][-1], sum(erosion["energy"]), 1e-9, relative=True)
c.check_below("largest energy balance error (with eroded energy)", max(energy["balance_error"]), 0.01)

e2 = results[2][0]
c.check_below("np = 2 against np = 1: largest relative difference of energy.csv",
              max_relative_difference(energy, e2), 1e-8)
erosion2 = read_csv(results[2][1])
c.check_true("np = 2 erodes the same elements", sorted(erosion2["element"]) == sorted(erosion["element"]),
             f"{len(erosion2['element'])} against {n}")
c.finish()
