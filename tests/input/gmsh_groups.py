"""Meshes made by Gmsh (Debian's gmsh, from tests/input/two_blocks.geo) as
users make them: two physical volumes in one file, a named physical
surface and a numbered one, ASCII formats 2.2 and 4.1, and a binary file.

- 'Region' takes one physical volume by name: element counts per body
  (32 each, not 64), and the same for both formats;
- the named surface ('Base', by 'Selection = surface') and the numbered
  one (7, by 'Selection = node set': its nodes) constrain the right faces:
  each block, moving at v0 along z with that face held, pulls rho c v0 A
  from its support until the wave returns (bar theory, nu = 0);
- np = 2 equals np = 1;
- a binary file and a tetrahedral mesh stop with one line each."""
import math
import os
import shutil
import subprocess
from anvil_test import Checker, arguments, run_anvil, write_scene, read_csv

args = arguments()
c = Checker("Gmsh files: physical volumes and surfaces by name and number")
gmsh = shutil.which("gmsh")
if not c.check_true("gmsh is installed (scripts/setup installs it)", gmsh is not None):
    c.finish()

geo = os.path.join(args.source_dir, "tests", "input", "two_blocks.geo")
for name, options in (("blocks41.msh", ["-format", "msh41"]), ("blocks22.msh", ["-format", "msh22"]),
                      ("blocks_binary.msh", ["-format", "msh41", "-bin"])):
    r = subprocess.run([gmsh, "-3", *options, geo, "-o", os.path.join(args.work_dir, name)],
                       capture_output=True, text=True)
    c.check_true(f"gmsh writes {name}", r.returncode == 0, r.stderr.strip()[-200:])

E, rho, v0 = 200e9, 7850.0, 1.0
cbar, length, area = math.sqrt(E / rho), 0.01, 4e-4
force = rho * cbar * v0 * area


def scene(name, mesh_file, end_time):
    text = "set Bodies = anvil, striker\n"
    for body, region in (("anvil", "Anvil"), ("striker", "striker")):
        text += f"""
subsection Body {body}
  subsection Mesh
    set Source = file
    set File name = {mesh_file}
    set Region = {region}
  end
  subsection Material
    subsection elastic
      set Density = {rho}
      set Young's modulus = {E}
      set Poisson's ratio = 0
    end
  end
  set Initial velocity = 0, 0, {v0}
end
"""
    text += f"""
set Boundary conditions = base, top
subsection Boundary condition base
  set Body = anvil
  set Selection = surface
  set Surfaces = base
  set Components = z
end
subsection Boundary condition top
  set Body = striker
  set Selection = node set
  set Node sets = 7
  set Components = z
end
subsection Simulation
  set End time = {end_time}
  set Print wall times = false
end
"""
    return write_scene(os.path.join(args.work_dir, name + ".prm"), text=text)


results = {}
for fmt in ("41", "22"):
    for np in ((1, 2) if fmt == "41" else (1,)):
        run = f"blocks{fmt}_np{np}"
        prm = scene(run, f"blocks{fmt}.msh", 1.8 * length / cbar)
        code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
        if not c.check_true(f"format {fmt[0]}.{fmt[1]}, np = {np}: runs", code == 0, err.strip()):
            continue
        b = read_csv(os.path.join(args.work_dir, f"output/{run}/bodies.csv"))
        r = read_csv(os.path.join(args.work_dir, f"output/{run}/reactions.csv"))
        results[fmt, np] = r
        if np == 1:
            for i, body in enumerate(b["body"]):
                c.check(f"format {fmt[0]}.{fmt[1]}: {body} elements (its physical volume only)",
                        b["elements"][i], 32, 0)
        if fmt == "41" and np == 1:
            for bc in ("base", "top"):
                window = [-fz for t, fz in zip(r["time"], r[f"{bc}_fz"])
                          if 0.4 * length / cbar <= t <= 1.6 * length / cbar]
                c.check(f"'{bc}' holds its face: mean reaction while the wave runs, rho c v0 A [N]",
                        sum(window) / len(window), force, 0.02, relative=True)


def largest_difference(a, b):
    return max(abs(x - y) for k in ("base_fz", "top_fz") for x, y in zip(a[k], b[k]))


if ("41", 1) in results and ("41", 2) in results:
    c.check("np = 2 against np = 1, largest reaction difference [N]",
            largest_difference(results["41", 1], results["41", 2]), 0.0, 1e-9 * force)
if ("41", 1) in results and ("22", 1) in results:
    c.check("format 2.2 against 4.1, largest reaction difference [N]",
            largest_difference(results["41", 1], results["22", 1]), 0.0, 1e-9 * force)

# Files Anvil cannot take: one line each, exit 2.
with open(os.path.join(args.work_dir, "tets.geo"), "w") as f:
    f.write("SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
            "Physical Volume(\"Block\") = {1};\n")
subprocess.run([gmsh, "-3", "-format", "msh41", os.path.join(args.work_dir, "tets.geo"), "-o",
                os.path.join(args.work_dir, "tets.msh")], capture_output=True)
for mesh_file, expected in (("blocks_binary.msh", "binary"), ("tets.msh", "hexahedra")):
    prm = write_scene(os.path.join(args.work_dir, "bad.prm"), text=f"""set Bodies = b
subsection Body b
  subsection Mesh
    set Source = file
    set File name = {mesh_file}
  end
end
""")
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=("--check",))
    lines = [l for l in err.strip().splitlines() if l]
    c.check_true(f"{mesh_file}: exit 2, one line saying '{expected}'",
                 code == 2 and len(lines) == 1 and expected in lines[0], err.strip()[-300:])
c.finish()
