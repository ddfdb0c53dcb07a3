"""Mesh sources as plugins (tests/input/mesh_sources.prm): the elements each
source makes, the entries of a source a body did not choose, bad input.

The scene holds one body of each generated source; `anvil --check` builds
the meshes and reports the elements, against the count by hand:
- the ball ('sphere'): deal.II's balanced ball of 32 cells, refined once:
  256; the roller ('cylinder'): a disk of 5 cells refined once in its
  section (20) times 4 along the axis: 80; the slab ('box'): 16; in all 352;
- 'Global refinements = 1' on the roller: its section refined twice (80)
  and its axis halved (8): 640, in all 912;
- the graded 'ball' in the sphere's place, a quarter and whole: n x n x 2n
  and 2n x 2n x 2n elements, its volume below the sphere's by less than
  1 % (bilinear faces with their corners on the sphere lie inside it), the
  quarter's a quarter of the whole's.
An entry that belongs to another source ('Region' on the box, 'Section
refinements' on the sphere, 'Subdivisions' on the cylinder, 'Length' on the
box) is ignored, and a warning names it and the source it belongs to (a
scene that includes another and switches the source inherits such entries,
so they are no error). Errors, one line each and exit 2:
- a ball refined 8 times (32 x 8^8 elements) does not fit and says so,
  naming 'Global refinements';
- a grading whose elements would span more than a factor 10^6 in size (a
  box's 'Grading' 10 over 40 elements, a ball's 3 over 40) is refused: the
  smallest element would set the step, or have no volume at all (it
  stopped with "a node has no mass" and MPI_ABORT);
- an unknown source lists the ones there are.
"""
import math
import os
from anvil_test import Checker, arguments, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("mesh sources: elements made, entries of other sources, bad input")
scene = "tests/input/mesh_sources.prm"


def check(name, overrides=None):
    prm = test_scene(args, scene, name, overrides)
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
    count = -1
    for line in out.splitlines():
        if "elements," in line:
            count = int(line.split(" elements,")[0].split()[-1])
    return code, count, err.strip()


code, n, err = check("as_shipped")
c.check_true("the scene is valid", code == 0, err[-300:])
c.check("elements: 32 x 8 (ball) + 5 x 4 x 4 (roller) + 16 (slab)", n, 32 * 8 + 5 * 4 * 4 + 16, 0)
code, n, err = check("roller_refined", {"Body roller/Mesh/Global refinements": 1})
c.check("roller refined once more: 32 x 8 + 5 x 16 x 8 + 16", n, 32 * 8 + 5 * 16 * 8 + 16, 0)

# The graded 'ball' in place of the sphere (8 elements along a radius,
# refined once): n x n x 2n for a quarter, 2n x 2n x 2n for the whole; its
# volume below that of the sphere (its faces are bilinear patches with
# their corners on it, inside it) by less than 1 %, the quarter a quarter
# of the whole.
volumes = {}
for part, cells in (("quarter", 2 * 8 ** 3), ("full", 8 * 8 ** 3)):
    ball = {"Body ball/Mesh/Source": "ball", "Body ball/Mesh/Ball part": part, "Body ball/Mesh/Ball subdivisions": 8,
            "Body ball/Mesh/Ball grading": 1.15}
    prm = test_scene(args, scene, f"ball_{part}", {**ball, "Simulation/End time": 1e-7})
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    if not c.check_true(f"ball, {part}: runs", code == 0, err[-300:]):
        continue
    b = read_csv(os.path.join(args.work_dir, "output", f"ball_{part}", "bodies.csv"))
    i = b["body"].index("ball")
    c.check(f"ball, {part}: elements, {cells} x 8", b["elements"][i], cells * 8, 0)
    volumes[part] = b["reference_volume"][i]
sphere = 4 / 3 * math.pi * 0.1 ** 3
if len(volumes) == 2:
    deficit = 1 - volumes["full"] / sphere
    print(f"  ball: volume {volumes['full']:.6g} m^3 against the sphere's {sphere:.6g} m^3 ({-100 * deficit:+.3f} %)")
    c.check_true("ball: its volume below the sphere's by less than 1 %", 0 < deficit < 0.01, f"{deficit:.4g}")
    c.check("ball: the quarter's volume / a quarter of the whole", volumes["quarter"] / (volumes["full"] / 4), 1.0, 1e-9)

for name, overrides, words in (
        ("region_on_box", {"Body slab/Mesh/Region": "PART-1"},
         ("body 'slab'", "'Region'", "'Source = file'", "'Source = box'")),
        ("section_on_sphere", {"Body ball/Mesh/Section refinements": 1},
         ("body 'ball'", "'Section refinements'", "'Source = cylinder'", "'Source = sphere'")),
        ("subdivisions_on_cylinder", {"Body roller/Mesh/Subdivisions": "2, 2, 2"},
         ("body 'roller'", "'Subdivisions'", "'Source = box'", "'Source = cylinder'")),
        ("length_on_box", {"Body slab/Mesh/Length": 2}, ("body 'slab'", "'Length'", "'Source = cylinder'"))):
    prm = test_scene(args, scene, name, overrides)
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
    warnings = [line for line in out.splitlines() if line.startswith("Warning:")]
    c.check_true(f"{name}: valid (exit 0), one warning naming {', '.join(words)}",
                 code == 0 and len(warnings) == 1 and all(w in warnings[0] for w in words),
                 (warnings[0] if warnings else err)[:400])

for name, overrides, words in (
        ("ball_too_fine", {"Body ball/Mesh/Global refinements": 8}, ("'Global refinements'", "Body ball/Mesh")),
        ("box_overgraded", {"Body slab/Mesh/Subdivisions": "40, 4, 1", "Body slab/Mesh/Grading": "10, 1, 1"},
         ("'Grading'", "40 elements", "1e+39", "Body slab/Mesh")),
        ("ball_overgraded", {"Body ball/Mesh/Source": "ball", "Body ball/Mesh/Ball subdivisions": 40,
                             "Body ball/Mesh/Ball grading": 3}, ("'Ball grading'", "40 elements", "Body ball/Mesh")),
        ("unknown_source", {"Body ball/Mesh/Source": "tube"}, ("Source", "box", "cylinder", "file", "sphere"))):
    code, n, err = check(name, overrides)
    c.check_true(f"{name}: exit 2 with one line naming {', '.join(words)}",
                 code == 2 and len(err.splitlines()) == 1 and all(w in err for w in words), err[:400])
c.finish()
