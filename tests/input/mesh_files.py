"""Meshes from files (ABAQUS .inp and Gmsh .msh, with 'Scale' from mm to m)
and the built-in cylinder, checked by a conservation law: a free body
thrown at v0 carries momentum rho V v0 exactly, with V the volume of the
geometry (a 2 x 1 x 1 m block from the files; the cylinder's regular
n-gon section times its length, for section and global refinements).
Also exercises a box-selected boundary condition (exit status and its
constrained momentum)."""
import math
import os
from anvil_test import Checker, arguments, run_anvil, write_scene, read_csv

args = arguments()
c = Checker("mesh files, cylinder generator, box-selected boundary condition")

# Nodes of a 2 x 1 x 1 block (in mm), two hexahedra, corner ordering of
# ABAQUS C3D8 and Gmsh hexahedra (bottom face counter-clockwise, then top).
nodes = []
for z in (0, 1000):
    for y in (0, 1000):
        for x in (0, 1000, 2000):
            nodes.append((x, y, z))
def nid(i, j, k):
    return 1 + i + 3 * j + 6 * k
hexes = [[nid(i, 0, 0), nid(i + 1, 0, 0), nid(i + 1, 1, 0), nid(i, 1, 0),
          nid(i, 0, 1), nid(i + 1, 0, 1), nid(i + 1, 1, 1), nid(i, 1, 1)] for i in (0, 1)]

inp = os.path.join(args.work_dir, "block.inp")
with open(inp, "w") as f:
    f.write("*Heading\n*Node\n")
    for k, p in enumerate(nodes):
        f.write(f"{k + 1}, {p[0]}, {p[1]}, {p[2]}\n")
    f.write("*Element, type=C3D8R\n")
    for k, h in enumerate(hexes):
        f.write(f"{k + 1}, " + ", ".join(map(str, h)) + "\n")
msh = os.path.join(args.work_dir, "block.msh")
with open(msh, "w") as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
    for k, p in enumerate(nodes):
        f.write(f"{k + 1} {p[0]} {p[1]} {p[2]}\n")
    f.write("$EndNodes\n$Elements\n%d\n" % len(hexes))
    for k, h in enumerate(hexes):
        f.write(f"{k + 1} 5 2 0 1 " + " ".join(map(str, h)) + "\n")
    f.write("$EndElements\n")

rho, v0 = 7850.0, 3.0
def scene(mesh, extra=""):
    return f"""
set Bodies = b
subsection Simulation
  set End time = 1e-4
  set Print wall times = false
end
subsection Body b
  subsection Mesh
{mesh}
  end
  subsection Material
    subsection elastic
      set Density = {rho}
    end
  end
  set Initial velocity = {v0}, 0, 0
end
{extra}
"""

for name, mesh in (("inp", f"    set Source = file\n    set File name = block.inp\n    set Scale = 0.001"),
                   ("msh", f"    set Source = file\n    set File name = block.msh\n    set Scale = 0.001")):
    prm = write_scene(os.path.join(args.work_dir, f"file_{name}.prm"), text=scene(mesh))
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    if c.check_true(f".{name}: runs", code == 0, err.strip()):
        p = read_csv(os.path.join(args.work_dir, f"output/file_{name}/momentum.csv"))
        c.check(f".{name}: momentum rho V v0 of the 2 m^3 block [kg m/s]", p["px"][-1], rho * 2.0 * v0, 1e-12, relative=True)

# The cylinder: its hull's corners lie on the circle and its faces are
# planar, so the section is a regular n-gon, n = 4 x 2^(section + global
# refinements), of area n/2 r^2 sin(2 pi / n): the momentum is rho A_n L v0
# to round-off, and the log names n and the area's shortfall.
r, length = 0.1, 0.5
for section, refinements in ((0, 2), (2, 0), (1, 1), (2, 1)):
    n = 4 * 2 ** (section + refinements)
    mesh = (f"    set Source = cylinder\n    set Radius = {r}\n    set Length = {length}\n"
            f"    set Section refinements = {section}\n    set Global refinements = {refinements}")
    run = f"cylinder_s{section}_g{refinements}"
    prm = write_scene(os.path.join(args.work_dir, run + ".prm"), text=scene(mesh))
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    if c.check_true(f"cylinder, {section} section and {refinements} global refinements: runs",
                    code == 0, err.strip()):
        p = read_csv(os.path.join(args.work_dir, f"output/{run}/momentum.csv"))
        area = 0.5 * n * r * r * math.sin(2 * math.pi / n)
        c.check(f"  {n}-gon: momentum against rho A_n L v0 [kg m/s]", p["px"][-1],
                rho * area * length * v0, 1e-12, relative=True)
        shortfall = 100 * (1 - area / (math.pi * r * r))
        c.check_true(f"  the log names the {n}-gon and its {shortfall:.4g} % shortfall",
                     f"a {n}-gon" in out and f"{shortfall:.4g} %" in out,
                     next((l for l in out.splitlines() if "cylinder section" in l), "no such line"))

# Box selection: hold the x-velocity of the nodes on the block's x = 0 face
# (a box around it). Of a 2 x 2 x 2 mesh, the x = 0 face carries a quarter
# of the lumped mass, so the initial x-momentum is 3/4 of rho V v0.
mesh = "    set Upper corner = 1, 1, 1\n    set Subdivisions = 2, 2, 2"
extra = """set Boundary conditions = hold
subsection Boundary condition hold
  set Body = b
  set Selection = box
  set Box lower corner = -0.1, -0.1, -0.1
  set Box upper corner = 0.1, 1.1, 1.1
  set Components = x
end"""
prm = write_scene(os.path.join(args.work_dir, "box_bc.prm"), text=scene(mesh, extra))
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if c.check_true("box-selected condition: runs", code == 0, err.strip()):
    p = read_csv(os.path.join(args.work_dir, "output/box_bc/momentum.csv"))
    c.check("box-selected condition: initial momentum of the free nodes [kg m/s]", p["px"][0], rho * 0.75 * v0, 1e-9, relative=True)
c.finish()
