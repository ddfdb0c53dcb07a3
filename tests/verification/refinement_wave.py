"""A plane wave across a 2:1 refinement interface, against the jump conditions.

The scene is tests/verification/refinement_wave.prm: a steel bar in uniaxial
strain strikes a wall at 10 m/s; its elements are halved in x < 0.5 m, so the
front crosses the interface fine to coarse, and the release wave from the free
end crosses it coarse to fine. The probe 'fine' (x = 0.26 m) and 'coarse'
(x = 0.76 m) see, in units of the transit time T of the bar (1 m):
- the front, then the jump state (stress -rho c v, velocity 0): 'coarse' from
  0.86 T to 1.20 T is the transmitted wave (within 2 % of the jump values);
- at 'fine', the interface's reflection of the front (arriving at 0.76 T): the
  mean stress from 0.80 T to 1.70 T less that from 0.36 T to 0.70 T, over the
  jump: the spurious reflection, printed, and held below 1 %;
- the release wave, back across the interface: 'fine' from 1.82 T to 2.20 T
  holds stress 0 and velocity +v (within 2 % of the jump); at 'coarse' the
  mean stress from 1.80 T to 2.6 T less that from 1.30 T to 1.70 T is its
  reflection, printed and held below 1 %.
The same measures on the uniform coarse mesh (the interface's absence) are
printed beside them. Also: the energy balance closes within 5e-4, and np = 2
gives np = 1's histories bit for bit, whether the elements are cut by kind
(the default), in the hierarchical order, by METIS or by Zoltan ('Partitioner'; the ghost layer of each
printed); with a 'Full integration region' (90 elements), np = 2 cut by
'metis per kind' gives np = 1's histories bit for bit and each process 45
(+-1) of the fully integrated elements (the hierarchical cut's share printed
beside it).
"""
import math
import os
import re
from anvil_test import Checker, arguments, run_anvil, read_csv

args = arguments()
c = Checker("refinement interface: a plane wave against the jump conditions")
rho, E, nu, v = 7850.0, 2e11, 0.3, 10.0
M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
cw = math.sqrt(M / rho)
T = 1.0 / cw
jump = -rho * cw * v
scene = os.path.join(args.source_dir, "tests/verification/refinement_wave.prm")
print(f"  c = {cw:.1f} m/s, T = {1e6 * T:.2f} us, jump: stress {1e-6 * jump:.2f} MPa, velocity 0")

# A 'Full integration region' over 0.3 m < x < 0.7 m: the 20 coarse
# elements with their centroid in it, 10 of them halved (80 + 10 = 90
# elements of the second kind).
full_region = ["--set", "Body bar/Full integration region/Lower corner=0.3, -1, -1",
               "--set", "Body bar/Full integration region/Upper corner=0.7, 1, 1"]
runs, logs = {}, {}
for name, np, extra in (("refined", 1, []), ("refined_np2", 2, []),
                        ("uniform", 1, ["--set", "Body bar/Refinement region/Levels=0"]),
                        ("metis_np2", 2, ["--set", "Simulation/Partitioner=metis"]),
                        ("hierarchical_np2", 2, ["--set", "Simulation/Partitioner=hierarchical"]),
                        ("zoltan_np2", 2, ["--set", "Simulation/Partitioner=zoltan"]),
                        ("full", 1, full_region),
                        ("kinds_np2", 2, full_region + ["--set", "Simulation/Partitioner=metis per kind"]),
                        ("full_np2", 2, full_region + ["--set", "Simulation/Partitioner=hierarchical"])):
    cwd = os.path.join(args.work_dir, name)
    os.makedirs(cwd, exist_ok=True)
    code, out, err = run_anvil(args.anvil, scene, np=np, cwd=cwd, extra_args=extra)
    if not c.check_true(f"{name} runs to its end", code == 0, err.strip()[-300:]):
        c.finish()
    d = os.path.join(cwd, "output", "refinement_wave")
    logs[name] = out
    runs[name] = {p: read_csv(os.path.join(d, f"probe_{p}.csv")) for p in ("fine", "coarse")}
    runs[name]["energy"] = read_csv(os.path.join(d, "energy.csv"))
    runs[name]["summary"] = {row[0]: row[1] for row in
                             (line.strip().split(",") for line in open(os.path.join(d, "summary.csv")))}


def mean(probe, key, a, b):
    values = [x for t, x in zip(probe["time"], probe[key]) if a * T <= t <= b * T]
    return sum(values) / len(values)


measures = {}
for name in ("refined", "uniform"):
    fine, coarse = runs[name]["fine"], runs[name]["coarse"]
    m = {
        "transmitted stress": mean(coarse, "stress_xx", 0.86, 1.20) / jump,
        "transmitted velocity": mean(coarse, "vx", 0.86, 1.20) / v,
        "reflection fine to coarse": (mean(fine, "stress_xx", 0.80, 1.70) - mean(fine, "stress_xx", 0.36, 0.70)) / jump,
        "release stress": mean(fine, "stress_xx", 1.82, 2.20) / jump,
        "release velocity": mean(fine, "vx", 1.82, 2.20) / v,
        "reflection coarse to fine": (mean(coarse, "stress_xx", 1.80, 2.60) - mean(coarse, "stress_xx", 1.30, 1.70)) / jump,
        "balance": max(runs[name]["energy"]["balance_error"]),
    }
    measures[name] = m
    print(f"  {name}: " + ", ".join(f"{k} {x:+.4f}" for k, x in m.items()))

m = measures["refined"]
c.check("transmitted stress behind the front (/ -rho c v)", m["transmitted stress"], 1.0, 0.02)
c.check("transmitted particle velocity behind the front (/ v)", m["transmitted velocity"], 0.0, 0.02)
c.check("stress behind the release wave, through the interface coarse to fine (/ rho c v)", m["release stress"], 0.0, 0.02)
c.check("particle velocity behind the release wave (/ v)", m["release velocity"], 1.0, 0.02)
c.check("spurious reflection of the front, fine to coarse (/ jump)", m["reflection fine to coarse"], 0.0, 0.01)
c.check("spurious reflection of the release wave, coarse to fine (/ jump)", m["reflection coarse to fine"], 0.0, 0.01)
c.check_below("energy balance error", m["balance"], 5e-4)

p1 = runs["refined"]
for name, what in (("refined_np2", "np = 2"), ("hierarchical_np2", "np = 2 cut in the hierarchical order"),
                   ("metis_np2", "np = 2 cut by METIS"),
                   ("zoltan_np2", "np = 2 cut by Zoltan")):
    p2 = runs[name]
    diff = max(abs(a - b) for p in ("fine", "coarse") for k in ("ux", "vx", "stress_xx")
               for a, b in zip(p1[p][k], p2[p][k]))
    print(f"  {what}: ghost elements {p2['summary']['ghost_elements']}, ghost dofs {p2['summary']['ghost_dofs']}")
    c.check(f"{what} against np = 1, probes (largest difference)", diff, 0.0, 0.0)

# 'Partitioner = metis per kind': each process an equal share of each kind
# of element; the default hierarchical cut, weighing a fully integrated
# element 15 one-point ones, gives the region's elements to the processes
# as they fall along the bar. The same histories bit for bit either way.
for name, what in (("kinds_np2", "'metis per kind'"), ("full_np2", "the hierarchical cut")):
    m = re.search(r"(\d+) element\(s\) fully integrated .*\(per process: (\d+), (\d+)\)", logs[name])
    shares = [int(m.group(2)), int(m.group(3))] if m else [-1, -1]
    print(f"  {what}, np = 2: fully integrated elements per process {shares[0]}, {shares[1]} of "
          f"{m.group(1) if m else '?'}")
    diff = max(abs(a - b) for p in ("fine", "coarse") for k in ("ux", "vx", "stress_xx")
               for a, b in zip(runs["full"][p][k], runs[name][p][k]))
    c.check(f"full integration region, np = 2 cut by {what} against np = 1, probes (largest difference)",
            diff, 0.0, 0.0)
    if name == "kinds_np2":
        c.check("'metis per kind': fully integrated elements on the first process, of 90", shares[0], 45, 1)
c.finish()
