"""A probe averaged over a section ('Average = section'): the motion of the
centre of mass of a body's cross-section, on the two colliding rods of
prm/elastic_rod_impact (rod B's mesh graded across, Grading 1.6 along y, so
that the section's nodes carry unequal masses).

- Definition, checked independently: at every VTU frame the probe equals
  the mean of the frame's displacements over the nodes of the plane x = 5,
  weighted by the lumped masses this script computes from the grid (a
  rectangular hexahedron gives each of its nodes rho V / 8: a node's mass
  is rho times the product of its half-cell widths), to 1e-10 of the
  largest displacement (the histories' 12 digits).
- Physics: the velocity of rod B's centre section against one-dimensional
  bar theory (d'Alembert, seed section 6.2): 0 until the wave arrives at
  L/2c, v0/2 until its reflection from the free end returns at 3L/2c, then
  v0: its mean between the fronts (0.02 s from them) within 2 % of v0 (the
  3D rods' lateral inertia rings about it, as about rod_impact's force). A corner node of the
  same section is printed beside it.
- The summary's peak of the probe is its history's largest |u|; np = 2
  writes the probe's history of np = 1 bit for bit (the section's nodes
  are summed in the order of their scene index on any partition).
"""
import math
import os
import numpy as np
from anvil_test import Checker, arguments, run_anvil, write_scene, read_csv

from anvil_vtu import read_grid, arrays

args = arguments()
c = Checker("section probe: the centre of mass of a section")
scene = os.path.join(args.source_dir, "prm/elastic_rod_impact/elastic_rod_impact.prm")
grading = 1.6
text = f"""
set Probes = face_a, face_b, centre_a, centre_b, centre_b_section, corner_b
subsection Simulation
  set Summary probe    = centre_b_section
  set Output interval  = 0.05
  set Print wall times = false
end
subsection Body rod_b
  subsection Mesh
    set Grading = 1, {grading}, 1
  end
end
subsection Probe centre_b_section
  set Body           = rod_b
  set Point          = 5, 0.5, 0.5
  set Average        = section
  set Section normal = x
end
subsection Probe corner_b
  set Body  = rod_b
  set Point = 5, 0.5, 0.5
end
"""
out_dirs = {}
for np_ in (1, 2):
    work = os.path.join(args.work_dir, f"np{np_}")
    os.makedirs(work, exist_ok=True)
    prm = write_scene(os.path.join(work, "rods.prm"), include=scene, text=text)
    code, out, err = run_anvil(args.anvil, prm, np=np_, cwd=work)
    if not c.check_true(f"np = {np_} exits 0", code == 0, err.strip()[-400:]):
        c.finish()
    out_dirs[np_] = os.path.join(work, "output/rods")
d = out_dirs[1]
probe = read_csv(os.path.join(d, "probe_centre_b_section.csv"))
corner = read_csv(os.path.join(d, "probe_corner_b.csv"))

# The lumped mass of a node of rod B's graded grid, up to the constant
# factors that cancel in the mean: the product of its half-cell widths
# along y and z (along x every node of the plane has the same).
def half_widths(lower, upper, n, r):
    sizes = [r ** i for i in range(n)]
    h = [(upper - lower) * s / sum(sizes) for s in sizes]
    nodes = [lower + sum(h[:i]) for i in range(n + 1)]
    width = [0.5 * ((h[i - 1] if i > 0 else 0) + (h[i] if i < n else 0)) for i in range(n + 1)]
    return nodes, width


ys, wy = half_widths(-0.5, 0.5, 4, grading)
zs, wz = half_widths(-0.5, 0.5, 4, 1.0)
print(f"  rod B's section: nodes at y = {', '.join(f'{y:.4f}' for y in ys)}; "
      f"mass weights from {min(wy) * min(wz):.4f} to {max(wy) * max(wz):.4f}")

scale = max(abs(u) for u in probe["ux"])
worst, frames = 0.0, 0
for f in sorted(x for x in os.listdir(d) if x.endswith(".pvtu")):
    grid = read_grid(os.path.join(d, f))
    t = float(arrays(grid.GetFieldData())["TIME"][0])
    u = arrays(grid.GetPointData())["displacement"]
    xyz = np.array([grid.GetPoint(i) for i in range(grid.GetNumberOfPoints())])
    total, mean, seen = 0.0, np.zeros(3), set()
    for p, ui in zip(xyz, u):
        if abs(p[0] - 5.0) > 1e-9 or (round(p[1], 9), round(p[2], 9)) in seen:
            continue
        seen.add((round(p[1], 9), round(p[2], 9)))
        j = min(range(5), key=lambda k: abs(ys[k] - p[1]))
        k = min(range(5), key=lambda k: abs(zs[k] - p[2]))
        total += wy[j] * wz[k]
        mean += wy[j] * wz[k] * ui
    mean /= total
    row = min(range(len(probe["time"])), key=lambda i: abs(probe["time"][i] - t))
    if abs(probe["time"][row] - t) > 1e-9 or len(seen) != 25:
        continue
    frames += 1
    worst = max(worst, max(abs(probe[k][row] - mean[i]) for i, k in enumerate(("ux", "uy", "uz"))))
c.check_true(f"frames compared ({frames}), each with the plane's 25 nodes", frames >= 6)
c.check_below("probe against the mass-weighted mean of the frames' displacements / largest |u|",
              worst / scale, 1e-10)


# Bar theory at the centre of rod B (rod_impact's rods: c = 100 m/s, L = 10 m):
# the particle velocity is 0 until the compressive wave arrives at L/2c,
# v0/2 behind it, v0 once its reflection from the free end has passed at
# 3L/2c. (The displacement lags bar theory's by the penalty springs' own
# compression, rod_impact's note, so the velocity is compared.)
def bar_velocity(t, v0=1.0, c0=100.0, length=10.0):
    return 0.0 if t < 0.5 * length / c0 else 0.5 * v0 if t < 1.5 * length / c0 else v0


for lo, hi in ((0.07, 0.13), (0.17, 0.3)):
    rows = [i for i, t in enumerate(probe["time"]) if lo <= t <= hi]
    mean = sum(probe["vx"][i] for i in rows) / len(rows)
    mean_corner = sum(corner["vx"][i] for i in rows) / len(rows)
    exact = bar_velocity(0.5 * (lo + hi))
    print(f"  t in [{lo}, {hi}] s: mean velocity of the section {mean:.5f} m/s, of its corner node "
          f"{mean_corner:.5f} m/s, bar theory {exact} m/s; the section's largest deviation "
          f"{max(abs(probe['vx'][i] - exact) for i in rows):.4f} m/s")
    c.check(f"centre section's mean velocity over [{lo}, {hi}] s against bar theory (m/s)", mean, exact, 0.02)

summary = read_csv(os.path.join(d, "summary.csv"))
s = dict(zip(summary["quantity"], summary["value"]))
peak = max(math.sqrt(x * x + y * y + z * z) for x, y, z in zip(probe["ux"], probe["uy"], probe["uz"]))
c.check("summary's peak of the section probe against its history (m)", s["peak_displacement_m"], peak, 1e-9)
same = open(os.path.join(d, "probe_centre_b_section.csv")).read() == \
    open(os.path.join(out_dirs[2], "probe_centre_b_section.csv")).read()
c.check_true("np = 2 writes the section probe's history of np = 1 (bitwise)", same)
c.finish()
