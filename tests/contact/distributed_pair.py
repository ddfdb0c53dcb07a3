"""Contact between two meshes, evaluated where the slave nodes are owned:
np = 2, 3 and 4 against np = 1 (tests/contact/distributed_pair.prm and
tests/contact/perforation.prm).

A steel block (14 x 14 x 4 elements) slides at (3, 1, -20) m/s onto a
larger, coarser one (6 x 6 x 3), off-centre, with Coulomb friction (mu_s =
0.3, mu_d = 0.2), and rebounds. A master node of the coarse face takes the
reactions of a dozen slave nodes, so a sum in another order would show. On two processes each block is a partition of its own:
every slave node's master segments come from the other rank (the halo),
and every reaction goes back. On three and four the contact faces
themselves are split, so a slave node's segments come from two ranks and
its reactions go to several.

Checks:
1. Every node's displacement and velocity at the end (the last frame, in
   double precision) are bitwise those of one process: largest
   difference 0.
2. The contact force history agrees to 1e-8 of its peak (the pair's sums
   are added over the ranks; the motion does not depend on them).
3. No external force acts: the total momentum stays that of the start,
   to 1e-12 of its magnitude (the slave's force and the reactions on the
   master nodes, by the segment's shape functions, cancel).
4. On two or more processes touches crossed partitions (the halo was in
   use), and the contact force rose above 50 MN (the blocks met).
5. A steel bar (4 x 4 x 10 elements) strikes a 4 mm steel plate (16 x 16
   x 2, edges held, failure and erosion at f_s = 0.12) at 600 m/s and
   perforates it: on three processes the same elements erode and every
   node's final displacement and velocity are bitwise those of one
   process (the eroded elements' faces leave the pair on every rank, and
   the halo sends the segments with them).
6. A run on three processes stopped at 0.2 ms, in contact, and resumed
   from its checkpoint at 0.1 ms to the end gives every history of the
   uninterrupted run byte for byte (the springs', friction's and partners'
   state of the own slave nodes is each rank's checkpoint; the halo and
   the search are made anew).
"""
import os
from anvil_test import Checker, arguments, max_relative_difference, read_csv, run_anvil, test_scene
from anvil_vtu import arrays, read_grid  # (anvil_test puts scripts/ on the path)

args = arguments()
c = Checker("contact between two meshes on 1-4 processes")

scene = test_scene(args, "tests/contact/distributed_pair.prm", "blocks")

runs = {}
for np in (1, 2, 3, 4):
    work = os.path.join(args.work_dir, f"np{np}")
    os.makedirs(work, exist_ok=True)
    code, out, err = run_anvil(args.anvil, scene, np=np, cwd=work)
    if not c.check_true(f"np = {np} exits 0", code == 0, err.strip()[-400:]):
        c.finish()
    runs[np] = os.path.join(work, "output", "blocks")


def summary(np):
    with open(os.path.join(runs[np], "summary.csv")) as fh:
        return dict(line.strip().split(",") for line in fh.readlines()[1:])


def final_state(np):
    """{node id: (displacement, velocity)} of the last frame, all pieces."""
    grid = read_grid(os.path.join(runs[np], "solution_0001.pvtu"))
    point = arrays(grid.GetPointData())
    return {int(i): tuple(u) + tuple(v)
            for i, u, v in zip(point["node_id"], point["displacement"], point["velocity"])}


reference = {name: read_csv(os.path.join(runs[1], name + ".csv")) for name in ("contact_press",)}
state = final_state(1)
for np in (2, 3, 4):
    other = final_state(np)
    worst = max(max(abs(a - b) for a, b in zip(state[i], other[i])) for i in state) \
        if set(other) == set(state) else float("inf")
    c.check_below(f"np = {np}: largest difference of a node's displacement or velocity at the end "
                  f"({len(state)} nodes)", worst, 0.0)
    c.check_below(f"np = {np}: contact force history, largest relative difference",
                  max_relative_difference(reference["contact_press"],
                                          read_csv(os.path.join(runs[np], "contact_press.csv"))), 1e-8)
    crossed = int(summary(np).get("contact_springs_across_partitions", "0"))
    c.check_true(f"np = {np}: touches crossed partitions ({crossed})", crossed > 0)

for np in (1, 4):
    m = read_csv(os.path.join(runs[np], "momentum.csv"))
    p0 = (m["px"][0] ** 2 + m["py"][0] ** 2 + m["pz"][0] ** 2) ** 0.5
    drift = max(((m["px"][i] - m["px"][0]) ** 2 + (m["py"][i] - m["py"][0]) ** 2
                 + (m["pz"][i] - m["pz"][0]) ** 2) ** 0.5 for i in range(len(m["px"])))
    c.check_below(f"np = {np}: change of the total momentum / its magnitude", drift / p0, 1e-12)
# Checkpoint and resume on three processes.
work = os.path.join(args.work_dir, "resume")
os.makedirs(work, exist_ok=True)
checkpoints = ["--set", "Simulation/Checkpoint interval=1e-4", "--set", "Simulation/Output interval=0"]
code, out, err = run_anvil(args.anvil, scene, np=3, cwd=work, extra_args=checkpoints + ["--set", "Simulation/Name=full"])
c.check_true("np = 3 with checkpoints exits 0", code == 0, err.strip()[-400:])
code, out, err = run_anvil(args.anvil, scene, np=3, cwd=work,
                           extra_args=checkpoints + ["--set", "Simulation/Name=cut", "--set", "Simulation/End time=2e-4"])
c.check_true("np = 3 stopped at 0.2 ms exits 0", code == 0, err.strip()[-400:])
code, out, err = run_anvil(args.anvil, scene, np=3, cwd=work,
                           extra_args=["--resume"] + checkpoints + ["--set", "Simulation/Name=cut"])
c.check_true("resumed on 3 processes from 0.1 ms", code == 0 and "resumed from the checkpoint at t = 0.0001" in out,
             (out + err).strip()[-400:])
differ = [n for n in ("contact_press.csv", "probe_a.csv", "probe_b.csv", "momentum.csv", "energy.csv")
          if open(os.path.join(work, "output", "full", n), "rb").read()
          != open(os.path.join(work, "output", "cut", n), "rb").read()]
c.check_true("resumed: five histories byte for byte those of the uninterrupted run", not differ, ", ".join(differ))

# A bar through an eroding plate, one and three processes.
perforation = test_scene(args, "tests/contact/perforation.prm", "perforation")
eroded = {}
for np in (1, 3):
    work = os.path.join(args.work_dir, f"perforation_np{np}")
    os.makedirs(work, exist_ok=True)
    code, out, err = run_anvil(args.anvil, perforation, np=np, cwd=work)
    if not c.check_true(f"perforation, np = {np} exits 0", code == 0, err.strip()[-400:]):
        c.finish()
    runs[f"perforation{np}"] = os.path.join(work, "output", "perforation")
    eroded[np] = sorted(read_csv(os.path.join(runs[f"perforation{np}"], "erosion.csv"))["element"])
c.check_true(f"perforation: the same {len(eroded[1])} elements erode on 1 and 3 processes",
             len(eroded[1]) > 10 and eroded[1] == eroded[3])
c.check_true("perforation: erosion.csv byte for byte the same on 1 and 3 processes (rows by element id)",
             open(os.path.join(runs["perforation1"], "erosion.csv"), "rb").read()
             == open(os.path.join(runs["perforation3"], "erosion.csv"), "rb").read())
state, other = final_state("perforation1"), final_state("perforation3")
worst = max(max(abs(a - b) for a, b in zip(state[i], other[i])) for i in state) \
    if set(other) == set(state) else float("inf")
c.check_below(f"perforation, np = 3: largest difference of a node's displacement or velocity at the end "
              f"({len(state)} nodes)", worst, 0.0)

peak = float(summary(1)["peak_contact_force_N"])
c.check_true(f"the blocks met: peak contact force {peak:.4g} N > 5e7 N", peak > 5e7)
c.finish()
