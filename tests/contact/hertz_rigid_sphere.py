"""Hertz impact: a rigid sphere on an elastic block (Johnson, Contact
Mechanics, section 11.4), quarter model, at two meshes.

Sphere: R = 0.05 m, mass 1 kg (0.25 kg in the quarter), v = 0.1 m/s, an
exact analytic sphere on a free rigid body that moves along z only. Block:
0.2 x 0.2 x 0.1 m (quarter 0.1 x 0.1 x 0.1 with symmetry planes x = 0 and
y = 0, base fixed), E = 1e7 Pa, nu = 0.3, rho = 1000 kg/m^3, meshed finer
towards the contact point (geometric grading). Penalty scale factor 1.0:
with f = 0.1 the penalty springs are softer than the Hertz contact at
these meshes (see the penalty sweep test).

Closed form, E* = E / (1 - nu^2):
  delta_max = (15 m v^2 / (16 E* R^(1/2)))^(2/5),
  F_max     = 4/3 E* R^(1/2) delta_max^(3/2) = 29.13 N,
  t_c       = 2.9432 delta_max / v = 12.63 ms.
The contact radius a = sqrt(R delta) = 4.6 mm is much smaller than the
block, and t_c is seven wave transits of the block depth: the block acts
as a half-space loaded quasi-statically. Tolerance: 10 % at the coarse mesh
(16^3, smallest element 1.8 mm), and both errors must fall at the finer
(24^3, 1.1 mm).
"""
import math
import os
from anvil_test import Checker, arguments, read_csv, run_anvil, write_scene

args = arguments()
c = Checker("Hertz: rigid sphere on an elastic half-space")
E, nu, R, m, v = 1e7, 0.3, 0.05, 1.0, 0.1
Es = E / (1 - nu ** 2)
delta = (15 * m * v * v / (16 * Es * math.sqrt(R))) ** 0.4
F_max = 4 / 3 * Es * math.sqrt(R) * delta ** 1.5
t_c = 2.9432 * delta / v


def run(n, grading):
    name = f"hertz_{n}"
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"), text=f"""
# Rigid sphere on an elastic block (Hertz), quarter model, {n}^3 elements.
set Bodies = ball, block
set Contact pairs = hit
set Boundary conditions = sym_x, sym_y, base
subsection Simulation
  set End time = 0.016
  set History interval = 2e-5
  set Print wall times = false
end
subsection Body ball
  subsection Mesh
    set Lower corner = 0, 0, 0.16
    set Upper corner = 0.01, 0.01, 0.17
  end
  subsection Material
    set Model = rigid
  end
  set Initial velocity = 0, 0, {-v}
  subsection Rigid body
    set Motion = free
    set Constraints = x, y, rx, ry, rz
    set Mass = {m / 4}
    set Contact shape = sphere
    set Shape point = 0, 0, 0.15001
    set Shape radius = {R}
  end
end
subsection Body block
  subsection Mesh
    set Lower corner = 0, 0, 0
    set Upper corner = 0.1, 0.1, 0.1
    set Subdivisions = {n}, {n}, {n}
    set Grading = {grading}, {grading}, {1 / grading}
  end
  subsection Material
    set Model = elastic
    subsection elastic
      set Density = 1000
      set Young's modulus = {E}
      set Poisson's ratio = {nu}
    end
  end
end
subsection Boundary condition sym_x
  set Body = block
  set Boundary ids = 0
  set Components = x
end
subsection Boundary condition sym_y
  set Body = block
  set Boundary ids = 2
  set Components = y
end
subsection Boundary condition base
  set Body = block
  set Boundary ids = 4
end
subsection Contact pair hit
  set First body = ball
  set Second body = block
  set Penalty scale factor = 1.0
end
""")
    code, out, err = run_anvil(args.anvil, prm, np=2, cwd=args.work_dir)
    if not c.check_true(f"{n}^3: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    d = os.path.join(args.work_dir, "output", name)
    rigid = read_csv(os.path.join(d, "rigid_ball.csv"))
    energy = read_csv(os.path.join(d, "energy.csv"))
    force = [4 * f for f in rigid["fz"]]
    on = [t for t, f in zip(rigid["time"], force) if f > 0]
    return max(force), on[-1] - on[0], max(energy["balance_error"])


errors = []
for n, grading in ((16, 1.15), (24, 1.1)):
    peak, duration, balance = run(n, grading)
    e_f = c.check(f"{n}^3: peak force [N]", peak, F_max, 0.10, relative=True)
    e_t = c.check(f"{n}^3: contact duration [s]", duration, t_c, 0.10, relative=True)
    c.check_below(f"{n}^3: largest energy balance error", balance, 0.01)
    errors.append((abs(peak / F_max - 1), abs(duration / t_c - 1)))
print(f"  errors (force, duration): 16^3 {errors[0][0]:.3f}, {errors[0][1]:.3f}; "
      f"24^3 {errors[1][0]:.3f}, {errors[1][1]:.3f}")
c.check_true("the finer mesh is closer in force and duration",
             errors[1][0] < errors[0][0] and errors[1][1] < errors[0][1])
c.finish()
