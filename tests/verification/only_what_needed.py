"""Only what a scene needs runs in its step.

Each run prints one line of what its step computes ('the step computes:
...', read from the flags that gate the loop) and TimerOutput's sections
with their numbers of calls. Checked here:
- the shipped rods: contact in 1 pair, bulk viscosity in both bodies, no
  rate effects, no erosion, no bars; TimerOutput has a 'contact' section
  entered once a step and no 'rebar and bond' section;
- the rods without contact pairs: no 'contact' section at all;
- the rods with bulk viscosity switched off: 'no bulk viscosity';
- a dormant third body 100 m away with a contact pair against rod B: the
  rods' contact impulse and duration, final kinetic energy and peak
  displacement equal those without it to 1e-3, and its pair never carries
  a force (its cost per element-cycle is
  printed, not asserted: benchmarks/scene_costs.py measures it);
- the steel bar with and without rate effects: 'rate effects in 1 body' and
  'no rate effects'; with 'Strain rate effects = auto' and the preset's C
  and p the line names Cowper-Symonds with C = 40 1/s and p = 5, with
  'Malvar-Crawford' it names that law;
- the pull-out's bar (elastic) 'no rate effects in bars'; the coarse column's
  bars (Table 1 steel, nothing said of rate effects) 'rate effects in 2 of 2
  rebar sets (Cowper-Symonds';
- the concrete pull-out: a 'rebar and bond' section entered once a step,
  no 'contact' section;
- the rods with 'Postprocess/List = energies, probes': energy.csv and the
  probes' histories are written, and none of the other postprocessors'
  files (momentum.csv, reactions.csv, bodies.csv, summary.csv, frames), with
  the same energy rows as the run with all of them.
"""
import os
import re
from anvil_test import Checker, arguments, read_csv, run_anvil, write_scene

args = arguments()
c = Checker("only what a scene needs runs in its step")
work = args.work_dir
src = os.path.abspath(args.source_dir)
rod = os.path.join(src, "prm", "elastic_rod_impact", "elastic_rod_impact.prm")
bar = os.path.join(src, "prm", "steel_bar_impact", "steel_bar_impact.prm")
pull = os.path.join(src, "prm", "pull_out", "pull_out_concrete.prm")
quiet = """
subsection Simulation
  set Output interval = 0
  set Plots = false
  set Print wall times = true
end
"""


def run(name, scene, text):
    prm = write_scene(os.path.join(work, name + ".prm"), include=scene, text=quiet + text)
    code, out, err = run_anvil(args.anvil, prm, cwd=work)
    if not c.check_true(f"{name}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    line = next((l for l in out.splitlines() if "the step computes:" in l), "")
    sections = {m.group(1).strip(): (int(m.group(2)), float(m.group(3)))
                for m in re.finditer(r"^\|\s*([a-z][a-z ]*?)\s*\|\s*(\d+)\s*\|\s*([0-9.e+-]+)s", out, re.M)}
    d = os.path.join(work, "output", name)
    s = read_csv(os.path.join(d, "summary.csv"))
    s = dict(zip(s["quantity"], s["value"]))
    print(f"  {name}: {line.strip()}")
    print(f"    sections (calls): " + ", ".join(f"{k} {v[0]}" for k, v in sorted(sections.items())))
    return dict(line=line, sections=sections, summary=s, dir=d)


def says(name, r, *parts):
    for p in parts:
        c.check_true(f"{name}: the step line says '{p}'", p in r["line"])


# The shipped rods.
base = run("rods", rod, "")
steps = int(base["summary"]["steps"])
says("rods", base, "elements of 2 bodies", "bulk viscosity in 2 bodies", "no rate effects", "no erosion",
     "contact in 1 pair", "no bars", "no mass damping", "no gravity")
c.check_true("rods: 'contact' entered once a step (and once for the initial state)",
             base["sections"].get("contact", (0, 0))[0] == steps + 1, str(base["sections"].get("contact")))
c.check_true("rods: no 'rebar and bond' section", "rebar and bond" not in base["sections"])

# No contact pairs: no contact code at all (the scene without its pair).
with open(rod) as fh:
    text = re.sub(r"subsection Contact pair impact.*?\nend\n", "", fh.read(), flags=re.S)
text = text.replace("set Contact pairs = impact", "set Contact pairs =")
lone = os.path.join(work, "rods_without_pair.prm")
with open(lone, "w") as fh:
    fh.write(text)
alone = run("rods_no_contact", lone, "")
says("rods without contact pairs", alone, "no contact")
c.check_true("rods without contact pairs: no 'contact' section", "contact" not in alone["sections"],
             ", ".join(alone["sections"]))

# Bulk viscosity off.
no_q = run("rods_no_bulk_viscosity", rod, "".join(f"""subsection Body {b}
  subsection Bulk viscosity
    set Linear coefficient = 0
    set Quadratic coefficient = 0
  end
end
""" for b in ("rod_a", "rod_b")))
says("rods without bulk viscosity", no_q, "no bulk viscosity")

# A dormant body far away, in contact pair with rod B.
dormant = run("rods_dormant_body", os.path.join(src, "tests", "verification", "dormant_rod.prm"), "")
says("dormant body", dormant, "contact in 2 pairs", "elements of 3 bodies")
# The rods' physics is the same with the body there: contact impulse,
# duration and the rods' final kinetic energy within 1e-3. (Histories are
# not compared row by row: the third body renumbers the nodes, the forces
# are summed in another order, and a round-off difference may move a step
# that is held against changes under 1 % by one step.)
def impulse(d):
    t = read_csv(os.path.join(d, "contact_impact.csv"))
    f = t["normal_force_x"]
    return sum(0.5 * (f[i] + f[i + 1]) * (t["time"][i + 1] - t["time"][i]) for i in range(len(f) - 1))


for q in ("contact_duration_s", "final_kinetic_energy_J", "peak_displacement_m"):
    c.check(f"dormant body: {q} / the run without it", dormant["summary"][q] / base["summary"][q], 1.0, 1e-3)
c.check("dormant body: contact impulse / the run without it", impulse(dormant["dir"]) / impulse(base["dir"]),
        1.0, 1e-3)
far = read_csv(os.path.join(dormant["dir"], "contact_far_pair.csv"))
c.check_below("dormant body: largest force of its pair [N]",
              max(abs(v) for k in ("normal_force_x", "normal_force_y", "normal_force_z") for v in far[k]), 0.0)
per_cycle = lambda r: 1e9 * sum(t for _, t in r["sections"].values()) / (
    r["summary"]["elements"] * r["summary"]["steps"])
print(f"  cost per element-cycle, all sections (noisy, not asserted): rods {per_cycle(base):.0f} ns, "
      f"with the dormant body {per_cycle(dormant):.0f} ns (ratio {per_cycle(dormant) / per_cycle(base):.2f})")

# Rate effects: only when asked for.
short = "subsection Simulation\n  set End time = 1e-5\nend\n"
rate = run("bar_rate", bar, short)
says("steel bar with rate effects", rate, "rate effects in 1 body")
no_rate = run("bar_no_rate", bar, short + """subsection Body bar
  subsection Material
    subsection plastic kinematic
      set Strain rate effects = false
    end
  end
end
""")
says("steel bar without rate effects", no_rate, "no rate effects")
law = lambda name: short + f"""subsection Body bar
  subsection Material
    subsection plastic kinematic
      set Strain rate effects = {name}
    end
  end
end
"""
auto = run("bar_auto", bar, law("auto"))
says("steel bar, 'auto' with the preset's C and p", auto,
     "rate effects in 1 body (Cowper-Symonds (C = 40 1/s, p = 5))")
malvar = run("bar_malvar", bar, law("Malvar-Crawford"))
says("steel bar, 'Malvar-Crawford'", malvar, "rate effects in 1 body (Malvar-Crawford (alpha = 0.04161))")

# Bars: their own section, entered once a step.
bars = run("pull_out", pull, "subsection Simulation\n  set End time = 0.001\nend\n")
says("pull-out", bars, "bar elements in 1 rebar set", "no contact", "no rate effects in bars")
column = os.path.join(src, "prm", "rc_column_impact", "rc_column_impact_coarse.prm")
col = run("column", column, "subsection Simulation\n  set End time = 2e-5\nend\n")
says("coarse column", col, "rate effects in 2 of 2 rebar sets (Cowper-Symonds (C = 40 1/s, p = 5))",
     "concrete DIF")
c.check_true("pull-out: 'rebar and bond' entered once a step (and once for the initial state)",
             bars["sections"].get("rebar and bond", (0, 0))[0] == int(bars["summary"]["steps"]) + 1,
             str(bars["sections"].get("rebar and bond")))
c.check_true("pull-out: no 'contact' section", "contact" not in bars["sections"])

# Only the postprocessors the scene lists.
prm = write_scene(os.path.join(work, "rods_listed.prm"), include=rod, text=quiet + """
subsection Postprocess
  set List = energies, probes
end
""")
code, out, err = run_anvil(args.anvil, prm, cwd=work)
c.check_true("'Postprocess/List = energies, probes': anvil exits 0", code == 0, err.strip()[-300:])
listed = os.path.join(work, "output", "rods_listed")
files = set(os.listdir(listed)) if os.path.isdir(listed) else set()
c.check_true("listed: energy.csv and probe_face_a.csv written", {"energy.csv", "probe_face_a.csv"} <= files,
             str(sorted(files)))
unlisted = {"momentum.csv", "reactions.csv", "bodies.csv", "summary.csv", "solution.pvd"} & files
c.check_true("listed: no file of the postprocessors left out", not unlisted, str(sorted(unlisted)))
if "energy.csv" in files:
    c.check_true("listed: energy.csv equals the full run's, row by row",
                 open(os.path.join(listed, "energy.csv")).read() ==
                 open(os.path.join(base["dir"], "energy.csv")).read())
c.finish()
