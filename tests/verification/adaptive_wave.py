"""A plane wave whose elements are refined and coarsened while it passes.

The scene is tests/verification/adaptive_wave.prm: the steel bar of
refinement_wave.prm (uniaxial strain, 20 mm elements) strikes a wall at
10 m/s; a massless marker runs with the wave front at c = sqrt(M / rho), and
every 7.5 us ('Simulation/Adapt interval') the bar's elements within 60 mm of
it are halved and those behind it joined again. Every round moves the
state onto the new mesh (interpolated motion, stresses and histories of the
parents or the children's means) and goes on from a checkpoint. In units of
the transit time T of the bar:
- the front, then the jump state (stress -rho c v, velocity 0) at the probes
  x = 0.26 m (0.36 T to 0.70 T) and x = 0.76 m (0.86 T to 1.20 T), within 2 %
  of the jump conditions;
- the state behind the front at x = 0.26 m until the release wave arrives
  (0.80 T to 1.70 T), where the rounds join the elements the front has left:
  its mean against that of 0.36 T to 0.70 T (the spurious reflection of the
  joins) below 1 % of the jump, its spread printed beside the uniform coarse
  mesh's;
- the energy balance closes within 5e-4 with the energy the rounds took out
  booked ('adaptation' in energy.csv), printed as a share of the initial
  energy beside what the balance would be without it;
- there were rounds that halved and rounds that joined elements;
- np = 2 gives np = 1's probe histories bit for bit.
"""
import math
import os
import re
from anvil_test import Checker, arguments, run_anvil, read_csv

args = arguments()
c = Checker("refinement during the run: a plane wave against the jump conditions")
rho, E, nu, v = 7850.0, 2e11, 0.3, 10.0
M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
cw = math.sqrt(M / rho)
T = 1.0 / cw
jump = -rho * cw * v
scene = os.path.join(args.source_dir, "tests/verification/adaptive_wave.prm")
print(f"  c = {cw:.1f} m/s, T = {1e6 * T:.2f} us, jump: stress {1e-6 * jump:.2f} MPa, velocity 0")

runs = {}
for name, np, extra in (("adaptive", 1, []), ("adaptive_np2", 2, []),
                        ("uniform", 1, ["--set", "Simulation/Adapt interval=0",
                                        "--set", "Body bar/Refinement region/Levels=0"])):
    cwd = os.path.join(args.work_dir, name)
    os.makedirs(cwd, exist_ok=True)
    code, out, err = run_anvil(args.anvil, scene, np=np, cwd=cwd, extra_args=extra)
    if not c.check_true(f"{name} runs to its end", code == 0, (out + err).strip()[-400:]):
        c.finish()
    d = os.path.join(cwd, "output", "adaptive_wave")
    runs[name] = {p: read_csv(os.path.join(d, f"probe_{p}.csv")) for p in ("fine", "coarse")}
    runs[name]["energy"] = read_csv(os.path.join(d, "energy.csv"))
    runs[name]["out"] = out
    runs[name]["files"] = {p: open(os.path.join(d, f"probe_{p}.csv")).read() for p in ("fine", "coarse")}


def window(probe, key, a, b):
    return [x for t, x in zip(probe["time"], probe[key]) if a * T <= t <= b * T]


def mean(probe, key, a, b):
    values = window(probe, key, a, b)
    return sum(values) / len(values)


measures = {}
for name in ("adaptive", "uniform"):
    fine, coarse = runs[name]["fine"], runs[name]["coarse"]
    behind = window(fine, "stress_xx", 0.80, 1.70)
    m = {
        "stress at 0.26 m": mean(fine, "stress_xx", 0.36, 0.70) / jump,
        "velocity at 0.26 m": mean(fine, "vx", 0.36, 0.70) / v,
        "stress at 0.76 m": mean(coarse, "stress_xx", 0.86, 1.20) / jump,
        "velocity at 0.76 m": mean(coarse, "vx", 0.86, 1.20) / v,
        "reflection of the joins": (mean(fine, "stress_xx", 0.80, 1.70) - mean(fine, "stress_xx", 0.36, 0.70)) / jump,
        "spread behind the front": (max(behind) - min(behind)) / abs(jump),
        "balance": max(runs[name]["energy"]["balance_error"]),
    }
    measures[name] = m
    print(f"  {name}: " + ", ".join(f"{k} {x:+.4f}" for k, x in m.items()))

m = measures["adaptive"]
c.check("stress behind the front at 0.26 m (/ -rho c v)", m["stress at 0.26 m"], 1.0, 0.02)
c.check("particle velocity behind the front at 0.26 m (/ v)", m["velocity at 0.26 m"], 0.0, 0.02)
c.check("stress behind the front at 0.76 m (/ -rho c v)", m["stress at 0.76 m"], 1.0, 0.02)
c.check("particle velocity behind the front at 0.76 m (/ v)", m["velocity at 0.76 m"], 0.0, 0.02)
c.check("spurious reflection of the joins behind the front (/ jump)", m["reflection of the joins"], 0.0, 0.01)

energy = runs["adaptive"]["energy"]
e0 = energy["total"][0]
booked = energy["adaptation"][-1]
unbooked = max(abs(t - b - e0 - w) / e0 for t, b, w in
               zip(energy["total"], energy["adaptation"], energy["external_work"]))
print(f"  energy the rounds took out: {booked:.4e} J ({booked / e0:.2e} of the initial energy); "
      f"the balance without it would reach {unbooked:.2e}")
c.check_below("energy balance error, the rounds' energy booked", m["balance"], 5e-4)

out = runs["adaptive"]["out"]
rounds = re.findall(r"adapt at t = \S+ s, step \d+: (\d+) element\(s\) halved, (\d+) group", out)
halved = sum(int(a) for a, b in rounds)
joined = sum(int(b) for a, b in rounds)
print(f"  {len(rounds)} rounds: {halved} elements halved, {joined} groups of eight joined")
c.check_true("rounds that halved and rounds that joined elements", len(rounds) >= 10 and halved > 0 and joined > 0,
             f"{len(rounds)} rounds, {halved} halved, {joined} joined")

same = all(runs["adaptive"]["files"][p] == runs["adaptive_np2"]["files"][p] for p in ("fine", "coarse"))
c.check_true("np = 2 writes np = 1's probe histories byte for byte", same)
c.finish()
