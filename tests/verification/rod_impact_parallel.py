"""The rod impact on two and three MPI processes gives the same histories as
on one. (Two processes split the scene exactly between the rods; three
split the rods themselves, so nodes are shared between partitions.)

Each process computes the forces of its owned and ghost elements and adds
them to its nodes in global element order; contact is evaluated on
replicated surface data in an order fixed by reference coordinates. The
trajectories are therefore bitwise identical; only reductions (the energy
sums) may differ by round-off. Limit: largest difference relative to each
column's magnitude below 1e-8.

The three-process run also prints its wall times (they change no result)
and the element loop's balance: one time per step and process, so the
steps counted equal the run's, and the processes' mean <= the slowest
process over the run <= the slowest process of each step, summed.
"""
import os
import re
from anvil_test import Checker, arguments, run_anvil, write_scene, read_csv, max_relative_difference

args = arguments()
scene = os.path.join(args.source_dir, "prm/elastic_rod_impact/elastic_rod_impact.prm")
c = Checker("rod impact: np=2 and np=3 against np=1")
results = {}
for np in (1, 2, 3):
    work = os.path.join(args.work_dir, f"np{np}")
    os.makedirs(work, exist_ok=True)
    prm = write_scene(os.path.join(work, "rods.prm"), include=scene, text="""
subsection Simulation
  set Output interval = 0
  set Print wall times = %s
end
""" % ("true" if np == 3 else "false"))
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=work)
    if not c.check_true(f"np={np} exits 0", code == 0, err.strip()[-400:]):
        c.finish()
    if np == 3:
        balance = re.search(r"element loop over (\d+) steps, wall time: the processes' mean ([0-9.]+) s; "
                            r"the slowest process over the run ([0-9.]+) s .*the slowest process of each "
                            r"step, summed, ([0-9.]+) s", out)
        done = re.search(r"done: (\d+) steps", out)
        if c.check_true("np=3 prints the element loop's balance", balance is not None and done is not None,
                        "" if balance and done else out.strip()[-400:]):
            steps, mean, whole, by_step = balance.groups()
            c.check_true(f"balance over the run's steps ({steps} of {done.group(1)})", steps == done.group(1))
            c.check_true(f"mean {mean} <= slowest over the run {whole} <= slowest by step {by_step}",
                         float(mean) <= float(whole) <= float(by_step))
    results[np] = os.path.join(work, "output/rods")

for name in ("energy.csv", "momentum.csv", "contact_impact.csv", "probe_face_a.csv",
             "probe_face_b.csv", "probe_centre_b.csv"):
    a = read_csv(os.path.join(results[1], name))
    for np in (2, 3):
        b = read_csv(os.path.join(results[np], name))
        c.check_below(f"np={np} {name}: largest relative difference", max_relative_difference(a, b), 1e-8)
c.finish()
