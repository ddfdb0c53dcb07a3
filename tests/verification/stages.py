"""Stages of a scene ('Stages', 'Stage NAME/Changes'): a run goes on, in one
command, on the state the one before left, with entries changed. The scenes
are tests/verification/rod_fixed_step.prm, rod_stages.prm,
damped_block.prm, settle_bar.prm, block_on_floor.prm and
hammer_removed.prm.

- A stage switch conserves the state: the rod impact split into two stages
  at t = 0.125 s gives, from the split on, the histories of the unsplit run
  byte for byte (a fixed step of 2^-13 s, so that both runs step through
  0.125 s alike); on two processes the stage's histories equal one
  process's to round-off of the energy sums.
- Mass damping ('Mass damping' alpha): a free elastic block moving at v0
  keeps its shape and slows as v0 exp(-alpha t); the damping column holds
  the kinetic energy lost, 1/2 m v0^2 (1 - exp(-2 alpha t)); the balance
  closes.
- A member that settles ('End kinetic to internal ratio'): a block under
  gravity, fixed at its base, rings, then settles in a damped stage that
  ends by the criterion; the top's displacement is the static rho g H^2 /
  (2 E) of a bar under its own weight (nu = 0: one-dimensional; total
  Lagrangian, whose hyperelastic energy the balance closes on).
- A body taken out ('Inactive bodies'): a rigid hammer flying at a block
  is removed before it strikes; its kinetic energy becomes the 'removed'
  column, it stays where it was, its contact pair never acts, the balance
  closes.
- Bad input: a stage that changes an entry that does not exist, or takes a
  deformable body out, stops before any run with one line (exit 2).
"""
import math
import os
import subprocess
from anvil_test import Checker, arguments, read_csv, run_anvil, test_scene, write_scene

args = arguments()
c = Checker("stages: state conserved, mass damping, settling, removed bodies")
work = args.work_dir
src = os.path.abspath(args.source_dir)
rod = os.path.join(src, "prm", "elastic_rod_impact", "elastic_rod_impact.prm")
quiet = """  set Plots = false
  set Print wall times = false
  set Overwrite existing output = true
"""


def summary(*parts):
    s = read_csv(os.path.join(work, "output", *parts, "summary.csv"))
    return dict(zip(s["quantity"], s["value"]))


# 1. A stage switch conserves the state.
quiet_entries = {"Simulation/Plots": "false", "Simulation/Print wall times": "false",
                 "Simulation/Overwrite existing output": "true"}
whole = test_scene(args, "tests/verification/rod_fixed_step.prm", "whole", quiet_entries)
split = test_scene(args, "tests/verification/rod_stages.prm", "split", quiet_entries)
split2 = test_scene(args, "tests/verification/rod_stages.prm", "split_np2", quiet_entries)
r1 = run_anvil(args.anvil, whole, cwd=work)
r2 = run_anvil(args.anvil, split, cwd=work)
r3 = run_anvil(args.anvil, split2, np=2, cwd=work)
if c.check_true("unsplit, split and split on 2 processes run", r1[0] == 0 and r2[0] == 0 and r3[0] == 0,
                (r1[2] + r2[2] + r3[2]).strip()[-300:]):
    differ, compared = [], 0
    for name in ("energy.csv", "momentum.csv", "probe_face_a.csv", "probe_centre_b.csv", "contact_impact.csv"):
        w = open(os.path.join(work, "output", "whole", name)).read().splitlines()
        s = open(os.path.join(work, "output", "split", "second", name)).read().splitlines()
        t0 = float(s[1].split(",")[0])
        tail = [l for l in w[1:] if float(l.split(",")[0]) >= t0]
        compared += len(s) - 1
        if tail != s[1:]:
            differ.append(name)
    c.check("stage 'second' starts at the split (s)", float(summary("split", "second")["end_time_s"]) - 0.125,
            0.125, 1e-12)
    c.check_true(f"the stage's {compared} history rows equal the unsplit run's from 0.125 s on, byte for byte",
                 not differ, ", ".join(differ))
    a = read_csv(os.path.join(work, "output", "split", "second", "probe_face_a.csv"))
    b = read_csv(os.path.join(work, "output", "split_np2", "second", "probe_face_a.csv"))
    scale = max(abs(x) for x in a["ux"])
    worst = max(abs(x - y) for x, y in zip(a["ux"], b["ux"])) / scale
    c.check_below("2 processes against 1: the stage's face displacement (relative to its peak)", worst, 1e-8)
    s = summary("split")
    c.check_true("the scene's summary.csv holds the stage's figures",
                 "second.peak_displacement_m" in s and "total_wall_time_s" in s)

# 2. Mass damping: a free block slows as exp(-alpha t).
v0, alpha, rho, side = 2.0, 40.0, 1000.0, 0.2
prm = test_scene(args, "tests/verification/damped_block.prm", "damped", quiet_entries)
code, out, err = run_anvil(args.anvil, prm, cwd=work)
if c.check_true("damped block runs", code == 0, err.strip()[-300:]):
    m = rho * side ** 3
    mom = read_csv(os.path.join(work, "output", "damped", "damped", "momentum.csv"))
    e = read_csv(os.path.join(work, "output", "damped", "damped", "energy.csv"))
    t = mom["time"][-1] - mom["time"][0]
    c.check("stage duration (s)", t, 0.05, 1e-12)
    # The decay between two rows inside the stage (at the switch the
    # damping acts from half a step before: the scheme's v^{n-1/2}).
    i, j = 2, len(mom["time"]) - 2
    c.check("momentum decay between two times / exp(-alpha (t2 - t1))",
            mom["px"][j] / mom["px"][i] / math.exp(-alpha * (mom["time"][j] - mom["time"][i])), 1.0, 1e-3)
    c.check("damping energy / 1/2 m v0^2 (1 - exp(-2 alpha t))", e["damping"][-1] /
            (0.5 * m * v0 ** 2 * (1 - math.exp(-2 * alpha * t))), 1.0, 1e-3)
    c.check_below("internal energy of the rigidly moving block (J)", abs(e["internal"][-1]), 1e-9)
    c.check_below("energy balance error with the damping booked", max(e["balance_error"]), 1e-6)

# 3. Settling under gravity: the static sag of a bar under its own weight.
E, H, g = 1e7, 1.0, 9.81
prm = test_scene(args, "tests/verification/settle_bar.prm", "settle", quiet_entries)
code, out, err = run_anvil(args.anvil, prm, cwd=work)
if c.check_true("settling block runs", code == 0, err.strip()[-300:]):
    s = summary("settle", "settle")
    c.check_true("the settling stage ended by its criterion before its 5 s",
                 s["ended_by_criterion"] == 1 and s["end_time_s"] < 5.0, f"at t = {s['end_time_s']:.3f} s")
    p = read_csv(os.path.join(work, "output", "settle", "settle", "probe_top.csv"))
    sag = rho * g * H ** 2 / (2 * E)
    c.check("top displacement after settling / rho g H^2 / (2 E)", -p["uz"][-1] / sag, 1.0, 0.01)
    e = read_csv(os.path.join(work, "output", "settle", "settle", "energy.csv"))
    c.check_below("kinetic / internal energy at the end", e["kinetic"][-1] / e["internal"][-1], 1e-6)
    # (Total Lagrangian: the updated Lagrangian's hypoelastic Jaumann rate
    # loses 3.5e-4 of the energy in the coarse steps of ringing.)
    c.check_below("energy balance error (gravity's work external, damping booked)", max(e["balance_error"]), 1e-4)
    c.check_true("the damping absorbed energy", e["damping"][-1] > 0, f"{e['damping'][-1]:.4g} J")

# 3b. The pairs an end criterion follows ('End contact pairs') and the
# subjects of summary.csv ('Summary probe', 'Summary contact pair'): the same
# block standing free on a rigid floor by contact, a rigid lid far above it.
# The floor pair carries the block's weight for ever, so a criterion that
# follows every pair never holds (the stage runs its whole 0.5 s); one that
# follows the lid's pair ends the stage once the block has settled, at the
# same sag. Summary.csv reports the probe and the pair named, and every
# pair by name.
weight = rho * side ** 2 * H * g
sag = rho * g * H ** 2 / (2 * E)
floor = os.path.join(src, "tests", "verification", "block_on_floor.prm")
named = """  set Summary probe = middle
  set Summary contact pair = lid
end
subsection Stage settle
  set Changes = Simulation/Mass damping=300; Simulation/End kinetic to internal ratio=1e-6; \\
                Simulation/End quiet time=0.05; Simulation/Duration=0.5; Simulation/End contact pairs=lid
"""
for name, changes in (("every_pair", ""), ("lid_pair", named)):
    prm = write_scene(os.path.join(work, name + ".prm"), text=f"include {floor}\nsubsection Simulation\n{quiet}{changes}end\n")
    code, out, err = run_anvil(args.anvil, prm, cwd=work)
    if not c.check_true(f"block on a floor ({name}) runs", code == 0, err.strip()[-300:]):
        continue
    s = summary(name, "settle")
    p = read_csv(os.path.join(work, "output", name, "settle", "probe_top.csv"))
    c.check(f"{name}: top displacement at the end / rho g H^2 / (2 E)", -p["uz"][-1] / sag, 1.0, 0.01)
    if name == "every_pair":
        c.check_true("following every pair (the floor carries the weight): the stage runs its whole 0.5 s",
                     s["ended_by_criterion"] == 0 and abs(s["end_time_s"] - 0.55) < 1e-9,
                     f"ended at {s['end_time_s']:.4f} s")
        c.check_true("summary.csv by default: the first probe's displacement, the first pair's force",
                     s["peak_displacement_m"] == s["peak_displacement_top_m"] and
                     s["peak_contact_force_N"] >= weight, f"{s['peak_contact_force_N']:.4g} N")
    else:
        c.check_true("following the lid's pair: the stage ends by its criterion",
                     s["ended_by_criterion"] == 1 and s["end_time_s"] < 0.5, f"at {s['end_time_s']:.4f} s")
        c.check_true("summary.csv follows the probe and the pair named (the middle, the lid: no force)",
                     s["peak_displacement_m"] == s["peak_displacement_middle_m"] and
                     s["peak_displacement_m"] != s["peak_displacement_top_m"] and s["peak_contact_force_N"] == 0,
                     f"{s['peak_displacement_m']:.4g} m, {s['peak_contact_force_N']:.4g} N")
        c.check_true("summary.csv's rows of every pair by name: the floor carries the weight, the lid nothing",
                     s["peak_contact_force_floor_N"] >= weight and s["peak_contact_force_lid_N"] == 0 and
                     s["contact_duration_lid_s"] == 0,
                     f"floor {s['peak_contact_force_floor_N']:.4g} N, lid {s['peak_contact_force_lid_N']:.4g} N")
for name, entry, words in (("bad_summary_probe", "Summary probe = bottom", ["Summary probe", "bottom", "top"]),
                           ("bad_end_pairs", "End contact pairs = lid, roof", ["End contact pairs", "roof"])):
    prm = write_scene(os.path.join(work, name + ".prm"), text=f"include {floor}\nsubsection Simulation\n  set {entry}\nend\n")
    code, out, err = run_anvil(args.anvil, prm, cwd=work, extra_args=["--check"])
    lines = [l for l in err.splitlines() if l.strip()]
    c.check_true(f"{name}: exit 2 with one line naming the entry and the name", code == 2 and len(lines) == 1 and
                 all(w in lines[0] for w in words), err.strip())

# 4. A body taken out: the hammer is removed before it strikes.
prm = test_scene(args, "tests/verification/hammer_removed.prm", "removed", quiet_entries)

code, out, err = run_anvil(args.anvil, prm, cwd=work)
if c.check_true("hammer removed in a stage", code == 0, err.strip()[-300:]):
    d = os.path.join(work, "output", "removed", "away")
    e = read_csv(os.path.join(d, "energy.csv"))
    h = read_csv(os.path.join(d, "rigid_hammer.csv"))
    f = read_csv(os.path.join(d, "contact_impact.csv"))
    c.check("removed energy / 1/2 M v0^2 of the hammer", e["removed"][-1] / (0.5 * 270 * 2.0 ** 2), 1.0, 1e-9)
    c.check_below("hammer's centre: largest movement during the stage (m)",
                  max(abs(z - h["z"][0]) for z in h["z"]), 0.0)
    c.check_below("contact force during the stage (N)", max(abs(x) for x in f["normal_force_z"]), 0.0)
    c.check_below("kinetic energy left (J)", abs(e["kinetic"][-1]), 1e-12)
    c.check_below("energy balance error", max(e["balance_error"]), 1e-9)

# 5. Bad input in a stage stops before any run.
for name, change, expect in (("bad_entry", "Simulation/No such entry=1", "No such entry"),
                             ("bad_body", "Simulation/Inactive bodies=rod_a", "deformable")):
    prm = write_scene(os.path.join(work, name + ".prm"), text=f"""include {rod}
set Stages = next
subsection Simulation
{quiet}end
subsection Stage next
  set Changes = {change}
end
""")
    code, out, err = run_anvil(args.anvil, prm, cwd=work)
    lines = err.strip().splitlines()
    c.check_true(f"stage with '{change}': exit 2, one line naming the stage, nothing run",
                 code == 2 and len(lines) == 1 and "Stage next" in err and expect in err and
                 not os.path.exists(os.path.join(work, "output", name)), err.strip()[:300])
c.finish()
