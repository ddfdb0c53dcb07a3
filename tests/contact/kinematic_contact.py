"""Kinematic contact enforcement ('Algorithm = kinematic',
Contact::KinematicContact): the penetration of each step's predicted motion
removed exactly, momentum conserved, friction by seed Eqs. (61)-(62).

1. Two elastic rods of unequal length (tests/contact/kinematic_rods.prm:
   rod A 5 m at 1 m/s into rod B 10 m at rest, c = 100 m/s). Bar theory:
   contact for 2 L_A / c = 0.1 s (measured as the time the force on A
   exceeds half of rho c A v0 / 2), then rod A at rest. Checks: the
   contact time within 1 %, rod A's momentum after the impact below 1 %
   of its initial one, the total momentum conserved to round-off (1e-12),
   the deepest penetration left at a step's end below 1e-3 of the element
   size (two deformable bodies: balanced passes, which leave half of what
   one pass alone would correct; 2e-4 measured, as the rods part), the
   energy balance below 1 %. The same scene with the penalty
   method at its default factor is run and printed beside it.
   np = 2 gives the contact force and the probes of np = 1 character for
   character (energy.csv and momentum.csv, sums over each process's nodes,
   within 1e-8).
   Faces that do not match (rod B 4 x 4 across, rod A 2 x 2), and rod B
   halved where y > 0 and x < 1 m (hanging nodes on its contact face and
   sides, moved through their masters): contact time within 2.5 %, rod A's
   rest within 2 %, penetration below 2 % of B's element (balanced passes
   leave half of the corrections' difference where the meshes differ),
   momentum to 1e-12, balance 1 %; np = 2 against np = 1 for the hanging
   nodes. The mismatched rods stopped with a numerical failure as they
   parted before the contact search took only faces facing the node.
   A rigid plate (prescribed, 1 m/s) pushing a block of its own section
   until the block leaves: no sideways momentum (1e-9), balance 1e-4 (it
   blew up as the block left before the faces had to face each other).
2. An elastic block sliding on a fixed rigid plane under gravity
   (tests/contact/kinematic_block.prm, mu = 0.3, v0 = 1 m/s): it stops at
   v0 / (mu g) after v0^2 / (2 mu g) (rigid-block theory) within 1 %; no
   penetration (below 1e-9 m) and no bounce (the bottom corner never
   lifts by more than 1e-5 m); the energy the contact took equals m v0^2 / 2
   within 2 %; the balance below 1 %. The same on the plane's exact
   analytic shape. np = 2 equals np = 1.
3. Static against dynamic friction (mu_s = 0.5, mu_d = 0.3, decay 100 s/m)
   on the flatter block: at a tangential load of 0.4 m g it sticks (moves
   less than 1 % of what mu_d alone would allow in 0.3 s); at 0.6 m g it
   slides at (0.6 - 0.3) g within 2 %.
4. 'Normal damping' with 'Algorithm = kinematic' is refused with one line,
   and so is 'Penalty scale factor' on a pair with a rigid body at the
   default 'Algorithm = automatic' (kinematic there).
5. An ABAQUS deck's *Contact Pair (tests/contact/kinematic_pair.inp: a block
   dropped at 1 m/s onto another) is kinematic, as ABAQUS/Explicit's
   default; with MECHANICAL CONSTRAINT=PENALTY it is a penalty pair. The
   deck runs with its momentum conserved to round-off.
6. The mass-based penalty ('Algorithm = penalty', 'Penalty stiffness =
   nodal mass', LS-DYNA's SOFT = 1): k = s m / dt^2. The block resting on
   the plane under gravity (20 % normal damping settles it) sinks by
   F / k at each node; with the contact pressure rho g H and the bottom
   nodes' mass rho h_z / 2 per unit area, delta = 2 g H dt^2 / (s h_z) =
   4 g dt^2 / s for H = 0.1 m, h_z = 0.05 m, whatever the node: within 2 %.
   Its springs set no step (the element-based ones of the same scene do).
7. Restart: the sliding block with a checkpoint every 0.15 s, resumed
   (`anvil --resume`) from its last checkpoint (t = 0.3 s, still sliding), writes the
   uninterrupted run's histories again, character for character (the
   pair's state: last step's forces and positions, the work so far).
"""
import os
import shutil
from anvil_test import Checker, arguments, max_relative_difference, read_csv, run_anvil

args = arguments()
c = Checker("kinematic contact: rods, sliding and sticking block")
here = os.path.join(os.path.abspath(args.source_dir), "tests", "contact")
g = 9.81


def run(name, scene, np=1, sets=()):
    extra = ["--set", f"Simulation/Output directory=output/{name}"]
    for s in sets:
        extra += ["--set", s]
    code, out, err = run_anvil(args.anvil, os.path.join(here, scene), np=np, cwd=args.work_dir,
                               extra_args=extra)
    if not c.check_true(f"{name} (np = {np}): anvil exits 0", code == 0, (out + err).strip()[-400:]):
        c.finish()
    return os.path.join(args.work_dir, "output", name, scene[:-4])


def csv(directory, name):
    return read_csv(os.path.join(directory, name + ".csv"))


def summary(directory):
    rows = {}
    with open(os.path.join(directory, "summary.csv")) as f:
        for line in f:
            key, _, value = line.strip().partition(",")
            rows[key] = value
    return rows


# 1. The rods.
plateau = 0.01 * 100 * 0.25 * 1.0 / 2
for name, sets in (("rods", ()), ("rods_penalty", ("Contact pair impact/Algorithm=penalty",))):
    d = run(name, "kinematic_rods.prm", sets=sets)
    contact, momentum = csv(d, "contact_impact"), csv(d, "momentum")
    on = [t for t, f in zip(contact["time"], contact["normal_force_x"]) if -f > 0.5 * plateau]
    duration = on[-1] - on[0]
    rest = momentum["rod_a_px"][-1] / momentum["rod_a_px"][0]
    if name == "rods":
        c.check("contact time / (2 L_A / c)", duration / 0.1, 1.0, 0.01)
        c.check_below("rod A's momentum after the impact / before", abs(rest), 0.01)
        c.check_below("total momentum, largest relative change",
                      max(abs(p / momentum["px"][0] - 1) for p in momentum["px"]), 1e-12)
        # Two deformable rods: the passes are balanced (the mean of two
        # corrections), exact where both passes hold the same nodes (1e-10
        # of the element during the impact), not where only one does (as
        # the rods part): ABAQUS's balanced master-slave leaves the same.
        c.check_below("deepest penetration at a step's end / element size (balanced passes)",
                      float(summary(d)["contact_impact_max_penetration"]) / 0.125, 1e-3)
        c.check_below("largest energy balance error", max(csv(d, "energy")["balance_error"]), 0.01)
        kinematic = (duration, rest)
    else:
        print(f"  penalty (factor 0.1) on the same rods: contact time / (2 L_A / c) = {duration / 0.1:.4f}, "
              f"rod A keeps {rest:.4f} of its momentum; kinematic: {kinematic[0] / 0.1:.4f}, {kinematic[1]:.4f}")
par = run("rods_np2", "kinematic_rods.prm", np=2)
serial = os.path.join(args.work_dir, "output", "rods", "kinematic_rods")
for f in ("contact_impact", "probe_face_a", "probe_face_b"):
    same = open(os.path.join(serial, f + ".csv")).read() == open(os.path.join(par, f + ".csv")).read()
    c.check_true(f"rods: np = 2 writes np = 1's {f}.csv, character for character", same)
# (Sums over the processes' nodes: equal to round-off.)
c.check_below("rods: np = 2 against np = 1, largest relative difference of energy.csv and momentum.csv",
              max(max_relative_difference(csv(serial, f), csv(par, f)) for f in ("energy", "momentum")), 1e-8)

# 1b. Faces that do not match. Rod B with 4 x 4 elements across (rod A 2 x
# 2): balanced passes leave half of the two corrections' difference as
# penetration (about 1 % of an element) and the contact time and rod A's
# rest lose about as much (+2.3 % and 1.5 % measured). As the rods part, a
# node in the middle of B's face lies a quarter of the section behind A's
# side face, just beyond its edge: taken as a contact, it blew the rods
# apart (0.11 s, numerical failure); the faces must face each other now
# (the node's face normal is B's axis, the side face's across it).
# Then rod B's elements halved where y > 0 and x < 1 m: hanging nodes on
# its contact face (the line y = 0) and on its sides (x = 1 m), moved
# through their masters (a hanging node's gap and correction are its
# masters'). The mismatch's tolerances, and np = 2 against np = 1.
half = ("Body rod_b/Refinement region/Lower corner=-1, 0, -1", "Body rod_b/Refinement region/Upper corner=1, 1, 1")
for name, sets, h in (("rods_mismatched", ("Body rod_b/Mesh/Subdivisions=80, 4, 4",), 0.125),
                      ("rods_hanging", half, 0.0625)):
    what = "faces 2 x 2 on 4 x 4" if name == "rods_mismatched" else "hanging nodes on the face"
    d = run(name, "kinematic_rods.prm", sets=sets)
    contact, momentum = csv(d, "contact_impact"), csv(d, "momentum")
    on = [t for t, f in zip(contact["time"], contact["normal_force_x"]) if -f > 0.5 * plateau]
    c.check(f"{what}: contact time / (2 L_A / c)", (on[-1] - on[0]) / 0.1, 1.0, 0.025)
    c.check_below(f"{what}: rod A's momentum after the impact / before",
                  abs(momentum["rod_a_px"][-1] / momentum["rod_a_px"][0]), 0.02)
    c.check_below(f"{what}: total momentum, largest relative change",
                  max(abs(p / momentum["px"][0] - 1) for p in momentum["px"]), 1e-12)
    c.check_below(f"{what}: deepest penetration at a step's end / B's element size at the face",
                  float(summary(d)["contact_impact_max_penetration"]) / h, 0.02)
    c.check_below(f"{what}: largest energy balance error", max(csv(d, "energy")["balance_error"]), 0.01)
par = run("rods_hanging_np2", "kinematic_rods.prm", np=2, sets=half)
for f in ("contact_impact", "probe_face_a", "probe_face_b"):
    c.check_true(f"hanging nodes on the face: np = 2 writes np = 1's {f}.csv, character for character",
                 open(os.path.join(d, f + ".csv")).read() == open(os.path.join(par, f + ".csv")).read())

# 1c. A rigid plate (one element, prescribed at 1 m/s) pushes a steel block
# of its own section (tests/input/refinement_region.prm, 4 x 4 x 4), whose
# edges meet the plate's: the block leaves after the wave's round trip.
# Where the edges meet, the block's face nodes lie in the planes of the
# plate's side faces; taken as contacts, those side faces kicked the nodes
# sideways as the block left and the run blew up (0.77 ms). The faces must
# face each other now: by symmetry no sideways momentum (1e-9 of the
# axial), and the balance within 1e-4.
plate = (f"Simulation/End time=0.002", "Simulation/Output interval=0", "Body plate/Mesh/Lower corner=1.00001, 0, 0",
         "Body plate/Initial velocity=-1, 0, 0", "Body block/Refinement region/Upper corner=-1, -1, -1",
         "Body block/Refinement region/Lower corner=-2, -2, -2")
pair = "set Contact pairs = touch\nsubsection Contact pair touch\n  set First body = plate\n  set Second body = block\nend\n"
with open(os.path.join(args.work_dir, "plate_block.prm"), "w") as f:
    f.write(f"include {os.path.join(os.path.abspath(args.source_dir), 'tests', 'input', 'refinement_region.prm')}\n"
            + pair)
extra = ["--set", "Simulation/Output directory=output/plate_block"]
for s_ in plate:
    extra += ["--set", s_]
code, out, err = run_anvil(args.anvil, "plate_block.prm", cwd=args.work_dir, extra_args=extra)
if c.check_true("plate pushing a block of its section: anvil exits 0", code == 0, (out + err).strip()[-300:]):
    d = os.path.join(args.work_dir, "output", "plate_block", "plate_block")
    momentum = csv(d, "momentum")
    sideways = max(max(abs(momentum["block_py"][k]), abs(momentum["block_pz"][k])) for k in range(len(momentum["time"])))
    c.check_below("plate pushing a block of its section: largest sideways momentum / axial",
                  sideways / max(abs(p) for p in momentum["block_px"]), 1e-9)
    c.check_below("plate pushing a block of its section: largest energy balance error",
                  max(csv(d, "energy")["balance_error"]), 1e-4)

# 2. The sliding block, on the plane's mesh and on its analytic shape.
mu, v0, mass = 0.3, 1.0, 1000 * 0.1 ** 3
for name, sets in (("slide", ()), ("slide_analytic", ("Body plane/Rigid body/Contact shape=plane",))):
    d = run(name, "kinematic_block.prm", sets=sets)
    momentum, probe, energy = csv(d, "momentum"), csv(d, "probe_corner"), csv(d, "energy")
    t, px = momentum["time"], momentum["block_px"]
    stop = next(i for i in range(len(t)) if px[i] <= 1e-3 * px[0])
    c.check(f"{name}: stopping time [s]", t[stop], v0 / (mu * g), 0.01, relative=True)
    c.check(f"{name}: stopping distance [m]", probe["ux"][-1], v0 ** 2 / (2 * mu * g), 0.01, relative=True)
    c.check_below(f"{name}: deepest penetration [m]", float(summary(d)["contact_floor_max_penetration"]), 1e-9)
    c.check_below(f"{name}: highest lift of the bottom corner [m]", max(probe["uz"]), 1e-5)
    c.check(f"{name}: energy taken by the contact [J]", energy["contact"][-1], 0.5 * mass * v0 ** 2, 0.02,
            relative=True)
    c.check_below(f"{name}: largest energy balance error", max(energy["balance_error"]), 0.01)
par = run("slide_np2", "kinematic_block.prm", np=2)
same = open(os.path.join(args.work_dir, "output", "slide", "kinematic_block", "energy.csv")).read() == \
    open(os.path.join(par, "energy.csv")).read()
c.check_true("slide: np = 2 writes np = 1's energy.csv, character for character", same)

# 3. Sticking and sliding on a slope of tangential gravity.
flat = ("Body block/Mesh/Upper corner=0.1, 0.1, 0.05", "Body block/Initial velocity=0, 0, 0",
        "Contact pair floor/Static friction coefficient=0.5",
        "Contact pair floor/Dynamic friction coefficient=0.3",
        "Contact pair floor/Friction decay coefficient=100", "Simulation/End time=0.3")
stuck = run("stuck", "kinematic_block.prm", sets=flat + (f"Simulation/Gravity={0.4 * g}, 0, {-g}",))
slid = 0.5 * (0.4 - 0.3) * g * 0.3 ** 2
c.check_below("0.4 m g < mu_s m g: displacement after 0.3 s / that at mu_d",
              max(abs(u) for u in csv(stuck, "probe_corner")["ux"]) / slid, 0.01)
slips = run("slips", "kinematic_block.prm", sets=flat + (f"Simulation/Gravity={0.6 * g}, 0, {-g}",))
momentum = csv(slips, "momentum")
t, px = momentum["time"], momentum["block_px"]
i0 = next(i for i in range(len(t)) if t[i] >= 0.1)
accel = (px[-1] - px[i0]) / (t[-1] - t[i0]) / (mass / 2)
c.check("0.6 m g > mu_s m g: sliding acceleration [m/s^2]", accel, (0.6 - 0.3) * g, 0.02, relative=True)

# 4. Bad input.
code, out, err = run_anvil(args.anvil, os.path.join(here, "kinematic_block.prm"), cwd=args.work_dir,
                           extra_args=["--check", "--set", "Contact pair floor/Normal damping=0.2"])
lines = [l for l in err.splitlines() if l.strip()]
c.check_true("'Normal damping' with kinematic contact: exit 2 and one error line",
             code == 2 and len(lines) == 1 and "Normal damping" in lines[0], err.strip())
# A penalty entry on a pair with a rigid body at the default ('automatic'
# makes it kinematic): refused, naming the entry and the way out.
code, out, err = run_anvil(args.anvil, os.path.join(here, "kinematic_block.prm"), cwd=args.work_dir,
                           extra_args=["--check", "--set", "Contact pair floor/Algorithm=automatic",
                                       "--set", "Contact pair floor/Penalty scale factor=1"])
lines = [l for l in err.splitlines() if l.strip()]
c.check_true("'Penalty scale factor' on an automatic pair with a rigid body: exit 2, one line naming "
             "'Algorithm = penalty'", code == 2 and len(lines) == 1 and "Penalty scale factor" in lines[0]
             and "Algorithm = penalty" in lines[0], err.strip())

# 5. An ABAQUS deck's *Contact Pair.
shutil.copy(os.path.join(here, "kinematic_pair.inp"), os.path.join(args.work_dir, "pair.inp"))
text = open(os.path.join(args.work_dir, "pair.inp")).read()
with open(os.path.join(args.work_dir, "pair_penalty.inp"), "w") as f:
    f.write(text.replace("*Contact Pair, interaction=none", "*Contact Pair, interaction=none, mechanical constraint=PENALTY"))
for deck, algorithm in (("pair.inp", "kinematic"), ("pair_penalty.inp", "penalty")):
    code, out, err = run_anvil(args.anvil, deck, cwd=args.work_dir, extra_args=["--translate"])
    c.check_true(f"{deck}: *Contact Pair translates to 'Algorithm = {algorithm}'",
                 code == 0 and f"set Algorithm = {algorithm}" in out, err.strip()[-300:])
code, out, err = run_anvil(args.anvil, "pair.inp", cwd=args.work_dir,
                           extra_args=["--set", "Simulation/Overwrite existing output=true"])
if c.check_true("pair.inp runs", code == 0, err.strip()[-300:]):
    momentum = read_csv(os.path.join(args.work_dir, "output", "pair", "momentum.csv"))
    c.check_below("pair.inp: total momentum, largest relative change",
                  max(abs(p / momentum["pz"][0] - 1) for p in momentum["pz"]), 1e-12)
    c.check_true("pair.inp: the upper block hands momentum to the lower one",
                 momentum["lower_pz"][-1] < -0.1 * abs(momentum["pz"][0]))

# 6. The mass-based penalty.
rest = ("Contact pair floor/Algorithm=penalty", "Body block/Initial velocity=0, 0, 0", "Simulation/End time=0.2",
        "Contact pair floor/Normal damping=0.2", "Simulation/Time step safety factor=0.7")
limited = {}
for name, stiffness in (("rest_mass", "nodal mass"), ("rest_element", "element")):
    d = run(name, "kinematic_block.prm", sets=rest + (f"Contact pair floor/Penalty stiffness={stiffness}",))
    s_ = summary(d)
    limited[name] = int(s_["contact_limited_steps"])
    if name == "rest_mass":
        dt = 0.2 / float(s_["steps"])
        depth = csv(d, "contact_floor")["max_penetration"][-1]
        c.check("nodal mass: resting penetration [m] against 4 g dt^2 / s", depth, 4 * g * dt ** 2 / 0.1, 0.02,
                relative=True)
        # (After the first 10 ms: the block starts at rest, and while the
        # energies are 1e-4 of the later ones, the start-up of the springs
        # is 1 % of them with either stiffness.)
        e = csv(d, "energy")
        c.check_below("nodal mass: largest energy balance error after 10 ms",
                      max(b for t, b in zip(e["time"], e["balance_error"]) if t >= 0.01), 0.01)
c.check_true("nodal mass: no step set by the springs (element-based: "
             f"{limited['rest_element']} of the steps)", limited["rest_mass"] == 0 and limited["rest_element"] > 0,
             f"{limited['rest_mass']} steps")

# 7. Restart.
ck = ("Simulation/Checkpoint interval=0.15",)
d = run("restart", "kinematic_block.prm", sets=ck)
files = ("energy.csv", "contact_floor.csv", "probe_corner.csv", "momentum.csv")
before = {f: open(os.path.join(d, f)).read() for f in files}
extra = ["--resume"]
for s_ in ck + ("Simulation/Output directory=output/restart",):
    extra = extra + ["--set", s_]
code, out, err = run_anvil(args.anvil, os.path.join(here, "kinematic_block.prm"), cwd=args.work_dir, extra_args=extra)
c.check_true("restart: the run resumes from its checkpoint at t = 0.3 s, while the block slides",
             code == 0 and "resumed from the checkpoint at t = 0.3" in out, (out + err).strip()[-300:])
for f in files:
    c.check_true(f"restart: the resumed run writes {f} again, character for character",
                 open(os.path.join(d, f)).read() == before[f])
c.finish()
