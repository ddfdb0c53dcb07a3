#!/usr/bin/env python3
"""MPI traffic of a step, counted: bytes each rank sends and messages per
step on 1, 2, 4 and 8 processes, for the production column
(prm/rc_column_impact, 21,600 elements, one contact pair, bars) and a
10^5-element block pressed on another (one contact pair of 2 x 40 x 40
faces). More processes than cores is fine: this counts, it does not time.

    /usr/bin/python3 benchmarks/communication.py --anvil build/anvil

Each scene runs twice on each number of processes, to two end times, with
build/benchmarks/libanvil_mpi_counts.so preloaded (benchmarks/mpi_counts.cc,
a PMPI layer that counts what each rank sends); the difference of the
counts over the difference of the steps is the step's own traffic (setup
and the final output cancel). Point-to-point: messages and bytes (the
ghost layer of the partition: positions and velocities of the nodes of
ghost cells). Collectives: calls and the bytes each rank puts in
(reductions of energies and of the stable step, and the contact pairs'
gather of every pair node's position to every rank). Nothing is
asserted; doc/performance.md turns the figures into a scaling note.

With --efficiency it times instead: the blocks (pressed together, before
and in contact) and the column (the hammer's first milliseconds) on one
and two processes over the same steps (one process pinned to each core in
turn), and prints the two-process parallel efficiency against the faster
and against the slower core (--repeat N: the fastest of N runs each, in
turn). It also runs two one-process runs side by side, one on each core:
their step against the step alone is what the machine itself takes from
each process when both cores work (shared caches, memory bandwidth, or
two virtual cores on one physical one), so t_alone / t_side_by_side is the
ceiling of any code's two-process efficiency here, and t_side_by_side /
(2 t_two) what is left to the code (its communication, waiting and
imbalance).
"""
import argparse
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.abspath(os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(SOURCE, "tests"))

COLUMN = os.path.join(SOURCE, "prm", "rc_column_impact", "rc_column_impact.prm")


def blocks_scene(path):
    # benchmarks/pressed_blocks.prm: two steel blocks of 51,200 elements,
    # the upper one moving down at 1 m/s onto the lower.
    with open(path, "w") as fh:
        fh.write(f"include {os.path.join(HERE, 'pressed_blocks.prm')}\n")
    return path


def counts(anvil, lib, work, scene, name, np, end_time):
    prefix = os.path.join(work, f"{name}_np{np}_{end_time:g}")
    for r in range(np):
        if os.path.exists(f"{prefix}.{r}"):
            os.remove(f"{prefix}.{r}")
    cmd = ["mpirun", "--oversubscribe", "-np", str(np), "-x", f"ANVIL_MPI_COUNTS={prefix}",
           "-x", f"LD_PRELOAD={lib}", anvil, scene]
    for s in (f"Simulation/Name={name}_np{np}", f"Simulation/End time={end_time}", "Simulation/Output interval=0",
              "Simulation/History interval=1", "Simulation/Plots=false", "Simulation/Overwrite existing output=true",
              "Simulation/End kinetic energy fraction=0"):
        cmd += ["--set", s]
    r = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{name} on {np}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
    with open(os.path.join(work, "output", f"{name}_np{np}", "summary.csv")) as fh:
        summary = dict(l.strip().split(",") for l in fh.readlines()[1:])
    ranks = []
    for k in range(np):
        with open(f"{prefix}.{k}") as fh:
            ranks.append({l.split()[0]: float(l.split()[1]) for l in fh})
    return float(summary["steps"]), float(summary["elements"]), ranks


def wall_per_step(anvil, work, scene, name, np, end_times, core=None):
    """Wall time per step between two end times (setup and the final
    output cancel), from each run's summary.csv; on core @p core alone
    when given (taskset)."""
    points = []
    for end_time in end_times:
        run_name = f"{name}_time_np{np}_{end_time:g}" + ("" if core is None else f"_core{core}")
        cmd = ["mpirun", "--oversubscribe", "-np", str(np), anvil, scene]
        if core is not None:
            # (mpirun binds a lone rank to core 0 whatever taskset allows:
            # not binding leaves it to the cores taskset gives.)
            cmd = ["taskset", "-c", str(core)] + cmd[:1] + ["--bind-to", "none"] + cmd[1:]
        for s in (f"Simulation/Name={run_name}", f"Simulation/End time={end_time}",
                  "Simulation/Output interval=0", "Simulation/Plots=false",
                  "Simulation/Overwrite existing output=true", "Simulation/End kinetic energy fraction=0"):
            cmd += ["--set", s]
        r = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
        if r.returncode != 0:
            raise SystemExit(f"{name} on {np}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
        with open(os.path.join(work, "output", run_name, "summary.csv")) as fh:
            summary = dict(l.strip().split(",") for l in fh.readlines()[1:])
        points.append((float(summary["steps"]), float(summary["wall_time_s"]), float(summary["elements"])))
    (s1, w1, elements), (s2, w2, _) = points
    return (w2 - w1) / (s2 - s1), s2 - s1, elements


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--anvil", default=os.path.join(SOURCE, "build", "anvil"))
    p.add_argument("--library", default=None, help="libanvil_mpi_counts.so (default: next to anvil)")
    p.add_argument("--work-dir", default="output/communication")
    p.add_argument("--processes", default="1,2,4,8")
    p.add_argument("--scenes", default="column,column_in_contact,blocks",
                   help="which of column, column_in_contact, blocks")
    p.add_argument("--efficiency", action="store_true",
                   help="time the step instead of counting: wall time per step on one and two "
                        "processes and the two-process parallel efficiency (blocks and column)")
    p.add_argument("--repeat", type=int, default=1,
                   help="with --efficiency: time each scene this many times on one and on two "
                        "processes, in turn, and keep the fastest of each (these shared machines "
                        "run the same work up to 60 % slower for minutes at a time)")
    a = p.parse_args()
    anvil = os.path.abspath(a.anvil)
    lib = os.path.abspath(a.library or os.path.join(os.path.dirname(anvil), "benchmarks", "libanvil_mpi_counts.so"))
    work = os.path.abspath(a.work_dir)
    os.makedirs(work, exist_ok=True)
    # The column twice: before the hammer arrives, and in contact (the
    # contact pair's records grow with the nodes in contact).
    scenes = [("column", COLUMN, (1e-5, 5e-5)), ("column_in_contact", COLUMN, (1e-3, 1.04e-3)),
              ("blocks", blocks_scene(os.path.join(work, "blocks.prm")), (2e-5, 1e-4))]
    if a.efficiency:
        # Timed on this machine's two cores: each scene on one process
        # pinned to each core, and on two, in turn, over the same steps.
        # The host may run one core slower than the other for minutes (up
        # to 1.6 times, doc/performance.md), and a two-process run waits
        # for the rank on the slower one: efficiency t1 / (2 t2) against
        # the faster core's t1, and against the slower core's (what the
        # code gets out of two such cores).
        times = [("blocks", blocks_scene(os.path.join(work, "blocks.prm")), (1e-4, 6e-4)),
                 ("column", COLUMN, (1e-3, 5e-3))]
        print("| scene | elements | steps timed | one process on core 0 / core 1, ms / step "
              "| two processes, ms / step | efficiency against the faster core "
              "| against the slower core | two one-process runs side by side, ms / step "
              "| the machine's ceiling | the code's share |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
        for name, scene, ends in times:
            if name not in a.scenes.split(","):
                continue
            t1 = [1e300, 1e300]
            t2 = 1e300
            side = 1e300
            for _ in range(a.repeat):
                for core in (0, 1):
                    t, steps, elements = wall_per_step(anvil, work, scene, name, 1, ends, core)
                    t1[core] = min(t1[core], t)
                t2 = min(t2, wall_per_step(anvil, work, scene, name, 2, ends)[0])
                # The same one-process run on both cores at once (the slower
                # of the two: a two-process run waits for it).
                with ThreadPoolExecutor(2) as pool:
                    pair = list(pool.map(lambda core: wall_per_step(anvil, work, scene, name + "_side", 1,
                                                                    ends, core)[0], (0, 1)))
                side = min(side, max(pair))
            print(f"| {name} | {elements:.0f} | {steps:.0f} | {1e3 * t1[0]:.2f} / {1e3 * t1[1]:.2f} | "
                  f"{1e3 * t2:.2f} | {100 * min(t1) / (2 * t2):.0f} % | {100 * max(t1) / (2 * t2):.0f} % | "
                  f"{1e3 * side:.2f} | {100 * min(t1) / side:.0f} % | {100 * side / (2 * t2):.0f} % |",
                  flush=True)
        return
    print("| scene | processes | elements | steps counted | p2p messages / rank / step | p2p bytes / rank / step "
          "| collective calls / step | collective bytes / rank / step | largest rank's bytes / step |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, scene, (t1, t2) in scenes:
        if name not in a.scenes.split(","):
            continue
        for np in (int(x) for x in a.processes.split(",")):
            s1, elements, c1 = counts(anvil, lib, work, scene, name, np, t1)
            s2, _, c2 = counts(anvil, lib, work, scene, name, np, t2)
            steps = s2 - s1
            per = [{k: (r2[k] - r1[k]) / steps for k in r2} for r1, r2 in zip(c1, c2)]
            mean = lambda k: sum(r[k] for r in per) / np
            largest = max(r["p2p_bytes"] + r["collective_bytes"] for r in per)
            print(f"| {name} | {np} | {elements:.0f} | {steps:.0f} | {mean('p2p_messages'):.1f} | "
                  f"{mean('p2p_bytes'):.0f} | {mean('collective_calls'):.1f} | {mean('collective_bytes'):.0f} | "
                  f"{largest:.0f} |", flush=True)


if __name__ == "__main__":
    main()
