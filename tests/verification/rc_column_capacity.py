"""Residual axial capacity of the coarse RC column and the damage index
(Shi, Hao and Li 2008: D = 1 - P_residual / P_intact), in stages.

- Intact: rc_column_axial_capacity_coarse.prm pushes the top face down at
  0.25 m/s (axial strain rate 0.167 1/s). Its peak reaction P_intact
  against the section's capacity at that rate, f'c CDIF A_c + f_y CS A_s
  (seed Eqs. (63)-(65): the rate effects are on), within 10 %; the design
  form 0.85 f'c A_c + f_y A_s (static) is printed beside it. The push is
  quasi-static: kinetic below 5 % of internal energy at the peak.
- Stages: the impact (rc_column_impact_coarse.prm, 'Checkpoint at end'),
  then rc_column_residual_capacity_coarse.prm from its checkpoint
  (`anvil --resume-from`): P_residual < P_intact and summary.csv's
  damage_index = 1 - P_residual / P_intact.
- A stage switch conserves the state: the impact split at 6 ms into two
  stages gives the unsplit run's histories from 6 ms on, byte for byte
  (a split at the end of a run: tests/verification/stages.py).
"""
import os
import subprocess
from anvil_test import Checker, arguments, read_csv, together
import concrete_reference as ref

args = arguments()
c = Checker("residual axial capacity and damage index (coarse column)")
work = args.work_dir
scenes = os.path.join(os.path.abspath(args.source_dir), "prm", "rc_column_impact")
quiet = ["--set", "Simulation/Plots=false", "--set", "Simulation/Print wall times=false"]


def run(*cmd):
    r = subprocess.run([args.anvil, *cmd, *quiet], cwd=work, capture_output=True, text=True)
    return r.returncode, r.stderr.strip()


def summary(name):
    s = read_csv(os.path.join(work, "output", name, "summary.csv"))
    return dict(zip(s["quantity"], s["value"]))


# Intact; beside it (one run a core) the same push to its end time, below.
(code, err), (code_whole, _) = together(
    lambda: run(os.path.join(scenes, "rc_column_axial_capacity_coarse.prm")),
    lambda: run(os.path.join(scenes, "rc_column_axial_capacity_coarse.prm"), "--set", "Simulation/End capacity drop=0",
                "--set", "Simulation/Name=whole_push"))
c.check_true("intact push runs", code == 0, err)
p_intact = summary("rc_column_axial_capacity_coarse")["axial_capacity_N"]
fc, fy, b, d_bar = 45.4e6, 335e6, 0.12, 0.008
A_s = 4 * 3.141592653589793 * d_bar ** 2 / 4
A_c = b * b - A_s
rate = 0.25 / 1.5
cs = 1 + (rate / 40.0) ** (1 / 5.0)
expected = fc * ref.cdif(rate, fc / 0.8) * A_c + fy * cs * A_s
c.check("P_intact against f'c CDIF A_c + f_y CS A_s at 0.167 1/s", p_intact, expected, 0.10, relative=True)
design = 0.85 * fc * A_c + fy * A_s
print(f"  P_intact {p_intact / 1e3:.1f} kN = {p_intact / design:.3f} x the static design capacity "
      f"0.85 f'c A_c + f_y A_s = {design / 1e3:.1f} kN (rate: CDIF {ref.cdif(rate, fc / 0.8):.3f}, "
      f"CS {cs:.3f}; 0.85: the design codes' in-situ factor)")
e = read_csv(os.path.join(work, "output", "rc_column_axial_capacity_coarse", "energy.csv"))
r = read_csv(os.path.join(work, "output", "rc_column_axial_capacity_coarse", "reactions.csv"))
peak_time = r["time"][max(range(len(r["time"])), key=lambda i: abs(r["top_fz"][i]))]
i = min(range(len(e["time"])), key=lambda k: abs(e["time"][k] - peak_time))
c.check_below(f"quasi-static: kinetic / internal energy at the peak (t = {peak_time * 1e3:.2f} ms)",
              e["kinetic"][i] / e["internal"][i], 0.05)
# 'End capacity drop = 0.5' with 'End quiet time = 0.002' (the shipped
# scene): the push stops at the first history row 2 ms after the reaction
# fell below half its peak and stayed there. The same push to its end time
# gives the same rows up to there and the same P_intact, bit for bit.
code = code_whole
w = read_csv(os.path.join(work, "output", "whole_push", "reactions.csv"))
stopped = summary("rc_column_axial_capacity_coarse")
magnitude, times = [abs(f) for f in r["top_fz"]], r["time"]
below = [0 < max(magnitude[:k + 1]) and magnitude[k] <= 0.5 * max(magnitude[:k + 1]) for k in range(len(magnitude))]
last = len(magnitude) - 2  # the row that ended the push (the last row is the final step, off the interval)
since = last
while since > 0 and below[since - 1]:
    since -= 1
held = times[last] - times[since]
c.check_true("the push ends at the first row 2 ms below half its peak (End capacity drop = 0.5)",
             code == 0 and stopped["ended_by_criterion"] == 1 and below[last] and held >= 0.002 - 1e-9 and
             times[last - 1] - times[since] < 0.002 - 1e-9 and len(w["time"]) > len(r["time"]),
             f"{len(r['time'])} rows against {len(w['time'])} to the end time; below half the peak from "
             f"{1e3 * times[since]:.3f} ms to {1e3 * times[last]:.3f} ms")
n = len(r["time"]) - 1  # the last row is the final step, off the history interval
c.check_true("P_intact and the rows before the stop as the whole push's, bit for bit",
             summary("whole_push")["axial_capacity_N"] == p_intact and
             all(w[k][:n] == r[k][:n] for k in r), f"P_intact {p_intact:.6e} N; {n} rows compared")
# The same push on two processes: the end decided on the reactions summed
# over both, at the same row, with the same P_intact (sums in another
# order: to round-off).
r2 = subprocess.run(["mpirun", "-np", "2", "--oversubscribe", args.anvil,
                     os.path.join(scenes, "rc_column_axial_capacity_coarse.prm"), *quiet,
                     "--set", "Simulation/Name=push_np2"], cwd=work, capture_output=True, text=True)
rows2 = read_csv(os.path.join(work, "output", "push_np2", "reactions.csv"))["time"] if r2.returncode == 0 else []
p2 = summary("push_np2")["axial_capacity_N"] if r2.returncode == 0 else 0
c.check_true("np = 2: the push ends at np = 1's row, P_intact to round-off",
             r2.returncode == 0 and rows2 == r["time"] and abs(p2 - p_intact) <= 1e-9 * p_intact,
             f"{len(rows2)} rows against {len(r['time'])}; P_intact {p2:.10e} against {p_intact:.10e} N")
prm_value = float([l.split("=")[1] for l in open(os.path.join(scenes, "rc_column_residual_capacity_coarse.prm"))
                   if l.strip().startswith("set Intact axial capacity")][0])
c.check("'Intact axial capacity' of the residual scene is this P_intact", prm_value, p_intact, 0.005, relative=True)

# Impact, then the residual push as a stage from its checkpoint; beside
# them (one chain a core) the split run of the last check.
every = ["--set", "Simulation/History interval=0", "--set", "Simulation/Output interval=0",
         "--set", "Simulation/End kinetic energy fraction=0"]
impact = os.path.join(scenes, "rc_column_impact_coarse.prm")


def impact_then_residual():
    first = run(impact, "--set", "Simulation/Checkpoint at end=true", "--set", "Simulation/Output interval=0")
    checkpoint = os.path.join(work, "output", "rc_column_impact_coarse", "checkpoint")
    if first[0] != 0 or not os.path.exists(os.path.join(checkpoint, "info")):
        return first, (1, "no checkpoint")
    return first, run("--resume-from", checkpoint, os.path.join(scenes, "rc_column_residual_capacity_coarse.prm"))


def split_run():
    first = run(impact, *every, "--set", "Simulation/End time=0.012", "--set", "Simulation/Name=unsplit",
                "--set", "Simulation/Checkpoint interval=0.006")
    return first, run("--resume-from", os.path.join(work, "output", "unsplit", "checkpoint"), impact, *every,
                      "--set", "Simulation/End time=0.012", "--set", "Simulation/Name=second")


((code, err), (code_res, err_res)), ((code1, _), (code2, err2)) = together(impact_then_residual, split_run)
c.check_true("impact stage runs and leaves a checkpoint", code == 0 and os.path.exists(
    os.path.join(work, "output", "rc_column_impact_coarse", "checkpoint", "info")), err)
c.check_true("residual push runs as a stage from the impact's checkpoint", code_res == 0, err_res)
s = summary("rc_column_residual_capacity_coarse")
p_res = s["axial_capacity_N"]
c.check_true("P_residual below P_intact", p_res < p_intact, f"{p_res / 1e3:.1f} kN against {p_intact / 1e3:.1f} kN")
c.check("summary.csv damage_index against 1 - P_residual / P_intact", s["damage_index"], 1 - p_res / prm_value, 1e-9)
D = s["damage_index"]
level = "low" if D < 0.2 else "medium" if D < 0.5 else "high" if D < 0.8 else "collapse"
print(f"  D = {D:.3f} ({level}; Shi, Hao and Li 2008: < 0.2 low, 0.2-0.5 medium, 0.5-0.8 high, > 0.8 collapse)")

# A stage switch conserves the state: a stage started from a checkpoint
# written mid-run (Checkpoint interval, at a step boundary) continues the
# unsplit run byte for byte. (A stage started from the end of a run does
# too where the end falls on a step of the unsplit run:
# tests/verification/stages.py.)
# (Run above, beside the impact and the residual push.)
c.check_true("split at a step boundary runs", code1 == 0 and code2 == 0, err2)
differ, compared = [], 0
for name in ("energy.csv", "momentum.csv", "probe_impact_point.csv", "contact_impact.csv", "rigid_hammer.csv",
             "reactions.csv", "rebar_longitudinal.csv"):
    whole = open(os.path.join(work, "output", "unsplit", name)).read().splitlines()
    tail = open(os.path.join(work, "output", "second", name)).read().splitlines()
    start = whole.index(tail[1]) if tail[1] in whole else -1
    if start < 0 or whole[start:] != tail[1:]:
        differ.append(name)
    compared += len(tail) - 1
c.check_true(f"the second stage's {compared} rows equal the unsplit run's from the split on", not differ,
             ", ".join(differ))
c.finish()
