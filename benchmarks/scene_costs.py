#!/usr/bin/env python3
"""What each option costs: small scenes run with one option changed, on one
process, each three times (the fastest kept: these machines are shared and
noisy), cost per element-cycle of the whole step (every TimerOutput section
but setup and output) and its ratio to the base scene of the same family,
measured in this one run.

    /usr/bin/python3 benchmarks/scene_costs.py --anvil build/anvil

Families: the rods of prm/elastic_rod_impact (elastic, contact) and the
steel bar of prm/steel_bar_impact (plastic kinematic steel, rate effects,
contact on a rigid wall). The README's table of option costs comes from
this. Nothing is asserted.
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.abspath(os.path.join(HERE, ".."))

ROD = os.path.join(SOURCE, "prm", "elastic_rod_impact", "elastic_rod_impact.prm")
BAR = os.path.join(SOURCE, "prm", "steel_bar_impact", "steel_bar_impact.prm")
RODS = ("rod_a", "rod_b")


def each(bodies, text):
    return "".join(f"subsection Body {b}\n{text}end\n" for b in bodies)


# tests/verification/dormant_rod.prm without its include of the rods: a
# third rod 100 m away in a contact pair that never closes.
DORMANT = "".join(line for line in open(os.path.join(SOURCE, "tests", "verification", "dormant_rod.prm"))
                  if not line.startswith("include "))
NO_Q = "  subsection Bulk viscosity\n    set Linear coefficient = 0\n    set Quadratic coefficient = 0\n  end\n"
STEEL = lambda entries: ("subsection Body bar\n  subsection Material\n    subsection plastic kinematic\n"
                         + "".join(f"      set {e}\n" for e in entries) + "    end\n  end\nend\n")

CASES = [
    ("rods", ROD, [
        ("shipped (elastic, one point, viscous hourglass, bulk viscosity, 1 contact pair)", ""),
        ("a dormant third body 100 m away, in a contact pair", DORMANT),
        ("no bulk viscosity", each(RODS, NO_Q)),
        ("stiffness hourglass control", each(RODS, "  subsection Hourglass control\n    set Type = stiffness\n  end\n")),
        ("no hourglass control", each(RODS, "  subsection Hourglass control\n    set Type = none\n  end\n")),
        ("total Lagrangian", each(RODS, "  set Formulation = total Lagrangian\n")),
        ("full integration (2x2x2 points)", each(RODS, "  set Integration = full\n")),
    ]),
    ("steel bar", BAR, [
        ("shipped (plastic kinematic, rate effects, 250 m/s)", ""),
        ("no rate effects", STEEL(["Strain rate effects = false"])),
        ("elastic range (5 m/s, no yield)", "subsection Body bar\n  set Initial velocity = 5, 0, 0\nend\n"),
        ("elastic material, 250 m/s", "subsection Body bar\n  subsection Material\n    set Model = elastic\n"
                                      "  end\nend\n"),
        ("erosion on (failure strain 0.8, not reached)", STEEL(["Erosion = true", "Failure strain = 0.8"])),
    ]),
]


def step_cost(anvil, work, name, scene, text, repeats):
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as fh:
        fh.write(f"include {scene}\n" + text + """
subsection Simulation
  set Output interval = 0
  set History interval = 0
  set Plots = false
  set Print wall times = true
end
""")
    best = None
    for _ in range(repeats):
        r = subprocess.run(["mpirun", "-np", "1", anvil, prm], cwd=work, capture_output=True, text=True)
        if r.returncode != 0:
            return None, r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}"
        sections = {m.group(1).strip(): float(m.group(2)) for m in
                    re.finditer(r"^\|\s*([a-z][a-z ]*?)\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s", r.stdout, re.M)}
        with open(os.path.join(work, "output", name, "summary.csv")) as fh:
            s = dict(l.strip().split(",") for l in fh.readlines()[1:])
        cycles = float(s["elements"]) * float(s["steps"])
        step = sum(t for k, t in sections.items() if k not in ("setup", "output"))
        cost = (1e9 * step / cycles, 1e9 * sections.get("element forces", 0) / cycles,
                1e9 * sections.get("contact", 0) / cycles)
        best = cost if best is None or cost[0] < best[0] else best
    return best, ""


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--anvil", default=os.path.join(SOURCE, "build", "anvil"))
    p.add_argument("--work-dir", default="output/scene_costs")
    p.add_argument("--repeats", type=int, default=3)
    a = p.parse_args()
    work = os.path.abspath(a.work_dir)
    os.makedirs(work, exist_ok=True)
    anvil = os.path.abspath(a.anvil)
    print("| scene | option | ns per element-cycle (step) | of which elements | contact | ratio to shipped |")
    print("| --- | --- | --- | --- | --- | --- |")
    for family, scene, variants in CASES:
        base = None
        for i, (label, text) in enumerate(variants):
            cost, err = step_cost(anvil, work, f"{family.replace(' ', '_')}_{i}", scene, text, a.repeats)
            if cost is None:
                print(f"| {family} | {label} | failed: {err} | | | |")
                continue
            base = base or cost
            print(f"| {family} | {label} | {cost[0]:.0f} | {cost[1]:.0f} | {cost[2]:.0f} | {cost[0] / base[0]:.2f} |",
                  flush=True)


if __name__ == "__main__":
    sys.exit(main())
