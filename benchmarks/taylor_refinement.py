#!/usr/bin/env python3
"""The Taylor bar (prm/steel_bar_impact) refined at its impact end, against
the uniform meshes.

Three runs on 2 processes, penalty contact in all (kinematic contact does not
take the hanging nodes where the refined end meets the rest of the lateral
surface): the shipped mesh (one global refinement), the uniform fine mesh
(two), and the shipped mesh halved in its last 38 mm before the wall
(x > 12 mm: 'Refinement region'). Prints the final length and impact-face
radius (bodies.csv, the bar's bounding box), elements, steps and wall time,
and the refined run's differences from the uniform fine one and its share of
that one's wall time. Figures only.

    /usr/bin/python3 benchmarks/taylor_refinement.py ANVIL
"""
import csv
import os
import subprocess
import sys
import tempfile

if len(sys.argv) < 2 or sys.argv[1].startswith("-") or not os.access(sys.argv[1], os.X_OK):
    sys.exit(f"usage: python3 {sys.argv[0]} ANVIL [options in its docstring] (ANVIL: the anvil executable, "
             f"build/anvil; got {sys.argv[1]!r})" if len(sys.argv) > 1 else
             f"usage: python3 {sys.argv[0]} ANVIL [options in its docstring] (ANVIL: the anvil executable, "
             f"build/anvil)")
anvil = os.path.abspath(sys.argv[1])
top = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
scene = os.path.join(top, "prm", "steel_bar_impact", "steel_bar_impact.prm")
work = tempfile.mkdtemp()
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
common = ["--set", "Contact pair impact/Algorithm=penalty", "--set", "Simulation/Plots=false",
          "--set", "Simulation/Output interval=0"]
variants = (("shipped mesh", []),
            ("uniform fine", ["--set", "Body bar/Mesh/Global refinements=2"]),
            ("refined end", ["--set", "Body bar/Refinement region/Lower corner=0.012, -1, -1",
                             "--set", "Body bar/Refinement region/Upper corner=1, 1, 1"]))
rows = {}
print("Taylor bar refined at the impact end, penalty contact, 2 processes")
for name, extra in variants:
    cwd = os.path.join(work, name.replace(" ", "_"))
    os.makedirs(cwd)
    r = subprocess.run(["mpirun", "-np", "2", "--oversubscribe", anvil, scene] + common + extra, cwd=cwd, env=env,
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{name}: anvil failed: {(r.stderr or r.stdout).strip()[-300:]}")
    out = os.path.join(cwd, "output", "steel_bar_impact")
    bar = [b for b in csv.DictReader(open(os.path.join(out, "bodies.csv"))) if b["body"] == "bar"][-1]
    s = {q["quantity"]: float(q["value"]) for q in csv.DictReader(open(os.path.join(out, "summary.csv")))}
    rows[name] = row = {"length": float(bar["xmax"]) - float(bar["xmin"]),
                        "radius": 0.5 * (float(bar["ymax"]) - float(bar["ymin"])),
                        "wall": s["wall_time_s"], "elements": s["elements"], "steps": s["steps"]}
    print(f"  {name}: {int(row['elements'])} elements, {int(row['steps'])} steps, {row['wall']:.2f} s; final length "
          f"{1e3 * row['length']:.3f} mm, impact-face radius {1e3 * row['radius']:.3f} mm", flush=True)
fine = rows["uniform fine"]
for name in ("shipped mesh", "refined end"):
    r = rows[name]
    print(f"  {name} against the uniform fine mesh: length {100 * (r['length'] / fine['length'] - 1):+.3f} %, "
          f"radius {100 * (r['radius'] / fine['radius'] - 1):+.2f} %, wall time {r['wall'] / fine['wall']:.2f}")
