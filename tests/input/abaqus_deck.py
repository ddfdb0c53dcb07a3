"""An ABAQUS deck laid out as Abaqus/CAE writes it: two parts, an assembly
of three instances (one translated and rotated, two of the same part),
element labels that do not start at 1, part- and assembly-level sets, an
element-based surface, and the rest of a full deck (materials, a step,
output requests) that Anvil skips with a warning.

Checked against closed forms and conservation laws, not against a golden
file:
- placement: each body's bounding box is its instance's, translated and
  rotated about the axis a -> b (exact to round-off);
- 'Region' takes one instance: the plate thrown at v0 carries momentum
  rho V v0 of one plate, not two;
- the surface and the node set constrain the right face: the bar, rotated
  onto the y axis and moving at -v0 along it onto its fixed end face, pulls
  rho c v0 A from its support until the wave returns (bar theory, nu = 0;
  a bar left unrotated would be loaded in shear, 29 % lower);
- the surface and the node set select the same nodes (same reaction),
  and np = 2 equals np = 1;
- a probe on a one-node set follows that node (the free end: -v0 until
  the wave arrives, +v0 after it reflects);
- bad references stop with one line naming what exists."""
import math
import os
from anvil_test import Checker, arguments, run_anvil, write_scene, read_csv

args = arguments()
c = Checker("ABAQUS/CAE deck: parts, instances, sets, surfaces")

E, rho, v0 = 200e9, 7850.0, 1.0


def block_part(name, n, size, node0, elem0, extra=""):
    """A part of n[0] x n[1] x n[2] C3D8R elements filling size (mm), node
    labels from node0, element labels from elem0."""
    lines = [f"*Part, name={name}", "*Node"]
    label = {}
    for k in range(n[2] + 1):
        for j in range(n[1] + 1):
            for i in range(n[0] + 1):
                label[i, j, k] = node0 + len(label)
                x = [size[0] * i / n[0], size[1] * j / n[1], size[2] * k / n[2]]
                lines.append(f"{label[i, j, k]:7d}, {x[0]:.6g}, {x[1]:.6g}, {x[2]:.6g}")
    lines.append("*Element, type=C3D8R")
    e = elem0
    for k in range(n[2]):
        for j in range(n[1]):
            for i in range(n[0]):
                v = [label[i, j, k], label[i + 1, j, k], label[i + 1, j + 1, k], label[i, j + 1, k],
                     label[i, j, k + 1], label[i + 1, j, k + 1], label[i + 1, j + 1, k + 1],
                     label[i, j + 1, k + 1]]
                lines.append(f"{e}, " + ", ".join(map(str, v)))
                e += 1
    lines.append(f"*Elset, elset=All, generate\n {elem0}, {e - 1}, 1")
    lines.append(f"*Nset, nset=All, generate\n {node0}, {node0 + len(label) - 1}, 1")
    lines.append("** Section: steel\n*Solid Section, elset=All, material=Steel\n,")
    lines.append(extra)
    lines.append("*End Part")
    return "\n".join(lines), label


bar, bar_nodes = block_part("Bar", (10, 1, 1), (100, 10, 10), 501, 1001, extra=(
    "*Elset, elset=_Front_S6, internal\n 1001,\n"
    "*Surface, type=ELEMENT, name=Front\n_Front_S6, S6\n"
    "*Nset, nset=Tip\n 511,"))
plate, _ = block_part("Plate", (2, 2, 1), (20, 20, 5), 1, 1)
end_nodes = ", ".join(str(bar_nodes[0, j, k]) for j in (0, 1) for k in (0, 1))
deck = f"""*Heading
** Job name: anvil-test Model name: Model-1
*Preprint, echo=NO, model=NO, history=NO, contact=NO
**
** PARTS
**
{bar}
{plate}
**
** ASSEMBLY
**
*Assembly, name=Assembly
**
*Instance, name=Bar-1, part=Bar
  50., 0., 0.
  50., 0., 0., 50., 0., 1., 90.
*End Instance
**
*Instance, name=Plate-1, part=Plate
  200., 0., 0.
*End Instance
*Instance, name=Plate-2, part=Plate
  300., 0., 0.
*End Instance
**
*Nset, nset=Fixed, instance=Bar-1
 {end_nodes}
*Elset, elset=_Impact_S6, internal, instance=Bar-1
 1001,
*Surface, type=ELEMENT, name=Impact
_Impact_S6, S6
*End Assembly
**
** MATERIALS
**
*Material, name=Steel
*Density
7.85e-09,
*Elastic
200000., 0.
**
** STEP: Step-1
**
*Step, name=Step-1, nlgeom=YES
*Dynamic, Explicit
, 0.0001
*Boundary
Fixed, 2, 2
** OUTPUT REQUESTS
*Output, field, variable=PRESELECT
*Element Output, directions=YES
S, LE
*End Step
"""
with open(os.path.join(args.work_dir, "cae.inp"), "w") as f:
    f.write(deck)


def body(name, region, velocity="0, 0, 0"):
    return f"""
subsection Body {name}
  subsection Mesh
    set Source = file
    set File name = cae.inp
    set Region = {region}
    set Scale = 0.001
  end
  subsection Material
    subsection elastic
      set Density = {rho}
      set Young's modulus = {E}
      set Poisson's ratio = 0
    end
  end
  set Initial velocity = {velocity}
end
"""


def scene(name, bodies, end_time, extra=""):
    names = ", ".join(b[0] for b in bodies)
    text = f"set Bodies = {names}\n" + "".join(body(*b) for b in bodies) + f"""
subsection Simulation
  set End time = {end_time}
  set Print wall times = false
end
{extra}
"""
    return write_scene(os.path.join(args.work_dir, name + ".prm"), text=text)


# Placement: nothing moves; each body's box is its instance's.
prm = scene("placement", [("bar", "Bar-1"), ("plate1", "plate-1"), ("plate2", "Plate-2.All")], 1e-6)
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if c.check_true("placement scene runs", code == 0, err.strip()):
    c.check_true("the skipped keywords are named in one warning",
                 any("Warning" in l and "*Material" in l and "*Step" in l and "*Solid Section" in l
                     for l in out.splitlines()), out.strip().splitlines()[0] if out else "")
    b = read_csv(os.path.join(args.work_dir, "output/placement/bodies.csv"))
    expected = {"bar": ((0.040, 0, 0), (0.050, 0.100, 0.010), 10),
                "plate1": ((0.200, 0, 0), (0.220, 0.020, 0.005), 4),
                "plate2": ((0.300, 0, 0), (0.320, 0.020, 0.005), 4)}
    for i, name in enumerate(b["body"]):
        lo, hi, n = expected[name]
        c.check(f"{name}: elements", b["elements"][i], n, 0)
        measured = [b[k][i] for k in ("xmin", "ymin", "zmin", "xmax", "ymax", "zmax")]
        error = max(abs(m - e) for m, e in zip(measured, lo + hi))
        c.check(f"{name}: bounding box of the placed instance, largest corner error [m]",
                error, 0.0, 1e-12)

# One instance by 'Region': momentum of one plate.
prm = scene("momentum", [("plate1", "PLATE-1", f"{v0}, 0, 0")], 1e-5)
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if c.check_true("momentum scene runs", code == 0, err.strip()):
    p = read_csv(os.path.join(args.work_dir, "output/momentum/momentum.csv"))
    c.check("plate-1 momentum rho V v0, V = 20 x 20 x 5 mm^3 [kg m/s]", p["px"][-1],
            rho * 2e-6 * v0, 1e-12, relative=True)

# The bar on its fixed end face: a plateau of rho c v0 A until 2 L / c.
cbar = math.sqrt(E / rho)
area, length = 1e-4, 0.1
force = rho * cbar * v0 * area
reactions = {}
for name, selection in (("surface", "surface\n  set Surfaces = impact"),
                        ("node_set", "node set\n  set Node sets = Fixed")):
    for np in (1, 2):
        bc = f"""set Boundary conditions = support
subsection Boundary condition support
  set Body = bar
  set Selection = {selection}
  set Components = y
end
set Probes = tip
subsection Probe tip
  set Body = bar
  set Node set = Bar-1.Tip
end"""
        prm = scene(f"wave_{name}_np{np}", [("bar", "Bar-1", f"0, {-v0}, 0")], 1.8 * length / cbar,
                    extra=bc)
        code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
        if not c.check_true(f"{name}, np = {np}: runs", code == 0, err.strip()):
            continue
        r = read_csv(os.path.join(args.work_dir, f"output/wave_{name}_np{np}/reactions.csv"))
        window = [fy for t, fy in zip(r["time"], r["support_fy"])
                  if 0.4 * length / cbar <= t <= 1.6 * length / cbar]
        reactions[name, np] = r["support_fy"]
        if np == 1:
            c.check(f"{name}: mean support reaction while the wave runs, rho c v0 A [N]",
                    sum(window) / len(window), force, 0.02, relative=True)
            # The probe on node set 'Bar-1.Tip' (node 511, the free end):
            # -v0 until the wave arrives at L / c, +v0 after its reflection.
            p = read_csv(os.path.join(args.work_dir, f"output/wave_{name}_np{np}/probe_tip.csv"))
            before = [vy for t, vy in zip(p["time"], p["vy"]) if t <= 0.8 * length / cbar]
            after = [vy for t, vy in zip(p["time"], p["vy"]) if 1.3 * length / cbar <= t]
            c.check(f"{name}: probe on node set 'Bar-1.Tip' (free end) before the wave [m/s]",
                    max(abs(v + v0) for v in before), 0.0, 1e-9)
            c.check(f"{name}: probe at the free end after the reflection, mean [m/s]",
                    sum(after) / len(after), v0, 0.03, relative=True)
for name in ("surface", "node_set"):
    if (name, 1) in reactions and (name, 2) in reactions:
        a, b = reactions[name, 1], reactions[name, 2]
        c.check(f"{name}: np = 2 against np = 1, largest reaction difference [N]",
                max(abs(x - y) for x, y in zip(a, b)), 0.0, 1e-9 * force)
if ("surface", 1) in reactions and ("node_set", 1) in reactions:
    a, b = reactions["surface", 1], reactions["node_set", 1]
    c.check("surface and node set select the same nodes: largest reaction difference [N]",
            max(abs(x - y) for x, y in zip(a, b)), 0.0, 1e-9 * force)

# Bad references: one line naming what exists, exit 2.
bad = [("region", [("bar", "Nope")], "", "BAR-1"),
       ("surface", [("bar", "Bar-1")],
        "set Boundary conditions = s\nsubsection Boundary condition s\n  set Body = bar\n"
        "  set Selection = surface\n  set Surfaces = Back\nend", "IMPACT"),
       ("node set", [("bar", "Bar-1")],
        "set Boundary conditions = s\nsubsection Boundary condition s\n  set Body = bar\n"
        "  set Selection = node set\n  set Node sets = Back\nend", "FIXED")]
for what, bodies, extra, named in bad:
    prm = scene("bad_" + what.replace(" ", "_"), bodies, 1e-6, extra=extra)
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=("--check",))
    lines = [l for l in err.strip().splitlines() if l]
    c.check_true(f"unknown {what}: exit 2, one line naming '{named}'",
                 code == 2 and len(lines) == 1 and named in lines[0], err.strip())
with open(os.path.join(args.work_dir, "tet.inp"), "w") as f:
    f.write("*Node\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n"
            "*Element, type=C3D4\n1, 1, 2, 3, 4\n")
prm = write_scene(os.path.join(args.work_dir, "tet.prm"), text="""set Bodies = b
subsection Body b
  subsection Mesh
    set Source = file
    set File name = tet.inp
  end
end
""")
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=("--check",))
lines = [l for l in err.strip().splitlines() if l]
c.check_true("element type C3D4: exit 2, one line naming it and its line (6)",
             code == 2 and len(lines) == 1 and "C3D4" in lines[0] and "line 6" in lines[0],
             err.strip())

# One element written mirrored (its top face first): turned, and the block
# carries rho V v0; one flat (a node on its neighbour): refused by label.
cube = "*Node\n" + "".join(f"{i + 1}, {x}, {y}, {z}\n" for i, (x, y, z) in enumerate(
    [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]))
for name, element, ok in (("mirrored", "7, 5, 6, 7, 8, 1, 2, 3, 4", True),
                          ("flat", "7, 1, 2, 3, 4, 1, 2, 3, 4", False)):
    with open(os.path.join(args.work_dir, f"{name}.inp"), "w") as f:
        f.write(cube + "*Element, type=C3D8\n" + element + "\n")
    prm = write_scene(os.path.join(args.work_dir, f"{name}.prm"), text=f"""set Bodies = b
subsection Body b
  subsection Mesh
    set Source = file
    set File name = {name}.inp
  end
  subsection Material
    subsection elastic
      set Density = {rho}
    end
  end
  set Initial velocity = {v0}, 0, 0
end
subsection Simulation
  set End time = 1e-6
  set Print wall times = false
end
""")
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    if ok and c.check_true("mirrored element: turned, the run exits 0", code == 0, err.strip()):
        p = read_csv(os.path.join(args.work_dir, "output/mirrored/momentum.csv"))
        c.check("mirrored element: momentum rho V v0 of the 1 m^3 cube [kg m/s]", p["px"][-1],
                rho * v0, 1e-12, relative=True)
    if not ok:
        lines = [l for l in err.strip().splitlines() if l]
        c.check_true("flat element: exit 2, one line naming element 7",
                     code == 2 and len(lines) == 1 and "element 7 " in lines[0], err.strip())
c.finish()
