"""Meshes from files (ABAQUS .inp and Gmsh .msh, with 'Scale' from mm to m)
and the built-in cylinder, checked by a conservation law: a free body
thrown at v0 carries momentum rho V v0 exactly, with V the volume of the
geometry (a 2 x 1 x 1 m block from the files; the cylinder's volume
converges to pi r^2 L as the refined hull approaches the circle).
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

r, length = 0.1, 0.5
errors = []
for refinements in (2, 3):
    mesh = f"    set Source = cylinder\n    set Radius = {r}\n    set Length = {length}\n    set Global refinements = {refinements}"
    prm = write_scene(os.path.join(args.work_dir, f"cylinder{refinements}.prm"), text=scene(mesh))
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    if c.check_true(f"cylinder, {refinements} refinements: runs", code == 0, err.strip()):
        p = read_csv(os.path.join(args.work_dir, f"output/cylinder{refinements}/momentum.csv"))
        exact = rho * math.pi * r * r * length * v0
        errors.append(abs(p["px"][-1] - exact) / exact)
        c.check(f"cylinder, {refinements} refinements: momentum against rho pi r^2 L v0 [kg m/s]",
                p["px"][-1], exact, 0.03 if refinements == 2 else 0.008, relative=True)
if len(errors) == 2:
    # The faceted hull converges at second order: halving h quarters the error.
    c.check("cylinder: error ratio between 2 and 3 refinements (second order: 4)", errors[0] / errors[1], 4.0, 0.5)

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
