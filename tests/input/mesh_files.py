"""Meshes from files (ABAQUS .inp and Gmsh .msh, with 'Scale' from mm to m)
and the built-in cylinder, checked by a conservation law: a free body
thrown at v0 carries momentum rho V v0 exactly, with V the volume of the
geometry (a 2 x 1 x 1 m block from the files; the cylinder's regular
n-gon section times its length, for section and global refinements). The
scene is tests/input/mesh_files.prm, on block_mm.inp and block_mm.msh.
Also exercises a box-selected boundary condition (exit status and its
constrained momentum)."""
import math
import os
from anvil_test import Checker, arguments, run_anvil, test_scene, read_csv

args = arguments()
c = Checker("mesh files, cylinder generator, box-selected boundary condition")

scene = "tests/input/mesh_files.prm"
rho, v0 = 7850.0, 3.0
for name in ("inp", "msh"):
    # The .inp is the scene's own (named relative to it, through the
    # include); the .msh named here, in the including file.
    msh = os.path.join(os.path.abspath(args.source_dir), "tests", "input", "block_mm.msh")
    prm = test_scene(args, scene, f"file_{name}", {"Body b/Mesh/File name": msh} if name == "msh" else {})
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
    run = f"cylinder_s{section}_g{refinements}"
    prm = test_scene(args, scene, run, {"Body b/Mesh/Source": "cylinder", "Body b/Mesh/File name": "",
                                        "Body b/Mesh/Scale": 1, "Body b/Mesh/Radius": r, "Body b/Mesh/Length": length,
                                        "Body b/Mesh/Section refinements": section,
                                        "Body b/Mesh/Global refinements": refinements})
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
extra = """set Boundary conditions = hold
subsection Boundary condition hold
  set Body = b
  set Selection = box
  set Box lower corner = -0.1, -0.1, -0.1
  set Box upper corner = 0.1, 1.1, 1.1
  set Components = x
end
"""
prm = test_scene(args, scene, "box_bc", {"Body b/Mesh/Source": "box", "Body b/Mesh/File name": "",
                                         "Body b/Mesh/Scale": 1, "Body b/Mesh/Upper corner": "1, 1, 1",
                                         "Body b/Mesh/Subdivisions": "2, 2, 2"}, extra)
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if c.check_true("box-selected condition: runs", code == 0, err.strip()):
    p = read_csv(os.path.join(args.work_dir, "output/box_bc/momentum.csv"))
    c.check("box-selected condition: initial momentum of the free nodes [kg m/s]", p["px"][0], rho * 0.75 * v0, 1e-9, relative=True)
c.finish()
