"""The steel bar impact scene (prm/steel_bar_impact, a Taylor test with the
seed's Table 1 steel and rate effects) against conservation laws.

- Energy: kinetic + internal (elastic and plastic work) + hourglass +
  contact = the initial kinetic energy; balance error below 1 %.
- Momentum: the impulse of the contact force on the wall equals the bar's
  loss of momentum, m v0 - p_x(end), within 1e-9 of m v0 (the fixed wall's
  reaction is the only external force). The histories are written every
  step: the trapezoidal sum of the force rows is then the central
  difference's impulse (the kinematic contact's force changes from step
  to step; rows every few steps would sample it).
- Plastic deformation happened: the bar is shorter and its impact face
  wider than at the start (printed: final length, impact-face radius, peak
  effective plastic strain, the scene's results).
- np = 2 gives the same energy history as np = 1 (largest relative
  difference below 1e-8).
"""
import os
from anvil_test import (Checker, arguments, max_relative_difference, read_csv, run_anvil,
                        write_scene)

args = arguments()
c = Checker("steel bar on a rigid wall: conservation of energy and momentum")
scene = os.path.join(args.source_dir, "prm/steel_bar_impact/steel_bar_impact.prm")
energies = {}
for np in (2, 1):
    prm = write_scene(os.path.join(args.work_dir, f"bar_np{np}.prm"), include=scene, text="""
subsection Simulation
  set Output interval = 0
  set History interval = 0
  set Print wall times = false
end
""")
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"np = {np}: anvil exits 0", code == 0, err.strip()):
        c.finish()
    energies[np] = read_csv(os.path.join(args.work_dir, "output", f"bar_np{np}", "energy.csv"))

d = os.path.join(args.work_dir, "output", "bar_np2")
energy = energies[2]
c.check_below("largest energy balance error", max(energy["balance_error"]), 0.01)
momentum = read_csv(os.path.join(d, "momentum.csv"))
contact = read_csv(os.path.join(d, "contact_impact.csv"))
t, f = contact["time"], contact["normal_force_x"]
impulse = sum(0.5 * (f[i] + f[i + 1]) * (t[i + 1] - t[i]) for i in range(len(t) - 1))
p0 = momentum["bar_px"][0]
c.check("impulse on the wall / loss of bar momentum", impulse, p0 - momentum["bar_px"][-1], 1e-9 * p0)

with open(os.path.join(d, "bodies.csv")) as fh:
    rows = fh.read().splitlines()
bar = dict(zip(rows[0].split(","), rows[1].split(",")))
length = float(bar["xmax"]) - float(bar["xmin"])
radius = 0.5 * (float(bar["ymax"]) - float(bar["ymin"]))
print(f"  final length {1000 * length:.2f} mm (from 50), impact-face radius {1000 * radius:.2f} mm "
      f"(from 5), peak effective plastic strain {float(bar['peak_effective_plastic_strain']):.3f}")
c.check_true("the bar shortened", length < 0.05, f"{1000 * length:.2f} mm")
c.check_true("the impact face widened", radius > 0.005, f"{1000 * radius:.2f} mm")
c.check_below("np = 2 against np = 1: largest relative difference of energy.csv",
              max_relative_difference(energies[1], energies[2]), 1e-8)
c.finish()
