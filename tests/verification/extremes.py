"""Stability at the extremes: each case is accurate, or it stops with one
located message (exit 3, time, step, element, position). doc/accuracy.md
("Stability at the extremes") tabulates what this test prints.

On the rod impact of prm/elastic_rod_impact (bar theory: contact force
rho c A v0 / 2 for 2 L / c, c = sqrt(E / rho) = 100 m/s):
- Poisson's ratio 0.4999: one-point elements do not lock (the force stays
  bar theory's within 3 %) and the step follows the dilatational wave
  speed (steps against sqrt((lambda + 2 mu) / rho) of nu = 0.3, within
  10 %); full integration locks (printed, not accurate: 2x2x2 points
  hold the volume of each element);
- impact speeds 10 and 100 times the shipped 1 m/s: 10 m/s (strain 5 %)
  runs with bar theory's force within 5 %; 100 m/s (the impact speed
  equals the wave speed: the struck ends are crushed flat) runs or stops
  with one located line;
- element aspect ratio 20 (1 m long, 0.05 m across): force within 5 %;
- hourglass coefficient 0 and 0.3: force within 3 %;
- penalty factor 1 and 10: force and duration within 3 %, the springs
  set the step.
On a block fixed on one face (the exact stable step of its mesh is min
L_e / c):
- time-step safety factor 1.05: stops with one located line;
- an element driven to inversion (30 m/s into its held face, the step
  ratio check off): stops naming the inverted element;
- 10^6 steps of elastic ringing (total Lagrangian, 8 fully integrated
  elements, nothing dissipates): the energy at each 10^5 steps stays
  within 3 % of the start (the leapfrog's bounded error at 0.9 of the
  stable step), with no trend (the step is held while the ringing moves
  the stable step by less than 1 %: a step that follows it pumps energy
  into the ringing).
Contact of very different bodies: a steel cube of 2 mm elements dropped
at 5 m/s on a block of soft concrete (E = 3 GPa, 70 times softer) of
20 mm elements: balance below 1 %, the cube's deepest point stays within
a quarter of a slab element of the face, penetration ratio below 0.5.
"""
import math
import os
import re
from anvil_test import Checker, arguments, run_anvil, test_scene, write_scene, read_csv

args = arguments()
c = Checker("stability at the extremes")
work = args.work_dir
rod = os.path.join(os.path.abspath(args.source_dir), "prm", "elastic_rod_impact", "elastic_rod_impact.prm")
located = ("numerical failure at t =", "step", "element", "near (")


def stopped_clearly(err):
    lines = [l for l in err.splitlines() if l.strip()]
    return len(lines) == 1 and lines[0].startswith("anvil: error:") and all(k in lines[0] for k in located)


def both(body_text):
    return "".join(f"subsection Body {b}\n{body_text}end\n" for b in ("rod_a", "rod_b"))


# The nearly incompressible rods take 36 times the steps: 2 x 2 elements
# across (bar theory holds for either) and to 0.22 s, past the contact.
slim = both("""  subsection Mesh
    set Subdivisions = 80, 2, 2
  end
""") + "subsection Simulation\n  set End time = 0.22\nend\n"


def run_rod(name, text, v0=1.0):
    prm = write_scene(os.path.join(work, name + ".prm"), include=rod, text="""
subsection Simulation
  set Output interval = 0
  set Print wall times = false
  set Plots = false
end
""" + text)
    code, out, err = run_anvil(args.anvil, prm, cwd=work)
    result = dict(code=code, err=err.strip())
    if code != 0:
        return result
    d = os.path.join(work, "output", name)
    contact = read_csv(os.path.join(d, "contact_impact.csv"))
    e = read_csv(os.path.join(d, "energy.csv"))
    s = read_csv(os.path.join(d, "summary.csv"))
    s = dict(zip(s["quantity"], s["value"]))
    t, force = contact["time"], [-f for f in contact["normal_force_x"]]
    exact = 0.01 * 100.0 * 1.0 * v0 / 2
    plateau = [f for ti, f in zip(t, force) if 0.03 <= ti <= 0.17]
    above = [ti for ti, f in zip(t, force) if f >= 0.5 * exact]
    result.update(force=sum(plateau) / len(plateau) / exact, duration=(above[-1] - above[0]) / 0.2 if above else 0,
                  balance=max(e["balance_error"]), steps=s["steps"],
                  hourglass=s["max_hourglass_to_internal"], contact_steps=s["contact_limited_steps"])
    return result


def report(name, r):
    if r["code"] == 0:
        print(f"  {name}: force / bar theory {r['force']:.4f}, duration / 2L/c {r['duration']:.4f}, "
              f"steps {r['steps']:.0f}, balance {r['balance']:.2e}, hourglass / internal {r['hourglass']:.3f}")
    else:
        print(f"  {name}: exit {r['code']}: {r['err'][-300:]}")


base = run_rod("base", "")
report("shipped rod (nu = 0.3)", base)
base_slim = run_rod("base_slim", slim)
report("shipped rod, 2 x 2 across, to 0.22 s (nu = 0.3)", base_slim)

# Poisson's ratio 0.4999.
incompressible = run_rod("nu4999", slim + both("""  subsection Material
    subsection elastic
      set Poisson's ratio = 0.4999
    end
  end
"""))
report("nu = 0.4999, one point", incompressible)
if c.check_true("nu = 0.4999, one point: runs", incompressible["code"] == 0, incompressible["err"][-300:]):
    c.check("nu = 0.4999, one point: contact force / bar theory (no locking)", incompressible["force"], 1.0, 0.03)
    wave = lambda nu: math.sqrt((1 - nu) / ((1 + nu) * (1 - 2 * nu)))
    c.check("nu = 0.4999: steps / steps at 0.3 against the dilatational wave speeds' ratio",
            incompressible["steps"] / base_slim["steps"] / (wave(0.4999) / wave(0.3)), 1.0, 0.10)
    c.check_below("nu = 0.4999, one point: energy balance error", incompressible["balance"], 0.01)
locked = run_rod("nu4999_full", slim + both("""  set Integration = full
  subsection Material
    subsection elastic
      set Poisson's ratio = 0.4999
    end
  end
"""))
report("nu = 0.4999, full integration", locked)
c.check_true("nu = 0.4999, full integration: runs (stable; its force shows the volumetric locking)",
             locked["code"] == 0 and locked["balance"] < 0.01, locked["err"][-300:])

# Impact speeds 10 and 100 times the shipped one.
fast = run_rod("v10", "subsection Body rod_a\n  set Initial velocity = 10, 0, 0\nend\n", v0=10.0)
report("v0 = 10 m/s", fast)
if c.check_true("v0 = 10 m/s: runs", fast["code"] == 0, fast["err"][-300:]):
    c.check("v0 = 10 m/s: contact force / bar theory", fast["force"], 1.0, 0.05)
    c.check_below("v0 = 10 m/s: energy balance error", fast["balance"], 0.01)
faster = run_rod("v100", "subsection Body rod_a\n  set Initial velocity = 100, 0, 0\nend\n", v0=100.0)
report("v0 = 100 m/s", faster)
# (The rods passing through each other keep a closed balance: running is
# accepted only if the contact acted.)
c.check_true("v0 = 100 m/s (the wave speed): runs with the contact acting and a closed balance, or stops "
             "with one located line that says the rods passed through each other",
             (faster["code"] == 0 and faster["balance"] < 0.05 and faster["force"] > 0.5) or
             (faster["code"] == 3 and stopped_clearly(faster["err"]) and "passed through" in faster["err"]),
             faster["err"][-300:])

# Element aspect ratio 20.
aspect = run_rod("aspect20", """subsection Body rod_a
  subsection Mesh
    set Subdivisions = 200, 1, 1
  end
end
subsection Body rod_b
  subsection Mesh
    set Subdivisions = 200, 1, 1
  end
end
""")
report("aspect ratio 20", aspect)
if c.check_true("aspect ratio 20: runs", aspect["code"] == 0, aspect["err"][-300:]):
    c.check("aspect ratio 20: contact force / bar theory", aspect["force"], 1.0, 0.05)
    c.check("aspect ratio 20: contact duration / 2L/c", aspect["duration"], 1.0, 0.05)

# Hourglass coefficient 0 and 0.3.
for q in (0.0, 0.3):
    r = run_rod(f"hourglass{q:g}", both(f"""  subsection Hourglass control
    set Coefficient = {q}
  end
"""))
    report(f"hourglass coefficient {q:g}", r)
    if c.check_true(f"hourglass coefficient {q:g}: runs", r["code"] == 0, r["err"][-300:]):
        c.check(f"hourglass coefficient {q:g}: contact force / bar theory", r["force"], 1.0, 0.03)
        c.check_below(f"hourglass coefficient {q:g}: energy balance error", r["balance"], 0.01)

# Penalty factor 1 and 10.
for f in (1, 10):
    r = run_rod(f"penalty{f}", f"subsection Contact pair impact\n  set Penalty scale factor = {f}\nend\n")
    report(f"penalty factor {f}", r)
    if r["code"] == 3 and f == 10:
        # (The springs' bound and the elements' are combined as
        # omega^2 = omega_e^2 + omega_c^2; at this stiffness the face
        # elements' L_e / c is not quite a bound: doc/accuracy.md.)
        c.check_true(f"penalty factor {f}: accurate, or stopped with one located line", stopped_clearly(r["err"]),
                     r["err"][-200:])
        continue
    if c.check_true(f"penalty factor {f}: runs", r["code"] == 0, r["err"][-300:]):
        c.check(f"penalty factor {f}: contact force / bar theory", r["force"], 1.0, 0.03)
        c.check(f"penalty factor {f}: contact duration / 2L/c", r["duration"], 1.0, 0.03)
        print(f"    steps {r['steps']:.0f} against {base['steps']:.0f} at 0.1; the springs set "
              f"{r['contact_steps']:.0f} of them")

# The block of tests/verification/stability.prm.
def block(name, end, factor, history, n, velocity, formulation="updated Lagrangian", **more):
    return test_scene(args, "tests/verification/stability.prm", name,
                      {"Simulation/End time": end, "Simulation/Time step safety factor": factor,
                       "Simulation/History interval": history, "Body block/Mesh/Subdivisions": f"{n}, {n}, {n}",
                       "Body block/Initial velocity": velocity, "Body block/Formulation": formulation, **more})


prm = block("factor105", 13, 1.05, 0, 6, "1, 0.5, 0")
code, out, err = run_anvil(args.anvil, prm, cwd=work)
print("  time-step factor 1.05:", err.strip()[-300:])
c.check_true("time-step factor 1.05: stops with exit 3 and one located line naming the instability",
             code == 3 and stopped_clearly(err) and "unstable" in err, f"exit {code}")

prm = block("inversion", 0.2, 0.9, 0, 6, "-90, 0, 0", **{"Simulation/Minimum time step ratio": 0})
code, out, err = run_anvil(args.anvil, prm, cwd=work)
print("  driven to inversion:", err.strip()[-300:])
c.check_true("element driven to inversion: stops with exit 3 and one located line that says an element "
             "inverts or collapses", code == 3 and stopped_clearly(err) and
             ("inverted" in err or "collapsing" in err), f"exit {code}")

# 10^6 steps of elastic ringing: full integration (no hourglass control),
# no bulk viscosity, total Lagrangian (hyperelastic): nothing dissipates.
prm = block("million", 1e9, 0.9, 0.5, 2, "1, 0.5, 0", "total Lagrangian",
            **{"Simulation/Maximum number of steps": 1000000, "Simulation/Progress interval": 0,
               "Body block/Integration": "full", "Body block/Bulk viscosity/Linear coefficient": 0,
               "Body block/Bulk viscosity/Quadratic coefficient": 0})
# (Maximum number of steps stops the run with exit 3 at 10^6 steps: the
# end time is out of reach on purpose.)
code, out, err = run_anvil(args.anvil, prm, cwd=work)
e = read_csv(os.path.join(work, "output", "million", "energy.csv"))
m = re.search(r"reached 'Maximum number of steps' = (\d+)", err)
c.check_true("10^6 steps: the run reaches its step limit", code == 3 and m is not None and m.group(1) == "1000000",
             err.strip()[-200:])
# The histories reach the stop: their rows are flushed before the run stops
# (they wait in memory for up to a second otherwise).
stop = re.search(r"at t = ([0-9.e+-]+) s", err)
c.check_below("10^6 steps: time of the stop - last row of energy.csv, over the history interval 0.5 s",
              (float(stop.group(1)) - e["time"][-1]) / 0.5 if stop else float("inf"), 1.0)
# The held face stops at the first step (the reaction's work is external);
# from then on total - external work is the block's energy.
level = [t - w for t, w in zip(e["total"], e["external_work"])]
e1 = level[1]
drifts = []
for k in range(1, 11):
    row = min(range(len(e["time"])), key=lambda i: abs(e["time"][i] - e["time"][-1] * k / 10))
    drifts.append((level[row] - e1) / e1)
print("  10^6 steps: energy drift at each 10^5 steps: " + ", ".join(f"{d:+.1e}" for d in drifts))
c.check_below("10^6 steps: largest energy excursion at the 10^5-step marks (relative to the block's energy)",
              max(abs(d) for d in drifts), 0.03)
c.check_below("10^6 steps: no trend (mean of the last five marks minus that of the first five)",
              abs(sum(drifts[5:]) - sum(drifts[:5])) / 5, 0.01)

# Stiff on soft, fine on coarse.
prm = test_scene(args, "tests/verification/stiff_on_soft.prm", "stiff_on_soft")

code, out, err = run_anvil(args.anvil, prm, cwd=work)
if c.check_true("steel on soft concrete, 1:10 elements: runs", code == 0, err.strip()[-300:]):
    d = os.path.join(work, "output", "stiff_on_soft")
    e = read_csv(os.path.join(d, "energy.csv"))
    b = read_csv(os.path.join(d, "bodies.csv"))
    k = read_csv(os.path.join(d, "contact_drop.csv"))
    c.check_below("steel on soft concrete: energy balance error", max(e["balance_error"]), 0.01)
    c.check_true("steel on soft concrete: the cube was stopped and pushed back (contact force acted)",
                 max(abs(f) for f in k["normal_force_z"]) > 0)
    zmin = b["zmin"][b["body"].index("cube")]
    c.check_below("steel on soft concrete: deepest point of the cube below the slab's reference face, "
                  "as a fraction of a slab element (20 mm)", -zmin / 0.02, 0.25)
    c.check_below("steel on soft concrete: largest penetration ratio", max(k["max_penetration_ratio"]), 0.5)
c.finish()
