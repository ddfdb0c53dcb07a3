"""Hertz impact: an elastic sphere dropped on a rigid plane (Johnson,
Contact Mechanics, section 11.4), quarter model, at two meshes.

Sphere: R = 0.05 m, E = 1e7 Pa, nu = 0.3, rho = 1000 kg/m^3 (m = 0.524 kg),
v = 0.2 m/s, meshed here as a quarter ball (symmetry planes x = 0, y = 0)
refined towards the south pole: a graded block [0,1]^2 x [-1,1] mapped onto
the ball by p -> R p |p|_inf / |p|_2, written as an ABAQUS .inp file. The
plane is an exact analytic plane carried by a fixed rigid body; penalty
scale factor 1.0.

Closed form, E* = E / (1 - nu^2):
  delta_max = (15 m v^2 / (16 E* R^(1/2)))^(2/5) = 0.577 mm,
  F_max     = 4/3 E* R^(1/2) delta_max^(3/2) = 45.39 N,
  t_c       = 2.9432 delta_max / v = 8.49 ms.
Contact radius 5.4 mm. Tolerance 10 % at the stated mesh (12 x 12 x 24
elements), and the errors must be smaller there than at 8 x 8 x 16.
"""
import math
import os
from anvil_test import (Checker, arguments, hertz_ball_scene, read_csv, run_anvil, write_ball,
                        write_scene)

args = arguments()
c = Checker("Hertz: elastic sphere on a rigid plane")
E, nu, rho, R, v = 1e7, 0.3, 1000.0, 0.05, 0.2
m = rho * 4 / 3 * math.pi * R ** 3
Es = E / (1 - nu ** 2)
delta = (15 * m * v * v / (16 * Es * math.sqrt(R))) ** 0.4
F_max = 4 / 3 * Es * math.sqrt(R) * delta ** 1.5
t_c = 2.9432 * delta / v


def run(n):
    name = f"ball_{n}"
    write_ball(os.path.join(args.work_dir, name + ".inp"), R, n, 1.15)
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"),
                      text=hertz_ball_scene(name + ".inp", R, E, nu, rho, v)
                      + "subsection Simulation\n  set Print wall times = false\nend\n")
    code, out, err = run_anvil(args.anvil, prm, np=2, cwd=args.work_dir)
    if not c.check_true(f"{n} x {n} x {2 * n}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    d = os.path.join(args.work_dir, "output", name)
    contact = read_csv(os.path.join(d, "contact_hit.csv"))
    energy = read_csv(os.path.join(d, "energy.csv"))
    force = [4 * abs(f) for f in contact["normal_force_z"]]
    on = [t for t, f in zip(contact["time"], force) if f > 0]
    return max(force), on[-1] - on[0], max(energy["balance_error"])


results = {n: run(n) for n in (8, 12)}
for n, (peak, duration, balance) in results.items():
    print(f"  {n} x {n} x {2 * n}: peak force {peak:.2f} N ({peak / F_max - 1:+.3f}), "
          f"duration {1000 * duration:.3f} ms ({duration / t_c - 1:+.3f}), balance {balance:.2e}")
peak, duration, balance = results[12]
c.check("12 x 12 x 24: peak force [N]", peak, F_max, 0.10, relative=True)
c.check("12 x 12 x 24: contact duration [s]", duration, t_c, 0.10, relative=True)
c.check_below("12 x 12 x 24: largest energy balance error", balance, 0.01)
err = {n: (abs(r[0] / F_max - 1), abs(r[1] / t_c - 1)) for n, r in results.items()}
c.check_true("the finer mesh is closer in force and duration",
             err[12][0] < err[8][0] and err[12][1] < err[8][1])
c.finish()
