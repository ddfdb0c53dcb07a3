"""A boundary condition that follows a function of time ('Type = velocity
function'), on tests/verification/velocity_ramp.prm: a steel bar (nu = 0)
on its fixed foot, its top driven down by v(t) = 0.25 min(t / 1 ms, 1) m/s.

- The top's displacement against the integral of v, -0.25 t^2 / (2 ms)
  during the ramp and -0.25 (t - 0.5 ms) after it, at every row: the held
  nodes take v at each half step, whose sum is the midpoint rule, exact for
  the linear ramp and the constant (the kink at 1 ms costs O(dt^2)).
- The top's velocity at every row equals v(t) (the probes read the
  prescribed velocity of t^n).
- The force that holds the top against bar theory, rho c A v(t), until the
  reflection from the foot returns at 2 L / c = 0.396 ms (rows 0.1-0.35 ms).
- np = 2 gives np = 1's probe and reaction histories value for value, and
  its energies to round-off (the sums over the processes differ in order).
- A function with two components, or one that does not parse, stops with
  one line naming the entry and exit 2.
"""
import math
import os
from anvil_test import Checker, arguments, read_csv, run_anvil, write_scene

args = arguments()
c = Checker("boundary condition 'velocity function' (a ramp on a bar)")
src = os.path.abspath(args.source_dir)
scene = os.path.join(src, "tests", "verification", "velocity_ramp.prm")
out = {}
for np in (1, 2):
    prm = write_scene(os.path.join(args.work_dir, f"ramp_{np}.prm"), include=scene, text="")
    code, o, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"np = {np}: anvil exits 0", code == 0, err.strip()[-400:]):
        c.finish()
    out[np] = os.path.join(args.work_dir, "output", f"ramp_{np}")

p = read_csv(os.path.join(out[1], "probe_top.csv"))
ramp = 1e-3


def v(t):
    return -0.25 * min(t / ramp, 1.0)


def u(t):
    return -0.25 * t * t / (2 * ramp) if t <= ramp else -0.25 * (t - 0.5 * ramp)


worst_u = max(abs(uz - u(t)) for t, uz in zip(p["time"], p["uz"])) / abs(u(p["time"][-1]))
c.check_below("top displacement against the integral of v(t), largest error over its final value", worst_u, 1e-4)
worst_v = max(abs(vz - v(t)) for t, vz in zip(p["time"], p["vz"])) / 0.25
c.check_below("top velocity against v(t), largest error over 0.25 m/s (12 printed digits)", worst_v, 1e-10)

r = read_csv(os.path.join(out[1], "reactions.csv"))
rho, E, A = 7850.0, 2e11, 0.04
impedance = rho * math.sqrt(E / rho) * A
rows = [(t, f) for t, f in zip(r["time"], r["top_fz"]) if 1e-4 <= t <= 3.5e-4]
worst_f = max(abs(-f - impedance * abs(v(t))) / (impedance * abs(v(t))) for t, f in rows)
c.check_below(f"force holding the top against rho c A v(t), {len(rows)} rows of 0.1-0.35 ms, largest relative error",
              worst_f, 0.02)

for name in ("probe_top.csv", "reactions.csv"):
    a = read_csv(os.path.join(out[1], name))
    b = read_csv(os.path.join(out[2], name))
    c.check_true(f"np = 2 writes np = 1's {name} value for value", a == b)
a = read_csv(os.path.join(out[1], "energy.csv"))
b = read_csv(os.path.join(out[2], "energy.csv"))
c.check_below("np = 2 against np = 1, total energy (sums over the processes in another order)",
              max(abs(x - y) / max(abs(x), 1e-300) for x, y in zip(a["total"], b["total"]) if x != 0), 1e-12)
e = read_csv(os.path.join(out[1], "energy.csv"))
c.check_below("energy balance error at the end (work of the held top against kinetic + internal)",
              e["balance_error"][-1], 1e-4)

for text, what in (("0; -0.25 * t", "two components"), ("0; 0; -0.25 * min(t / 0.001", "an expression that does not parse")):
    prm = write_scene(os.path.join(args.work_dir, "bad.prm"), include=scene, text=f"""
subsection Boundary condition top
  set Velocity function = {text}
end
""")
    code, o, err = run_anvil(args.anvil, prm, np=1, cwd=args.work_dir)
    lines = [l for l in err.strip().splitlines() if l.startswith("anvil: error")]
    c.check_true(f"{what}: exit 2 and one line naming 'Velocity function'",
                 code == 2 and len(lines) == 1 and "Velocity function" in lines[0], err.strip()[-300:])
c.finish()
