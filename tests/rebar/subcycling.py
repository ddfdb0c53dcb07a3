"""Subcycling of bond-slip bars ('Subcycling').

The bars of prm/pull_out (a 16 mm steel bar of 10 mm elements in a
concrete block of 10 mm elements) set the step: their L / c is 1.98 us.
Subcycled, they take substeps of their own stable step inside the block's:
- the stable step is the block's: the one the same scene gets with the
  bars mass-scaled far beyond (1 s), which takes them out of the step's
  bound (relative 1e-3);
- a bar pulled at its end with a negligible bond (G_s = 1 Pa/m) carries the
  1D elastic wave: behind the front the axial force is rho c A v (v the pull
  velocity, c = sqrt(E / rho)). Its mean at the bar's middle while the
  front has passed and its reflection from the free end has not come back
  (12-26 us) is within 2 % of that, subcycled and not: the substeps
  integrate the bar's wave;
- the pull-out of the scene to 5 ms is quasi-static: the bar's axial force
  at the probe and the block's bearing reaction, each averaged over 3-5 ms,
  equal those without subcycling within 1 %;
- the energy balance closes (1e-4): the host gets the bond reactions of the
  step's ends, the bars feel the bond at every substep;
- two processes give one process's histories, every column (1e-8);
- 'Subcycling' on a perfectly bonded bar stops with one line (exit 2).
"""
import math
import os
import re
from anvil_test import Checker, arguments, max_relative_difference, read_csv, run_anvil, write_scene

args = arguments()
c = Checker("subcycling of bond-slip bars")
scene = os.path.join(os.path.abspath(args.source_dir), "prm", "pull_out", "pull_out.prm")
rho, E, d, L = 7850.0, 2e11, 0.016, 0.01
wave = math.sqrt(E / rho)
area = math.pi * d * d / 4


def prm(name, subcycling, text="", end=0.005, history=1e-4):
    return write_scene(os.path.join(args.work_dir, name + ".prm"), include=scene, text=f"""
subsection Simulation
  set End time = {end}
  set Output interval = 0
  set History interval = {history}
  set Plots = false
  set Print wall times = false
end
subsection Rebar bar
  set Subcycling = {'true' if subcycling else 'false'}
end
""" + text)


def run(name, subcycling, text="", np=1, **kw):
    code, out, err = run_anvil(args.anvil, prm(name, subcycling, text, **kw), np=np, cwd=args.work_dir)
    if not c.check_true(f"{name}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    d_out = os.path.join(args.work_dir, "output", name)
    s = read_csv(os.path.join(d_out, "summary.csv"))
    return dict(out=out, summary=dict(zip(s["quantity"], s["value"])),
                rebar=read_csv(os.path.join(d_out, "rebar_bar.csv")),
                reactions=read_csv(os.path.join(d_out, "reactions.csv")),
                energy=read_csv(os.path.join(d_out, "energy.csv")))


def stable_step(name, subcycling, text=""):
    code, out, err = run_anvil(args.anvil, prm(name, subcycling, text), cwd=args.work_dir,
                               extra_args=["--print-cost"])
    m = re.search(r"stable step ([0-9.e+-]+) s", out)
    return float(m.group(1)) if code == 0 and m else float("nan")


# 1. The bars no longer bound the step.
bar_step = stable_step("cost_bars", False)
sub_step = stable_step("cost_subcycled", True)
host_step = stable_step("cost_host", False, "subsection Rebar bar\n  set Mass scaling time step = 1\nend\n")
print(f"  stable steps: {bar_step:.4g} s bars as they are (L / c = {L / wave:.4g} s), {sub_step:.4g} s "
      f"subcycled, {host_step:.4g} s the block's")
c.check("subcycled: stable step / the block's (the bars no longer set it)", sub_step / host_step, 1.0, 1e-3)

# 2. The bar's wave, bond negligible: rho c A v behind the front.
v = 0.01
expected = rho * wave * area * v
for subcycling in (False, True):
    name = "wave_" + ("subcycled" if subcycling else "plain")
    r = run(name, subcycling, "subsection Rebar bar\n  set Bond modulus = 1\nend\n", end=3e-5, history=5e-7)
    t, f = r["rebar"]["time"], r["rebar"]["probe_axial_force"]
    window = [fi for ti, fi in zip(t, f) if 12e-6 <= ti <= 26e-6]
    mean = sum(window) / len(window)
    c.check(f"{name}: mean axial force at the middle, 12-26 us / rho c A v ({expected:.4g} N)",
            mean / expected, 1.0, 0.02)

# 3. The quasi-static pull-out, with and without subcycling.
runs = {name: run(name, name == "subcycled") for name in ("plain", "subcycled")}
print(f"  steps: {runs['plain']['summary']['steps']:.0f} plain, {runs['subcycled']['summary']['steps']:.0f} "
      f"subcycled (ratio {runs['subcycled']['summary']['steps'] / runs['plain']['summary']['steps']:.3f})")
mean = lambda t: sum(v for time, v in zip(t[0], t[1]) if time >= 0.003) / sum(1 for time in t[0] if time >= 0.003)
for column, table in (("probe_axial_force", "rebar"), ("bearing_fx", "reactions")):
    a, b = (mean((runs[r][table]["time"], runs[r][table][column])) for r in ("plain", "subcycled"))
    c.check(f"{column}, mean over 3-5 ms, subcycled / plain", b / a, 1.0, 0.01)
c.check_below("subcycled: largest energy balance error", max(runs["subcycled"]["energy"]["balance_error"]), 1e-4)

# 4. Two processes.
two = run("subcycled_np2", True, np=2)
for table in ("rebar", "reactions", "energy"):
    c.check_below(f"np = 2 against np = 1: {table} (every column), largest difference / peak",
                  max_relative_difference(runs["subcycled"][table], two[table]), 1e-8)

# 5. Perfect bond cannot be subcycled.
code, out, err = run_anvil(args.anvil, prm("perfect_bond", True, """subsection Rebar bar
  set Coupling = perfect bond
  set Pull velocity = 0, 0, 0
end
"""), cwd=args.work_dir)
lines = [l for l in err.splitlines() if l.strip()]
c.check_true("perfect bond with subcycling: exit 2 and one line naming the entry",
             code == 2 and len(lines) == 1 and "Subcycling" in lines[0], err.strip())
c.finish()
