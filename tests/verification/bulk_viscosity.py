"""Bulk viscosity against the jump conditions of a plane wave, on
tests/verification/bulk_viscosity.prm.

A steel plate 1 m thick (100 elements through it, lateral faces held: uniaxial
strain) moving at 10 m/s strikes a fixed wall at x = 0. A compression front
runs into the plate at the constrained wave speed c = sqrt(M / rho); behind
it the particle velocity is 0 and the stress -rho c v (the jump conditions;
elastic, so exact). The probe half way through the plate sees the front at
t = 0.5 / c and nothing else until 3 x 0.5 / c.

Without bulk viscosity the front rings (the dispersion of the discrete
mesh: a step overshoots); with ABAQUS's defaults (b_1 = 0.06, b_2 = 1.2) the
front is smeared over a few elements and the plateau holds the jump
conditions. Checked, after the front has passed (from 1.3 x arrival to the
end): mean stress and particle velocity within 2 % of the jump values,
overshoot of the stress below 5 % with viscosity, larger without; the
viscous energy booked so that the balance closes (5e-4; 9.4e-4 without
viscosity, the ringing front); np = 2 equals np = 1.
"""
import math
import os
from anvil_test import Checker, arguments, run_anvil, test_scene, read_csv

args = arguments()
c = Checker("bulk viscosity: plane wave against the jump conditions")
rho, E, nu, v = 7850.0, 2e11, 0.3, 10.0
M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
cw = math.sqrt(M / rho)
arrival = 0.5 / cw
jump_stress = -rho * cw * v
print(f"  c = {cw:.1f} m/s, front at the probe at {1e6 * arrival:.2f} us, jump: velocity 0, "
      f"stress {1e-6 * jump_stress:.2f} MPa")

results = {}
inviscid = {"Body plate/Bulk viscosity/Linear coefficient": 0, "Body plate/Bulk viscosity/Quadratic coefficient": 0}
for name, overrides, np in (("viscous", {}, 1), ("viscous_np2", {}, 2), ("inviscid", inviscid, 1)):
    prm = test_scene(args, "tests/verification/bulk_viscosity.prm", name, overrides)
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"{name} runs to its end", code == 0, err.strip()[-300:]):
        c.finish()
    d = os.path.join(args.work_dir, "output", name)
    results[name] = (read_csv(os.path.join(d, "probe_middle.csv")), read_csv(os.path.join(d, "energy.csv")))

for name in ("viscous", "inviscid"):
    probe, energy = results[name]
    after = [i for i, t in enumerate(probe["time"]) if t >= 1.3 * arrival]
    sxx = [probe["stress_xx"][i] for i in after]
    vx = [probe["vx"][i] for i in after]
    mean_s = sum(sxx) / len(sxx)
    mean_v = sum(vx) / len(vx)
    overshoot = max(s / jump_stress for s in probe["stress_xx"]) - 1
    print(f"  {name}: mean stress {1e-6 * mean_s:.2f} MPa, mean velocity {mean_v:.4f} m/s, "
          f"overshoot {100 * overshoot:.1f} %, viscous energy {energy['viscous'][-1]:.4g} J "
          f"of {energy['total'][0]:.4g} J")
    if name == "viscous":
        c.check("viscous: stress behind the front against -rho c v (relative)", mean_s, jump_stress, 0.02,
                relative=True)
        c.check("viscous: particle velocity behind the front (/ v)", mean_v / v, 0.0, 0.02)
        c.check_below("viscous: stress overshoot at the front", overshoot, 0.05)
        c.check_below("viscous: energy balance error, the viscous work booked (the front's own "
                      "discretisation error without viscosity is 9.4e-4)", max(energy["balance_error"]), 5e-4)
        c.check_true("viscous: the viscous energy is positive", energy["viscous"][-1] > 0)
    else:
        c.check_true("inviscid: the front overshoots by more than 10 % (what the viscosity removes)",
                     overshoot > 0.10, f"{100 * overshoot:.1f} %")

p1, p2 = results["viscous"][0], results["viscous_np2"][0]
diff = max(abs(a - b) for k in ("ux", "vx", "stress_xx") for a, b in zip(p1[k], p2[k]))
c.check_below("np = 2 against np = 1, probe (largest difference)", diff, 1e-9 * abs(jump_stress))
c.finish()
