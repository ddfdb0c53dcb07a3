"""The paper's hammer-mass and hammer-velocity studies on the coarse RC
column (prm/rc_column_impact/studies/*_coarse.prm, run by `anvil --study`),
each run the three stages of rc_column_damage_index_coarse.prm: the impact,
the column settling without the hammer, the axial push to failure.

The mass study is first stopped with SIGTERM and started again: its runs
resume from their checkpoints. Checks: every run ends (exit 0) with its energy balance closed (below 2 %
of the scale); the initial energy of each run is the hammer's 1/2 m v^2
(the study changed the entry it names); and the trend directions of the
seed's section 5.5.1-5.5.2: the peak displacement of the impact point
grows with the hammer mass and with its velocity, and so does the damage
index D = 1 - P_residual / P_intact (the paper's criterion). The sizes of the
increments are printed beside the paper's (doc/studies.md says why they
differ: the arching of the fixed ends, prm/rc_column_impact/README.md).
"""
import os
import signal
import shutil
import subprocess
import time
from anvil_test import Checker, arguments, read_csv, together

args = arguments()
c = Checker("column studies: hammer mass and velocity (coarse)")
studies = os.path.join(os.path.abspath(args.source_dir), "prm", "rc_column_impact", "studies")

# The mass study is stopped (SIGTERM) while its first runs are under way:
# they write checkpoints, and the study started again resumes them (its
# results then pass the same checks as an uninterrupted study's).
# The signal goes 1 s after both first runs have finished their setup (not
# at a fixed time: a run takes a few seconds, and faster code once let two
# of them finish before a fixed 6 s; nor when their logs appear: a run still
# starting MPI under load then died without a checkpoint).
shutil.rmtree(os.path.join(args.work_dir, "output", "hammer_mass_coarse"), ignore_errors=True)
p = subprocess.Popen([args.anvil, "--study", os.path.join(studies, "hammer_mass_coarse.prm"), "--jobs", "2"],
                     cwd=args.work_dir, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
deadline = time.time() + 300
def set_up(i):
    log = os.path.join(args.work_dir, "output", "hammer_mass_coarse", f"run_0{i}", "run.log")
    return os.path.exists(log) and "results in" in open(log, errors="replace").read()


while time.time() < deadline and p.poll() is None and not all(set_up(i) for i in (1, 2)):
    time.sleep(0.05)
time.sleep(1.0)
p.send_signal(signal.SIGTERM)
out, err = p.communicate()
c.check_true("a study stopped by SIGTERM: exit 5, its runs checkpointed", p.returncode == 5 and
             os.path.exists(os.path.join(args.work_dir, "output", "hammer_mass_coarse", "run_01", "checkpoint")),
             (out + err).strip().splitlines()[-1])

# The resumed mass study and the velocity study side by side, one job
# each: six runs in three rounds on two cores (each study alone on two
# jobs leaves a core idle in its second round).
cases = (("hammer_mass_coarse", "mass_plot_value", lambda x: 0.5 * x * 2.0 ** 2, "+33 mm, then +27 mm"),
         ("hammer_velocity_coarse", "velocity_plot_value", lambda x: 0.5 * 270 * x ** 2,
          "+35.4 mm, then +97.6 mm"))
ran = together(*[lambda study=case[0]: subprocess.run(
    [args.anvil, "--study", os.path.join(studies, study + ".prm"), "--jobs", "1"],
    cwd=args.work_dir, capture_output=True, text=True) for case in cases])
for (study, values, energy, paper), r in zip(cases, ran):
    if not c.check_true(f"{study}: every run ends", r.returncode == 0, (r.stderr or r.stdout).strip()[-400:]):
        continue
    t = read_csv(os.path.join(args.work_dir, "output", study, "study.csv"))
    if study == "hammer_mass_coarse":
        log = open(os.path.join(args.work_dir, "output", study, "run_01", "run.log")).read()
        c.check_true("the stopped runs resumed from their checkpoints", "resumed from the checkpoint" in log)
    x, peak = t[values], t["peak_displacement_m"]
    for i in range(len(x)):
        c.check(f"{study} {x[i]:g}: initial energy against 1/2 m v^2", t["initial_energy_J"][i],
                energy(x[i]), 1e-9, relative=True)
        c.check_below(f"{study} {x[i]:g}: largest energy balance error", t["max_balance_error"][i], 0.02)
    order = sorted(range(len(x)), key=lambda i: x[i])
    grows = all(peak[order[k + 1]] > peak[order[k]] for k in range(len(order) - 1))
    steps = ", ".join(f"{1e3 * (peak[order[k + 1]] - peak[order[k]]):+.1f} mm" for k in range(len(order) - 1))
    c.check_true(f"{study}: peak displacement grows with the varied value",
                 grows, f"peaks {', '.join(f'{1e3 * peak[i]:.2f}' for i in order)} mm; increments {steps} "
                 f"(the paper: {paper})")
    # The damage index of each run's last stage: the axial push of the
    # settled column against the intact column's capacity.
    D, P = t["damage_index"], t["axial_capacity_N"]
    c.check_true(f"{study}: damage index D = 1 - P_residual / P_intact grows with the varied value",
                 all(D[order[k + 1]] > D[order[k]] for k in range(len(order) - 1)),
                 f"D {', '.join(f'{D[i]:.3f}' for i in order)} (P_residual "
                 f"{', '.join(f'{P[i] / 1e3:.0f}' for i in order)} kN)")
    for i in range(len(x)):
        c.check_below(f"{study} {x[i]:g}: the column settled (kinetic / internal energy when the push starts)",
                      t["settle.final_kinetic_energy_J"][i] / t["settle.internal_energy_J"][i], 1e-3)
c.finish()
