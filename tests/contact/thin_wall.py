"""A wall one element thick, struck hard: the contact search keeps the face
a node has penetrated.

The scene is tests/contact/thin_wall.prm: an elastic steel block (20 x 10 x
10 mm, 2 mm elements) strikes at 500 m/s a steel layer 2 mm thick, meshed with one element through its thickness
(2 mm elements across, nodes in line with the block's), whose back face is
fixed. At the default penalty factor 0.1 the contact pressure of such a
strike (about rho c v / 2 = 12 GPa) presses the block's nodes more than half
the layer's thickness into it (l / h = p / (f K)). Past the middle of the
layer a node's nearest wall node is on the back face, whose faces point
away from the block: a search that tried only the faces around the nearest
node lost the node there, it went on through the wall and the energy
balance broke. Now the face that held a node last step, and the other faces
of the elements around its nearest node, stay candidates.

Checks:
- the strike reaches the failure mode: the deepest penetration exceeds half
  the layer's current thickness (printed);
- no node passes through: at every history row, the front-face probes of
  the block (its centre node and a corner node) stay in front of the
  layer's fixed back face, and at the end the whole block is in front of
  the layer's front face;
- the block rebounds: an elastic block against a fixed, stiff layer leaves
  with nearly its impact speed (a rigid wall: exactly), within 10 %;
- energy balance error below 1 %;
- np = 2 equals np = 1 (energy.csv, relative difference below 1e-8).
"""
import os
from anvil_test import Checker, arguments, max_relative_difference, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("thin meshed wall struck at 500 m/s: no node passes through")
v0, length = 500.0, 0.02
back = 0.002  # the layer spans x in [0, 2 mm]; the block's front face is at x = 0
energies = {}
for np in (1, 2):
    prm = test_scene(args, "tests/contact/thin_wall.prm", f"wall_np{np}")
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"np = {np}: anvil exits 0", code == 0, err.strip()[-400:]):
        c.finish()
    energies[np] = read_csv(os.path.join(args.work_dir, "output", f"wall_np{np}", "energy.csv"))

d = os.path.join(args.work_dir, "output", "wall_np1")
contact = read_csv(os.path.join(d, "contact_strike.csv"))
ratio = max(contact["max_penetration_ratio"])
print(f"  deepest penetration {1000 * max(contact['max_penetration']):.3f} mm, "
      f"{ratio:.2f} of the current element thickness")
c.check_true("the strike presses nodes past the middle of the layer (ratio > 0.5)", ratio > 0.5,
             f"{ratio:.3f}")
deepest = -1e300
for probe, x0 in (("front_centre", 0.0), ("front_corner", 0.0)):
    p = read_csv(os.path.join(d, f"probe_{probe}.csv"))
    deepest = max(deepest, max(x0 + u for u in p["ux"]))
c.check_below("front probes of the block: largest x over the history / back face x", deepest / back,
              1.0)
bodies = read_csv(os.path.join(d, "bodies.csv"))
bounds = {name: {k: bodies[k][i] for k in bodies} for i, name in enumerate(bodies["body"])}
c.check_true("at the end the block is in front of the layer",
             bounds["block"]["xmax"] < bounds["wall"]["xmin"],
             f"block xmax {bounds['block']['xmax']}, wall xmin {bounds['wall']['xmin']}")
momentum = read_csv(os.path.join(d, "momentum.csv"))
mass = 7850 * length * 0.01 * 0.01
c.check("rebound velocity of the block [m/s]", momentum["block_px"][-1] / mass, -v0, 0.10,
        relative=True)
c.check_below("largest energy balance error", max(energies[1]["balance_error"]), 0.01)
c.check_below("np = 2 against np = 1: largest relative difference of energy.csv",
              max_relative_difference(energies[1], energies[2]), 1e-8)
c.finish()
