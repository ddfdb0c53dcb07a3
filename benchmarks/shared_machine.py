#!/usr/bin/env python3
"""Two processes on a machine that has other work: the wall time of a scene
on one and on two processes, on a quiet machine and beside one busy
single-core job (a spinning process of its own), with Open MPI's waiting
ranks polling (mpi_yield_when_idle = 0, Open MPI's default, which Anvil
keeps) and yielding the core (1).

    /usr/bin/python3 benchmarks/shared_machine.py --anvil build/anvil [--scene S.prm] [--repeat N]
                                                  [--rebalance INTERVAL] [--nice N]

--rebalance: the two-process runs partition anew during the run
('Rebalance interval = INTERVAL', threshold 1.1), so that the process
sharing its core with the busy job gets fewer elements. --nice: the busy
job runs at that niceness (19: a low-priority job, as the performance
issue's was; 0, the default: a job of the same priority as the run).

Default scene: prm/rc_column_impact/rc_column_impact_coarse.prm to 5 ms
(--end-time; doc/performance.md quotes 12 ms).
Prints each run's wall time (the fastest of --repeat) and the ratios one
process / two processes; nothing is asserted. A speed-up below 1 beside
the busy job is the collapse the performance issue measured (two ranks
polling for each other while the busy job holds one of the two cores).
"""
import argparse
import multiprocessing
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def spin(stop, niceness=0):
    if niceness:
        os.nice(niceness)
    x = 0
    while not stop.is_set():
        x += 1


def run(anvil, scene, np, yield_when_idle, end_time, work, rebalance=None):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    env.pop("OMPI_MCA_mpi_yield_when_idle", None)
    if yield_when_idle is not None:
        env["OMPI_MCA_mpi_yield_when_idle"] = str(yield_when_idle)
    out = os.path.join(work, f"np{np}_y{yield_when_idle}_{time.time_ns()}")
    cmd = ["mpirun", "--bind-to", "none", "-np", str(np), anvil, scene,
           "--set", f"Simulation/Output directory={out}", "--set", f"Simulation/End time={end_time}",
           "--set", "Simulation/Output interval=0", "--set", "Simulation/Print wall times=false"] + \
        (["--set", f"Simulation/Rebalance interval={rebalance}"] if rebalance and np > 1 else [])
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=os.path.dirname(scene), env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"shared_machine: {' '.join(cmd)} failed: {r.stderr.strip()[-300:]}")
    return time.perf_counter() - t0


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--anvil", required=True)
    p.add_argument("--scene", default=os.path.join(HERE, "..", "prm", "rc_column_impact",
                                                   "rc_column_impact_coarse.prm"))
    p.add_argument("--end-time", default="0.005")
    p.add_argument("--repeat", type=int, default=1)
    p.add_argument("--rebalance", default=None)
    p.add_argument("--nice", type=int, default=0)
    a = p.parse_args()
    anvil, scene = os.path.abspath(a.anvil), os.path.abspath(a.scene)
    with tempfile.TemporaryDirectory() as work:
        for busy in (False, True):
            stop = multiprocessing.Event()
            spinner = multiprocessing.Process(target=spin, args=(stop, a.nice)) if busy else None
            if spinner:
                spinner.start()
            try:
                for y in (0, 1):
                    t = {np: min(run(anvil, scene, np, y, a.end_time, work, a.rebalance) for _ in range(a.repeat))
                         for np in (1, 2)}
                    print(f"{'beside a busy job' if busy else 'quiet machine':18s} yield_when_idle {y}: "
                          f"one process {t[1]:7.2f} s, two {t[2]:7.2f} s, speed-up {t[1] / t[2]:5.2f}",
                          flush=True)
            finally:
                if spinner:
                    stop.set()
                    spinner.join()


if __name__ == "__main__":
    main()
