"""Partitioning anew during the run ('Rebalance interval'): the trajectory
does not depend on it, bit for bit.

With 'Rebalance threshold = 1' and 'Rebalance when it pays = false' every
check partitions anew (no two processes ever spend exactly the same time),
each element weighed by its
group's measured time per element on its process; the run goes on from a
checkpoint on the new partition. Checked:
1. The coarse RC column (concrete damaged plasticity, bond-slip bars, the
   rigid hammer with friction) to 12 ms on two processes, a check every
   2 ms: five new partitions (their elements per process printed); every
   history of nodes,
   contact, bars and hammer byte for byte the run without rebalancing;
   energy.csv and momentum.csv, sums over the processes' shares, to 1e-9
   of each value (or of 1 J, 1 kg m/s); every node's displacement and
   velocity in the last frame bitwise.
2. Two blocks in frictional contact (the pair's halo between the ranks) on
   three processes against one: every node's final displacement and
   velocity bitwise.
3. A bar perforating an eroding plate on three processes against one: the
   same elements erode (erosion.csv byte for byte) and the final state is
   bitwise.
4. A threshold no run reaches partitions nothing (no rebalance line), and
   on one process there is nothing to balance.
"""
import os
from anvil_test import Checker, arguments, run_anvil, test_scene
from anvil_vtu import arrays, read_grid  # (anvil_test puts scripts/ on the path)

args = arguments()
c = Checker("partitioning anew during the run")
column = os.path.join(os.path.abspath(args.source_dir), "prm", "rc_column_impact", "rc_column_impact_coarse.prm")
column_end = ["--set", "Simulation/End time=0.012", "--set", "Simulation/Output interval=0.006"]


def rebalancing(interval, threshold=1.0):
    return ["--set", f"Simulation/Rebalance interval={interval}", "--set", f"Simulation/Rebalance threshold={threshold}",
            "--set", "Simulation/Rebalance when it pays=false"]


def run(scene, name, np, extra=()):
    work = os.path.join(args.work_dir, name)
    os.makedirs(work, exist_ok=True)
    code, out, err = run_anvil(args.anvil, scene, np=np, cwd=work,
                               extra_args=list(extra) + ["--set", f"Simulation/Name={name}"])
    c.check_true(f"{name}: {np} process(es), exits 0", code == 0, err.strip()[-400:])
    return os.path.join(work, "output", name), out


def final_state(directory):
    """{node id: displacement and velocity} of the last frame, all pieces."""
    frames = sorted(n for n in os.listdir(directory) if n.startswith("solution_") and n.endswith(".pvtu"))
    point = arrays(read_grid(os.path.join(directory, frames[-1])).GetPointData())
    return {int(i): tuple(u) + tuple(v)
            for i, u, v in zip(point["node_id"], point["displacement"], point["velocity"])}


def same_state(label, a, b):
    sa, sb = final_state(a), final_state(b)
    worst = max(max(abs(x - y) for x, y in zip(sa[i], sb[i])) for i in sa) if set(sa) == set(sb) else float("inf")
    c.check_below(f"{label}: largest difference of a node's displacement or velocity in the last frame "
                  f"({len(sa)} nodes)", worst, 0.0)


def largest_difference(x, y):
    """Largest difference of two CSV files' numbers, relative to each value
    (or to 1); infinity where their rows or columns differ."""
    rx, ry = open(x).read().splitlines(), open(y).read().splitlines()
    if len(rx) != len(ry) or rx[:1] != ry[:1]:
        return float("inf")
    worst = 0.0
    for a, b in zip(rx[1:], ry[1:]):
        for u, v in zip(a.split(","), b.split(",")):
            worst = max(worst, abs(float(u) - float(v)) / max(1.0, abs(float(u))))
    return worst


# 1. The column on two processes.
plain, _ = run(column, "column", 2, column_end)
moved, out = run(column, "column_rebalanced", 2, column_end + rebalancing(0.002))
lines = [l for l in out.splitlines() if "rebalance at t =" in l]
counts = [l.split("elements per process:")[1].strip(" )") for l in out.splitlines() if "elements per process:" in l]
print("  elements per process after each rebalance: " + "; ".join(counts))
c.check_true(f"column: {len(lines)} new partitions of 5 checks", len(lines) == 5 and len(counts) == 5)
histories = sorted(n for n in os.listdir(plain) if n.endswith(".csv") and n != "summary.csv")
sums = ("energy.csv", "momentum.csv")
differ = [n for n in histories if n not in sums and
          open(os.path.join(plain, n), "rb").read() != open(os.path.join(moved, n), "rb").read()]
c.check_true(f"column: {len(histories) - len(sums)} histories byte for byte those of the run without rebalancing",
             not differ and len(histories) >= 8, ", ".join(differ))
for n in sums:
    c.check_below(f"column: {n}, largest relative difference", largest_difference(os.path.join(plain, n),
                                                                               os.path.join(moved, n)), 1e-9)
same_state("column", plain, moved)

# 2. Two blocks in contact, three processes against one.
blocks = test_scene(args, "tests/contact/distributed_pair.prm", "blocks")
one, _ = run(blocks, "blocks_np1", 1)
three, out = run(blocks, "blocks_np3", 3, rebalancing(5e-5))
c.check_true("blocks: partitioned anew on three processes", "rebalance at t =" in out)
same_state("blocks, np = 3 rebalanced against np = 1", one, three)

# 3. Perforation with erosion, three processes against one.
plate = test_scene(args, "tests/contact/perforation.prm", "perforation")
one, _ = run(plate, "perforation_np1", 1)
three, out = run(plate, "perforation_np3", 3, rebalancing(2e-5))
c.check_true("perforation: partitioned anew on three processes", "rebalance at t =" in out)
c.check_true("perforation: erosion.csv byte for byte that of one process",
             open(os.path.join(one, "erosion.csv"), "rb").read() == open(os.path.join(three, "erosion.csv"), "rb").read()
             and len(open(os.path.join(one, "erosion.csv")).read().splitlines()) > 10)
same_state("perforation, np = 3 rebalanced against np = 1", one, three)

# 4. Only when asked and needed.
_, out = run(column, "column_balanced", 2, column_end + rebalancing(0.002, 1e6))
c.check_true("a threshold no run reaches: no new partition", "rebalance at t =" not in out)
_, out = run(blocks, "blocks_np1_asked", 1, rebalancing(5e-5))
c.check_true("one process: nothing to balance", "rebalance at t =" not in out)
c.finish()
