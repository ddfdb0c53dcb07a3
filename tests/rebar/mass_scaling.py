"""Selective mass scaling of bond-slip bars ('Mass scaling time step').

The pull-out of prm/pull_out (a 16 mm steel bar of 10 mm elements in a
concrete block of 10 mm elements, pulled at 10 mm/s) to 5 ms:
- without scaling the bar sets the step: --print-cost's stable step is the
  bar's L / c = 0.01 / sqrt(2e11 / 7850) = 1.98 us (within 1 %);
- asked for 2.68 us, every element gets (f - 1) rho A L of added mass,
  f = (2.68e-6 c / L)^2: summary.csv's bar_added_mass_kg equals the sum
  (relative 1e-9), and the bar no longer sets the step: the stable step
  is the one with a step asked for far beyond (1 s), the block's;
- the pull is quasi-static: the bar's axial force at the probe and the
  block's bearing reaction, each averaged over 3-5 ms (the pull's start
  still rings), equal those without scaling within 1 %;
- the energy balance closes (1e-3) with the added mass moving;
- 'Mass scaling time step' on a perfectly bonded bar stops with one line
  (exit 2).
"""
import math
import os
import re
from anvil_test import Checker, arguments, read_csv, run_anvil, write_scene

args = arguments()
c = Checker("selective mass scaling of bond-slip bars")
scene = os.path.join(os.path.abspath(args.source_dir), "prm", "pull_out", "pull_out.prm")
rho, E, d, L, n = 7850.0, 2e11, 0.016, 0.01, 10
wave = math.sqrt(E / rho)
target = 2.68e-6


def prm(name, step, text=""):
    return write_scene(os.path.join(args.work_dir, name + ".prm"), include=scene, text=f"""
subsection Simulation
  set End time = 0.005
  set Output interval = 0
  set History interval = 1e-4
  set Plots = false
  set Print wall times = false
end
subsection Rebar bar
  set Mass scaling time step = {step}
end
""" + text)


def stable_step(step):
    code, out, err = run_anvil(args.anvil, prm(f"cost_{step}", step), cwd=args.work_dir,
                               extra_args=["--print-cost"])
    m = re.search(r"stable step ([0-9.e+-]+) s", out)
    return float(m.group(1)) if code == 0 and m else float("nan")


bar_step = stable_step(0)
c.check("without scaling: stable step / the bar's L / c", bar_step / (L / wave), 1.0, 0.01)
scaled_step, host_step = stable_step(target), stable_step(1)
print(f"  stable steps: {bar_step:.4g} s unscaled, {scaled_step:.4g} s asked {target:.3g} s, "
      f"{host_step:.4g} s asked 1 s (the block's)")
c.check("scaled: stable step / the block's (the bar no longer sets it)", scaled_step / host_step, 1.0, 1e-3)

runs = {}
for name, step in (("unscaled", 0), ("scaled", target)):
    code, out, err = run_anvil(args.anvil, prm(name, step), cwd=args.work_dir)
    if not c.check_true(f"{name}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    d_out = os.path.join(args.work_dir, "output", name)
    s = read_csv(os.path.join(d_out, "summary.csv"))
    runs[name] = dict(summary=dict(zip(s["quantity"], s["value"])),
                      rebar=read_csv(os.path.join(d_out, "rebar_bar.csv")),
                      reactions=read_csv(os.path.join(d_out, "reactions.csv")),
                      energy=read_csv(os.path.join(d_out, "energy.csv")))

f = (target * wave / L) ** 2
added = n * (f - 1) * rho * math.pi * d * d / 4 * L
c.check("added mass [kg] against n (f - 1) rho A L", runs["scaled"]["summary"]["bar_added_mass_kg"], added,
        1e-9, relative=True)
print(f"  steps: {runs['unscaled']['summary']['steps']:.0f} unscaled, {runs['scaled']['summary']['steps']:.0f} "
      f"scaled (ratio {runs['scaled']['summary']['steps'] / runs['unscaled']['summary']['steps']:.3f})")
mean = lambda t: sum(v for time, v in zip(t[0], t[1]) if time >= 0.003) / sum(1 for time in t[0] if time >= 0.003)
for column, table in (("probe_axial_force", "rebar"), ("bearing_fx", "reactions")):
    a, b = (mean((runs[r][table]["time"], runs[r][table][column])) for r in ("unscaled", "scaled"))
    c.check(f"{column}, mean over 3-5 ms, scaled / unscaled", b / a, 1.0, 0.01)
c.check_below("scaled: largest energy balance error", max(runs["scaled"]["energy"]["balance_error"]), 1e-3)

code, out, err = run_anvil(args.anvil, prm("perfect_bond", target, """subsection Rebar bar
  set Coupling = perfect bond
  set Pull velocity = 0, 0, 0
end
"""), cwd=args.work_dir)
lines = [l for l in err.splitlines() if l.strip()]
c.check_true("perfect bond with mass scaling: exit 2 and one line naming the entry",
             code == 2 and len(lines) == 1 and "Mass scaling time step" in lines[0], err.strip())
c.finish()
