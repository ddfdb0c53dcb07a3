"""'Refinement region' as a user writes it: which elements it refines, and its errors.

A unit block of 4 x 4 x 4 elements and a rigid plate 0.1 m beyond its face
x = 1, checked with `anvil --check` (the mesh is built and refined, the
families set up, nothing runs); the element count it reports against the
count by hand:
- the box x < 0.5 m, one level: 32 elements become 256, 32 stay (+ 1 plate
  element): 289;
- 'Near body = plate' within 0.2 m: the layer of centroids at x = 0.875
  (0.225 m from the plate's box) is out of reach, so none; within 0.3 m:
  that layer of 16 becomes 128: 177;
- two levels in the box x < 0.25 m: the first layer's 16 elements become
  128, all with their centroid in the box, and those 1,024; the second
  layer (x from 0.25 to 0.5 m) would meet level-2 elements two levels
  apart, so the one-level rule halves it too (128): 1,024 + 128 + 32 + 1 =
  1,185 (the box alone would give 1,024 + 48 + 1 = 1,073).
Errors, one line each and exit 2: 'Near body' naming no body, 'Near body'
without a distance, a rigid body refined, and a kinematic contact pair on a
surface with hanging nodes (the penalty takes it: exit 0).
"""
import os
import re
from anvil_test import Checker, arguments, run_anvil, write_scene

args = arguments()
c = Checker("refinement region: elements refined and bad input")
base = """
set Bodies = block, plate
subsection Body block
  subsection Mesh
    set Subdivisions = 4, 4, 4
  end
  subsection Material
    subsection elastic
      set Density = 7850
      set Young's modulus = 2e11
      set Poisson's ratio = 0.3
    end
  end
  subsection Refinement region
{region}
  end
end
subsection Body plate
  subsection Mesh
    set Lower corner = 1.1, 0, 0
    set Upper corner = 1.2, 1, 1
    set Subdivisions = 1, 1, 1
  end
  subsection Material
    set Model = rigid
  end
{plate}
end
{extra}
"""


def check(name, region, plate="", extra=""):
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"),
                      text=base.format(region=region, plate=plate, extra=extra))
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
    m = re.search(r"(\d+) elements", out)
    return code, int(m.group(1)) if m else -1, err.strip()


code, n, err = check("box", "set Lower corner = -1, -1, -1\nset Upper corner = 0.5, 2, 2")
c.check("box x < 0.5 m, one level: elements", n, 289, 0)
code, n, err = check("near_short", "set Near body = plate\nset Distance = 0.2")
c.check("near the plate within 0.2 m: elements", n, 65, 0)
code, n, err = check("near", "set Near body = plate\nset Distance = 0.3")
c.check("near the plate within 0.3 m: elements", n, 177, 0)
code, n, err = check("two_levels", "set Lower corner = -1, -1, -1\nset Upper corner = 0.25, 2, 2\nset Levels = 2")
c.check("two levels in x < 0.25 m, the next layer refined once by the one-level rule: elements", n, 1185, 0)

for name, region, plate, extra, what in (
        ("unknown_near", "set Near body = wall\nset Distance = 0.1", "", "", "is not in 'Bodies'"),
        ("no_distance", "set Near body = plate", "", "", "needs a 'Distance'"),
        ("rigid_refined", "", "subsection Refinement region\nset Lower corner = 0, 0, 0\n"
                              "set Upper corner = 2, 2, 2\nend", "", "a rigid body"),
        ("kinematic", "set Lower corner = -1, -1, -1\nset Upper corner = 0.5, 2, 2", "",
         "set Contact pairs = touch\nsubsection Contact pair touch\nset First body = block\n"
         "set Second body = plate\nend", "kinematic contact does not take")):
    code, n, err = check(name, region, plate, extra)
    c.check_true(f"{name}: exit 2 with one line saying '{what}'",
                 code == 2 and len(err.splitlines()) == 1 and what in err, err[:300])
code, n, err = check("penalty", "set Lower corner = -1, -1, -1\nset Upper corner = 0.5, 2, 2", "",
                     "set Contact pairs = touch\nsubsection Contact pair touch\nset First body = block\n"
                     "set Second body = plate\nset Algorithm = penalty\nend")
c.check_true("the same pair with the penalty: valid", code == 0, err[:300])
c.finish()
