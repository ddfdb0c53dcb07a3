"""'Refinement region' as a user writes it: which elements it refines, and its
errors (tests/input/refinement_region.prm).

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
  1,185 (the box alone would give 1,024 + 48 + 1 = 1,073);
- two regions, x < 0.75 m at one level and 'Refinement region 2' x < 0.25 m
  at two: 1,297; the second region alone near the plate: 177;
- the second region during the run: the plate flying at 100 m/s towards
  the block comes within 0.2 m of the layer x = 0.875 between the rounds
  of 0.2 and 0.4 ms, which halves its 16 elements (177), np = 1 and 2;
- rounds on the two-level box: the layer halved by the one-level rule asks
  to be joined, the rule refuses: the round says so and keeps the mesh.
'Indicator = contact_pressure' during the run (the plate pressed into the
block at 1 m/s): at half the plane wave's pressure rho c v the 16 face
elements are halved, at twice it none. With the penalty, a round at the
pressed face leaves the contact force where the unrefined run has it.
Errors, one line each and exit 2: 'Near body' naming no body, 'Near body'
without a distance, a rigid body refined and 'contact_pressure' on a body
in no contact pair; a contact pair on a surface
with hanging nodes is valid, kinematic or penalty.
"""
import os
import re
from anvil_test import Checker, arguments, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("refinement region: elements refined and bad input")
R = "Body block/Refinement region/"
no_box = {R + "Lower corner": "", R + "Upper corner": ""}


def check(name, overrides=None, text=""):
    prm = test_scene(args, "tests/input/refinement_region.prm", name, overrides, text)
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
    m = re.search(r"(\d+) elements", out)
    return code, int(m.group(1)) if m else -1, err.strip()


touch = "set Contact pairs = touch\nsubsection Contact pair touch\nset First body = block\nset Second body = plate\n"
code, n, err = check("box")
c.check("box x < 0.5 m, one level: elements", n, 289, 0)
code, n, err = check("near_short", {**no_box, R + "Near body": "plate", R + "Distance": 0.2})
c.check("near the plate within 0.2 m: elements", n, 65, 0)
code, n, err = check("near", {**no_box, R + "Near body": "plate", R + "Distance": 0.3})
c.check("near the plate within 0.3 m: elements", n, 177, 0)
code, n, err = check("two_levels", {R + "Upper corner": "0.25, 2, 2", R + "Levels": 2})
c.check("two levels in x < 0.25 m, the next layer refined once by the one-level rule: elements", n, 1185, 0)
# Two regions: the first (x < 0.75 m, one level) halves the three layers
# of centroids 0.125, 0.375 and 0.625 m (384 elements), the second
# (x < 0.25 m, two levels) the first layer's 128 again (1,024): 1,024 +
# 128 + 128 + 16 + 1 = 1,297 (the first region alone: 385 + 16 + 1 = 401).
R2 = "Body block/Refinement region 2/"
code, n, err = check("two_regions", {R + "Upper corner": "0.75, 2, 2", R2 + "Lower corner": "-1, -1, -1",
                                     R2 + "Upper corner": "0.25, 2, 2", R2 + "Levels": 2})
c.check("two regions, x < 0.75 m one level and x < 0.25 m two: elements", n, 1297, 0)
code, n, err = check("second_near", {**no_box, R2 + "Near body": "plate", R2 + "Distance": 0.3, R2 + "Levels": 1})
c.check("the second region alone, near the plate within 0.3 m: elements", n, 177, 0)

# The second region during the run: the plate flies at 100 m/s towards the
# block (no contact pair), 'Near body = plate' within 0.2 m, a round every
# 0.2 ms. At the start the layer of centroids x = 0.875 is 0.225 m from
# the plate's box (65 elements); at the round of 0.4 ms the plate has come
# 0.04 m closer (0.185 m), at that of 0.2 ms only 0.02 m (0.205 m): one
# round, which halves the layer's 16 elements (177), on one process and on
# two alike.
flying = {**no_box, R2 + "Near body": "plate", R2 + "Distance": 0.2, R2 + "Levels": 1,
          "Simulation/Adapt interval": 2e-4, "Simulation/End time": 5e-4, "Body plate/Initial velocity": "-100, 0, 0"}
for np in (1, 2):
    prm = test_scene(args, "tests/input/refinement_region.prm", f"second_flying_np{np}", flying, "")
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    rounds = re.findall(r"adapt at t = (\S+) s, step \d+: (\d+) element\(s\) halved", out)
    m = re.search(r"the state moved onto (\d+) elements", out)
    c.check_true(f"the plate entering the second region during the run, np = {np}: exit 0, one round after "
                 f"0.4 ms", code == 0 and len(rounds) == 1 and float(rounds[0][0]) >= 4e-4,
                 f"exit {code}, rounds {rounds}, {err[-300:]}")
    c.check(f"the plate entering the second region, np = {np}: elements halved", int(rounds[0][1]) if rounds else -1,
            16, 0)
    c.check(f"the plate entering the second region, np = {np}: elements after the round", int(m.group(1)) if m else -1,
            177, 0)

# Rounds during the run on the two-level box: the layer the one-level rule
# halved asks to be joined (no region wants it), which the rule refuses
# while the box stays finer beside it. The round is tried on a copy of the
# mesh first: one line saying the 16 groups stay, no new mesh, and not
# asked again at the next round (before, each such round wrote a
# checkpoint and built the same mesh again).
for np in (1, 2):
    prm = test_scene(args, "tests/input/refinement_region.prm", f"refused_joins_np{np}",
                     {R + "Upper corner": "0.25, 2, 2", R + "Levels": 2, "Simulation/Adapt interval": 2e-4,
                      "Simulation/End time": 5e-4}, "")
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    stay = re.findall(r"adapt at t = \S+ s, step \d+: the (\d+) group\(s\) of eight asked to be joined stay", out)
    rebuilt = re.findall(r"adapt at t = \S+ s, step \d+: \d+ element\(s\) halved", out)
    c.check_true(f"joins the one-level rule refuses, np = {np}: one round says the 16 groups stay, no new mesh, "
                 f"exit 0", code == 0 and stay == ["16"] and not rebuilt,
                 f"exit {code}, stay {stay}, rebuilt {rebuilt}, {err[-300:]}")

# A 'Full integration region' whose boundary x = 0.15 m cuts the first
# layer of refined elements: an element keeps the integration of the
# element it was made from (its centroid, x = 0.375, in the box; x = 0.125
# not), so 16 coarse elements give 128 fully integrated children, beside
# the 32 unrefined elements beyond x = 0.5 m: 160; by the children's own
# centroids (x = 0.1875, 0.3125, 0.4375) it would be 192 + 32.
# A child then never changes group when a round of refinement makes it.
prm = test_scene(args, "tests/input/refinement_region.prm", "full_region",
                 {"Body block/Full integration region/Lower corner": "0.15, -1, -1",
                  "Body block/Full integration region/Upper corner": "2, 2, 2",
                  "Body block/Refinement region/Upper corner": "0.5, 2, 2",
                  "Simulation/End time": 1e-7}, "")
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
m = re.search(r"body 'block':.*; (\d+) element\(s\) fully integrated", out)
c.check("full integration region cutting refined elements: fully integrated elements (those of the 16 "
        "coarse ones inside)", int(m.group(1)) if m else -1, 16 * 8 + 2 * 16, 0)

# 'Indicator = contact_pressure' during the run: the rigid plate 10 um from
# the block's face x = 1, prescribed at 1 m/s into it, checked after 0.2 ms.
# The plane wave's pressure is rho c v (c of uniaxial strain, 5,856 m/s:
# 46 MPa), which each face element's inner node carries on its area h^2:
# at a threshold of half that pressure the 16 elements of the face are
# halved, at twice it none.
E, nu, rho, v = 2e11, 0.3, 7850.0, 1.0
pressure = rho * (E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho) ** 0.5 * v
pressing = {**no_box, R + "Indicator": "contact_pressure", R + "Levels": 1, "Simulation/Adapt interval": 2e-4,
            "Simulation/End time": 3e-4, "Body plate/Mesh/Lower corner": "1.00001, 0, 0",
            "Body plate/Initial velocity": "-1, 0, 0"}
for factor, expected in ((0.5, 16), (2.0, 0)):
    prm = test_scene(args, "tests/input/refinement_region.prm", f"pressure_{factor:g}",
                     {**pressing, R + "Indicator threshold": factor * pressure}, touch + "end\n")
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    m = re.search(r"adapt at t = \S+ s, step \d+: (\d+) element\(s\) halved", out)
    c.check(f"contact_pressure above {factor:g} rho c v ({factor * pressure:.3g} Pa): elements halved",
            int(m.group(1)) if m else (0 if code == 0 else -1), expected, 0)

# The same press with the penalty and a plate wider than the face (no
# node on its edge), the face halved during the run at a tenth of rho c v:
# an element halved during the run keeps the pressure stiffness f K / h of
# the element the run started with, so the round leaves the contact force
# where the unrefined run has it. (Before, with the child's own h, the
# force doubled at the round: +87 %.)
penalty = {**pressing, "Body plate/Mesh/Lower corner": "1.00001, -0.5, -0.5",
           "Body plate/Mesh/Upper corner": "1.1, 1.5, 1.5", "Simulation/End time": 4e-4}
press = touch + "set Algorithm = penalty\nend\n"
forces = {}
for name, threshold in (("penalty_refined", 0.1 * pressure), ("penalty_uniform", 100 * pressure)):
    prm = test_scene(args, "tests/input/refinement_region.prm", name,
                     {**penalty, R + "Indicator threshold": threshold}, press)
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    m = re.search(r"adapt at t = (\S+) s", out)
    forces[name] = (code, float(m.group(1)) if m else None,
                    read_csv(os.path.join(args.work_dir, "output", name, "contact_touch.csv")) if code == 0 else None)
(code_r, t_round, refined), (code_u, _, uniform) = forces["penalty_refined"], forces["penalty_uniform"]
c.check_true("penalty press refined during the run and unrefined: both run to the end, one round",
             code_r == 0 and code_u == 0 and t_round is not None, f"exit {code_r}, {code_u}")
if refined and uniform and t_round:
    def force_at(data, t):
        times, f = data["time"], data["normal_force_x"]
        for i in range(1, len(times)):
            if times[i] >= t:
                w = (t - times[i - 1]) / (times[i] - times[i - 1])
                return f[i - 1] + w * (f[i] - f[i - 1])
        return f[-1]
    after = [(t, f) for t, f in zip(refined["time"], refined["normal_force_x"]) if t > t_round * 1.0001][:3]
    worst = max(abs(f / force_at(uniform, t) - 1) for t, f in after)
    c.check("penalty press: contact force in the three rows after the round against the unrefined run's, "
            "largest relative difference", worst, 0, 0.02)

for name, overrides, text, what in (
        ("unknown_near", {**no_box, R + "Near body": "wall", R + "Distance": 0.1}, "", "is not in 'Bodies'"),
        ("no_distance", {**no_box, R + "Near body": "plate"}, "", "needs a 'Distance'"),
        ("rigid_refined", {**no_box, "Body plate/Refinement region/Lower corner": "0, 0, 0",
                           "Body plate/Refinement region/Upper corner": "2, 2, 2"}, "", "a rigid body"),
        ("pressure_no_pair", {**no_box, R + "Indicator": "contact_pressure"}, "", "no pair"),
        ("second_unknown_near", {**no_box, "Body block/Refinement region 2/Near body": "wall",
                                 "Body block/Refinement region 2/Distance": 0.1},
         "", "Refinement region 2': body 'wall' is not in 'Bodies'")):
    code, n, err = check(name, overrides, text)
    c.check_true(f"{name}: exit 2 with one line saying '{what}'",
                 code == 2 and len(err.splitlines()) == 1 and what in err, err[:300])
code, n, err = check("kinematic", {}, touch + "end\n")
c.check_true("a kinematic pair on a surface with hanging nodes (moved through their masters): valid", code == 0,
             err[:300])
code, n, err = check("penalty", {}, touch + "set Algorithm = penalty\nend\n")
c.check_true("the same pair with the penalty: valid", code == 0, err[:300])
c.finish()
