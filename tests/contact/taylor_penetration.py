"""Penalty contact under large deformation: the Taylor bar of
prm/steel_bar_impact (Table 1 steel, 250 m/s, 1 mm elements along the axis)
at the default penalty factor 0.1 against the same run at 1.0.

The impact face spreads to several times its area. With the penalty
stiffness of seed Eq. (59) from the reference face, each face node then
carried several times the load on the same spring and the face sank about
1.3 elements into the wall, which lengthened the bar and widened its foot
by 1-5 %. With k from the current area (and per node from its tributary
area) the penetration under a contact pressure p is l / h = p / (f K) of
the element's current thickness h.

Checks:
- final length and foot radius (the bar's extent, bodies.csv) at f = 0.1
  within 1 % of the run at f = 1.0;
- the deepest penetration at f = 0.1, over the whole history, below 10 % of
  the smallest contact element size (the axial element length, 1 mm);
- once the elastic transient of the first microsecond is over (from
  t = 2 us), the deepest penetration below 10 % of the current thickness of
  the element it presses into (max_penetration_ratio); during the first
  microsecond the face meets the wall at full speed and the ratio is that of
  the elastic impact pressure rho c v over f K (printed);
- energy balance below 1 % at both factors.
"""
import os
from anvil_test import Checker, arguments, read_csv, run_anvil, write_scene

args = arguments()
c = Checker("Taylor bar on a rigid wall: penetration and result at the default penalty factor")
scene = os.path.join(args.source_dir, "prm/steel_bar_impact/steel_bar_impact.prm")
element_length = 0.05 / 25 / 2


def run(factor):
    name = f"taylor_f{factor}"
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"), include=scene, text=f"""
subsection Simulation
  set Output interval = 0
  set Print wall times = false
end
subsection Contact pair impact
  set Penalty scale factor = {factor}
end
""")
    code, out, err = run_anvil(args.anvil, prm, np=2, cwd=args.work_dir)
    if not c.check_true(f"f = {factor}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    d = os.path.join(args.work_dir, "output", name)
    bodies = read_csv(os.path.join(d, "bodies.csv"))
    i = bodies["body"].index("bar")
    length = bodies["xmax"][i] - bodies["xmin"][i]
    radius = 0.5 * (bodies["ymax"][i] - bodies["ymin"][i])
    return (length, radius, read_csv(os.path.join(d, "contact_impact.csv")),
            max(read_csv(os.path.join(d, "energy.csv"))["balance_error"]))


soft = run(0.1)
stiff = run(1.0)
for factor, (length, radius, contact, balance) in ((0.1, soft), (1.0, stiff)):
    print(f"  f = {factor}: final length {1000 * length:.3f} mm, foot radius {1000 * radius:.3f} mm, "
          f"deepest penetration {1000 * max(contact['max_penetration']):.4f} mm, largest ratio to the "
          f"current thickness {max(contact['max_penetration_ratio']):.3f}, balance {balance:.2e}")
c.check("final length at f = 0.1 / at f = 1 [m]", soft[0], stiff[0], 0.01, relative=True)
c.check("foot radius at f = 0.1 / at f = 1 [m]", soft[1], stiff[1], 0.01, relative=True)
contact = soft[2]
c.check_below("f = 0.1: deepest penetration / smallest contact element size (1 mm)",
              max(contact["max_penetration"]) / element_length, 0.10)
late = [r for t, r in zip(contact["time"], contact["max_penetration_ratio"]) if t >= 2e-6]
early = [r for t, r in zip(contact["time"], contact["max_penetration_ratio"]) if t < 2e-6]
print(f"  f = 0.1: largest ratio to the current thickness in the first 2 us {max(early):.3f}, "
      f"after {max(late):.3f}")
c.check_below("f = 0.1, t >= 2 us: deepest penetration / current element thickness", max(late), 0.10)
c.check_below("f = 0.1: largest energy balance error", soft[3], 0.01)
c.check_below("f = 1.0: largest energy balance error", stiff[3], 0.01)
c.finish()
