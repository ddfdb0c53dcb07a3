#!/usr/bin/env python3
"""The partitioners side by side: 'Partitioner = hierarchical | metis | zoltan |
metis per kind' on the production column (prm/rc_column_impact, 21,600
elements).

For each partitioner and 2, 4 and 8 processes (more than the cores is fine:
these count), a run of a few steps prints the ghost layer all processes hold
(summary.csv: ghost_elements, the elements computed twice or more;
ghost_dofs, the nodal entries exchanged every step). On 2 processes a run to
END_TIME_S (default 5 ms: the hammer's first milliseconds) is timed: wall
time and the element loop's imbalance (from the log: the slowest process
over the run, the partition's share, and the slowest process of each step
summed, which adds the work moving between the processes), and the fully
integrated elements each process holds. Figures only; compare within one run.

    /usr/bin/python3 benchmarks/partitioners.py ANVIL [END_TIME_S]
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

if len(sys.argv) < 2 or sys.argv[1].startswith("-") or not os.access(sys.argv[1], os.X_OK):
    sys.exit(f"usage: python3 {sys.argv[0]} ANVIL [options in its docstring] (ANVIL: the anvil executable, "
             f"build/anvil; got {sys.argv[1]!r})" if len(sys.argv) > 1 else
             f"usage: python3 {sys.argv[0]} ANVIL [options in its docstring] (ANVIL: the anvil executable, "
             f"build/anvil)")
anvil = os.path.abspath(sys.argv[1])
end_time = float(sys.argv[2]) if len(sys.argv) > 2 else 0.005
top = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
scene = os.path.join(top, "prm", "rc_column_impact", "rc_column_impact.prm")
work = tempfile.mkdtemp()
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run(name, np, partitioner, end, wall_times=False):
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(f"""include {scene}
subsection Simulation
  set Partitioner = {partitioner}
  set End time = {end!r}
  set End kinetic energy fraction = 0
  set Output interval = 0
  set Plots = false
  set Print wall times = {'true' if wall_times else 'false'}
end
""")
    r = subprocess.run(["mpirun", "-np", str(np), "--oversubscribe", anvil, prm], cwd=work, env=env,
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{name}: anvil failed: {(r.stderr or r.stdout).strip()[-300:]}")
    with open(os.path.join(work, "output", name, "summary.csv")) as f:
        s = {row["quantity"]: float(row["value"]) for row in csv.DictReader(f)}
    m = re.search(r"slowest process over the run [\d.e+-]+ s \(\+([\d.-]+) %.*each step, summed, [\d.e+-]+ s "
                  r"\(\+([\d.-]+) %", r.stdout)
    full = re.search(r"fully integrated .*\(per process: ([\d, ]+)\)", r.stdout)
    return s, ((m.group(1), m.group(2)) if m else ("?", "?")), (full.group(1) if full else "?")


print(f"partitioners on the production column ({end_time * 1e3:g} ms timed on 2 processes)")
for partitioner in ("hierarchical", "metis", "zoltan", "metis per kind"):
    counts = []
    tag = partitioner.replace(" ", "_")
    for np in (2, 4, 8):
        s, _, _ = run(f"{tag}_np{np}", np, partitioner, 2e-5)
        counts.append(f"np = {np}: {int(s['ghost_elements'])} ghost elements, {int(s['ghost_dofs'])} ghost dofs")
    s, (whole, by_step), full = run(f"{tag}_timed", 2, partitioner, end_time, wall_times=True)
    print(f"  {partitioner}: " + "; ".join(counts) + f"; timed on 2: {s['wall_time_s']:.1f} s wall, "
          f"{int(s['steps'])} steps, fully integrated elements per process {full}, element loop's slowest "
          f"process over the mean +{whole} % over the run, +{by_step} % step by step", flush=True)
