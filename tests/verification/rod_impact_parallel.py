"""The rod impact on two MPI processes gives the same histories as on one.

Partitioning changes only the order of floating-point sums at nodes shared
by partitions (and in reductions), so histories may differ by round-off
growth only: the largest difference, relative to each column's magnitude,
must stay below 1e-8. Contact is evaluated on replicated surface data in an
order fixed by reference coordinates, so it does not depend on the
partition.
"""
import os
from anvil_test import Checker, arguments, run_anvil, write_scene, read_csv, max_relative_difference

args = arguments()
scene = os.path.join(args.source_dir, "prm/elastic_rod_impact/elastic_rod_impact.prm")
c = Checker("rod impact: np=2 against np=1")
results = {}
for np in (1, 2):
    work = os.path.join(args.work_dir, f"np{np}")
    os.makedirs(work, exist_ok=True)
    prm = write_scene(os.path.join(work, "rods.prm"), include=scene, text="""
subsection Simulation
  set Output interval = 0
  set Print wall times = false
end
""")
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=work)
    if not c.check_true(f"np={np} exits 0", code == 0, err.strip()[-400:]):
        c.finish()
    results[np] = os.path.join(work, "output/rods")

for name in ("energy.csv", "momentum.csv", "contact_impact.csv", "probe_face_a.csv",
             "probe_face_b.csv", "probe_centre_b.csv"):
    a = read_csv(os.path.join(results[1], name))
    b = read_csv(os.path.join(results[2], name))
    c.check_below(f"{name}: largest relative difference", max_relative_difference(a, b), 1e-8)
c.finish()
