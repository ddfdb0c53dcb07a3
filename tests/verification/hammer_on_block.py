"""The hammer_on_block scene (prm/): a free rigid hammer with an analytic
spherical nose, friction and gravity on an elastic block.

Checks conservation and determinism, the only exact statements for this
scene: the energy balance (kinetic + internal + hourglass + contact +
friction = E_0 + work of gravity and of the base reaction) below 1 %; the
hammer's momentum change equals the impulse of the contact force plus its
weight (within 1e-6 of M v0, histories written every step: the rigid body
integrates exactly what the contact gives it); np = 2 against np = 1 (largest relative difference of
energy.csv below 1e-8). Shortened to 3 ms.
"""
import os
from anvil_test import (Checker, arguments, max_relative_difference, read_csv, run_anvil,
                        write_scene)

args = arguments()
c = Checker("hammer on a block: conservation and determinism")
scene = os.path.join(args.source_dir, "prm/hammer_on_block/hammer_on_block.prm")
energies = {}
for np in (2, 1):
    prm = write_scene(os.path.join(args.work_dir, f"hammer_np{np}.prm"), include=scene, text="""
subsection Simulation
  set End time = 0.003
  set Output interval = 0
  set History interval = 0
  set Print wall times = false
end
""")
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"np = {np}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    energies[np] = read_csv(os.path.join(args.work_dir, "output", f"hammer_np{np}", "energy.csv"))
d = os.path.join(args.work_dir, "output", "hammer_np2")
c.check_below("largest energy balance error", max(energies[2]["balance_error"]), 0.01)
rigid = read_csv(os.path.join(d, "rigid_hammer.csv"))
contact = read_csv(os.path.join(d, "contact_impact.csv"))
M, g, v0 = 270.0, 9.81, 2.0
t, fz = contact["time"], contact["normal_force_z"]
ffz = contact["friction_force_z"]
# Force on the hammer (the pair's first body), every step, by the
# trapezoidal rule: the central-difference impulse sum F^n (dt^- + dt^+)/2.
impulse = sum(0.5 * (fz[i] + ffz[i] + fz[i + 1] + ffz[i + 1]) * (t[i + 1] - t[i]) for i in range(len(t) - 1))
dp = M * (rigid["vz"][-1] - rigid["vz"][0])
c.check("hammer: momentum change / (contact impulse - weight impulse) [N s]", dp,
        impulse - M * g * (t[-1] - t[0]), 1e-6 * M * v0)
print(f"  peak force {max(rigid['fz']) / 1e3:.1f} kN, rebound velocity {rigid['vz'][-1]:.3f} m/s")
c.check_below("np = 2 against np = 1: largest relative difference of energy.csv",
              max_relative_difference(energies[1], energies[2]), 1e-8)
c.finish()
