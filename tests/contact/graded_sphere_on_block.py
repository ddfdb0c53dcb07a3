"""A graded elastic sphere on a graded elastic block: the time step follows
the contact springs that act, and the force stays Hertz's.

The scene is tests/contact/graded_sphere_on_block.prm. Sphere: the quarter
ball of hertz_elastic_sphere (R = 0.05 m, E = 1e7 Pa,
nu = 0.3, rho = 1000 kg/m^3, 12 x 12 x 24 elements graded towards its south
pole, 1.7 mm there) at v = 0.2 m/s. Block: the same material, a quarter
block 0.1 x 0.1 x 0.1 m below the pole, 13 elements a side graded from
1.7 mm under the pole by 1.25 per element, its bottom fixed; symmetry
planes x = 0 and y = 0 for both. Symmetric penalty contact at factor 1.0,
and kinematic contact with its two passes balanced.

The graded block has stiff far-field faces: the faces of its large, thin
elements far from the contact (K A^2 / V grows with A / h) are up to ~30
times stiffer than those under the pole, and the ball's lightest nodes are
on its axis. A stable step that paired the stiffest segment anywhere with
the lightest slave node anywhere (printed: the steps that would take,
computed here from the meshes) costs several times the steps the springs in
contact need.

Hertz (two equal elastic bodies), 1/E* = 2 (1 - nu^2) / E:
  delta_max = (15 m v^2 / (16 E* R^(1/2)))^(2/5), F_max = 4/3 E* R^(1/2)
  delta_max^(3/2), t_c = 2.9432 delta_max / v.
The block is finite (0.1 m, 16 contact radii deep), which adds a compliance
of about 1.5 % of delta (F (1 - nu^2) / (pi E D) over delta).

Checks: peak force and contact duration within 5 % of Hertz; energy
balance below 1 %; the run takes at most half the steps of the worst
pairing (printed: steps taken, steps the elements alone need, steps of the
worst pairing). Kinematic:
peak force and duration within 4 % of Hertz (the ball's own waves stiffen
the impact by about 3 % at this speed: hertz_elastic_sphere), the force
smooth (no row-to-row change above 5 % of the peak), energy balance 1 %.
"""
import math
import os
from anvil_test import (Checker, arguments, ball_nodes, graded, lumped_masses, read_csv, run_anvil,
                        test_scene)

args = arguments()
c = Checker("graded sphere on a graded block: Hertz, and the steps the springs need")
E, nu, rho, R, v, f = 1e7, 0.3, 1000.0, 0.05, 0.2, 1.0
K = E / (3 * (1 - 2 * nu))
m_ball = rho * 4 / 3 * math.pi * R ** 3
Es = E / (2 * (1 - nu ** 2))
delta = (15 * m_ball * v * v / (16 * Es * math.sqrt(R))) ** 0.4
F_max = 4 / 3 * Es * math.sqrt(R) * delta ** 1.5
t_c = 2.9432 * delta / v

# The meshes of tests/contact/graded_sphere_on_block.prm, node by node, for
# the bound of the worst pairing below.
ball, ball_shape = ball_nodes(R, 12, 1.15)
n, size = 13, 0.1
s = [size * x for x in graded(n, 1.25)]
gap = 1e-5
block = [(x, y, -R - gap - z) for z in s for y in s for x in s]
block_shape = (n, n, n)


def segments(nodes, shape, selector):
    """Boundary faces (4 node indices) of a structured mesh on the faces
    that 'selector' keeps: (axis, side) pairs, side 0 or 1."""
    nx, ny, nz = shape
    node = lambda i, j, k: i + (nx + 1) * (j + (ny + 1) * k)
    faces = []
    for axis, side in selector:
        dims = [nx, ny, nz]
        a, b = [d for d in range(3) if d != axis]
        for p in range(dims[a]):
            for q in range(dims[b]):
                ijk = [0, 0, 0]
                ijk[axis] = side * dims[axis]
                quad = []
                for dp, dq in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    ijk[a], ijk[b] = p + dp, q + dq
                    quad.append(node(*ijk))
                # The element behind the face: its thickness along the axis.
                ijk2 = list(ijk)
                ijk2[axis] = side * dims[axis] + (-1 if side else 1)
                ijk2[a], ijk2[b] = p, q
                faces.append((quad, node(*ijk2)))
    return faces


def stiffest_segment(nodes, faces):
    """max f K A^2 / V over the faces (A: the quad's area, V ~ A h with h
    the distance to the opposite face's node)."""
    best = 0.0
    for quad, behind in faces:
        p = [nodes[i] for i in quad]
        d1 = [p[2][k] - p[0][k] for k in range(3)]
        d2 = [p[3][k] - p[1][k] for k in range(3)]
        cr = [d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0]]
        A = 0.5 * math.sqrt(sum(x * x for x in cr))
        nrm = [x / (2 * A) for x in cr]
        h = abs(sum((nodes[behind][k] - p[0][k]) * nrm[k] for k in range(3)))
        best = max(best, f * K * A * A / (A * h))
    return best


# Every boundary face except those on the symmetry planes x = 0, y = 0:
# the old bound took the surface as the scene defines it (the whole body).
ball_faces = segments(ball, ball_shape, [(0, 1), (1, 1), (2, 0), (2, 1)])
block_faces = segments(block, block_shape, [(0, 1), (1, 1), (2, 0), (2, 1)])
m_ball_nodes = lumped_masses(ball, ball_shape, rho)
m_block_nodes = lumped_masses(block, block_shape, rho)
w2_old = max(4 * stiffest_segment(block, block_faces) / min(m_ball_nodes),
             4 * stiffest_segment(ball, ball_faces) / min(m_block_nodes))


def run(np, algorithm="penalty"):
    name = f"sphere_block_np{np}" + ("" if algorithm == "penalty" else "_" + algorithm)
    contact = ({"Contact pair hit/Algorithm": "penalty", "Contact pair hit/Penalty scale factor": f}
               if algorithm == "penalty" else {})
    prm = test_scene(args, "tests/contact/graded_sphere_on_block.prm", name, contact)
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"np = {np}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    d = os.path.join(args.work_dir, "output", name)
    summary = read_csv(os.path.join(d, "summary.csv"))
    return (read_csv(os.path.join(d, "contact_hit.csv")), read_csv(os.path.join(d, "energy.csv")),
            dict(zip(summary["quantity"], summary["value"])))


contact, energy, summary = run(1)
force = [-4 * fz for fz in contact["normal_force_z"]]  # on the ball, +z
on = [t for t, fz in zip(contact["time"], force) if fz > 0]
peak, duration = max(force), on[-1] - on[0]
print(f"  Hertz: F_max {F_max:.2f} N, t_c {1000 * t_c:.3f} ms; Anvil: {peak:.2f} N ({peak / F_max - 1:+.3f}),"
      f" {1000 * duration:.3f} ms ({duration / t_c - 1:+.3f})")
c.check("peak contact force [N]", peak, F_max, 0.05, relative=True)
c.check("contact duration [s]", duration, t_c, 0.05, relative=True)
c.check_below("largest energy balance error", max(energy["balance_error"]), 0.01)

steps, element_steps = summary["steps"], summary["steps_elements_only"]
# The elements' mean critical step over the run (safety factor 0.9 by
# default): the worst pairing would have cut every step by
# 1 / sqrt(1 + w^2 dt_e^2 / 4).
dt_e = 0.014 / element_steps / 0.9
worst = element_steps * math.sqrt(1 + 0.25 * w2_old * dt_e * dt_e)
print(f"  steps taken {steps:.0f} ({summary['contact_limited_steps']:.0f} of them set by the contact "
      f"springs); the elements alone need {element_steps:.0f}; the worst pairing (stiffest segment "
      f"with the lightest node) would take {worst:.0f}")
c.check_below("steps taken / steps of the worst pairing", steps / worst, 0.5)
c.check_true("the springs in contact set some steps (the bound is live)",
             summary["contact_limited_steps"] > 0)

# (np = 2 against np = 1 for a penalty pair between two meshes:
# distributed_pair, at 2, 3 and 4 processes; for a kinematic pair:
# kinematic_contact.)

# Kinematic contact between the two deformable bodies, whose meshes do not
# match: the two passes balanced (each corrects the predicted motion alone,
# the step takes the mean). Both passes' constraints enforced at once
# over-constrain the interface: force spikes of 45 % of Hertz's peak
# between history rows at this speed, and a stop at 0.4 m/s.
contact, energy, summary = run(1, "kinematic")
force = [-4 * fz for fz in contact["normal_force_z"]]
on = [t for t, fz in zip(contact["time"], force) if fz > 0]
peak, duration = max(force), on[-1] - on[0]
jump = max(abs(a - b) for a, b in zip(force[1:], force[:-1]))
print(f"  kinematic: {peak:.2f} N ({peak / F_max - 1:+.3f}), {1000 * duration:.3f} ms ({duration / t_c - 1:+.3f}),"
      f" largest change between rows {jump / F_max:.3f} F_max, deepest penetration "
      f"{max(contact['max_penetration_ratio']):.2g} of the element")
c.check("kinematic: peak contact force [N]", peak, F_max, 0.04, relative=True)
c.check("kinematic: contact duration [s]", duration, t_c, 0.04, relative=True)
c.check_below("kinematic: largest change of the force between history rows / Hertz's peak (smooth, no "
              "locking)", jump / F_max, 0.05)
c.check_below("kinematic: largest energy balance error", max(energy["balance_error"]), 0.01)
c.finish()
