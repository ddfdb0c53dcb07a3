"""Wall time of the seed's RC column (prm/rc_column_impact), and its mesh study.

Cost: the production scene (10 mm, 21,600 elements, bond-slip bars) for a
shortened end time on 1 and 2 MPI processes; prints steps, wall time,
nanoseconds per element-cycle (wall time / (elements x steps), bars and
contact included), the share of each TimerOutput section, and the wall
time extrapolated to 150 ms at the measured step; and the memory on one
process: the peak resident set per element, and the marginal memory per
element (the production column's peak against the coarse column's, 2,700
elements, over the difference in elements: what an element, its nodes and
its share of the bars cost, without the executable and its libraries),
and of it what summary.csv accounts for: the triangulation, the DoF
handler, the nodal vectors and the element groups' state.
`END_TIME_S = 0.15` runs the issue's whole 150 ms.

Mesh study (--mesh-study): the bond-slip column at 20, 15 and 10 mm to the
end criterion; prints peak and residual displacement of the impact point
and of the far face, peak hammer force, hourglass share, and each
quantity's change from the previous mesh.

Whole scene (--whole): the production scene as it ships (its end
criterion ends it once the impact is over), on 1 and 2 processes, and on 2
partitioned anew during the run ('Rebalance interval = 1 ms', threshold
1.1): end time, steps, wall time, sections, new partitions.

Local refinement (--adaptive): the bond-slip column to the end criterion on
2 processes, uniform at 10 mm (the production scene), uniform at 20 mm, and
at 20 mm halved to 10 mm in the struck part of the member (0.3 m < z <
0.7 m, where the concrete cracks and crushes), and at 20 mm halved during
the run within 0.15 m of the hammer and where the damage exceeds 0.1,
joined again where neither holds (a round every 2 ms; bars in 10 mm
trusses in all four); prints each one's peak and residual displacement of the impact
point and the far face, peak force, elements and wall time, and the
refined mesh's differences from the uniform 10 mm one and its share of that
one's wall time.

The nose (--nose): the column to 20 ms (past the struck point's peak at
11 ms) on 2 processes, uniform at 10 mm, and at 20 mm halved to 10 mm in
0.3 m < z < 0.7 m and within 0.07 m of the hammer to 5 mm and to 2.5 mm
('Refinement region 2', Levels 2 and 3), each with the scene's 'Full
integration region' and with none (all one-point); prints each one's
peak at the impact point, peak force, hourglass energy over internal
energy, steps and wall time, and its peak against the 2.5 mm fully
integrated nose (the reference: about 25 minutes of the ~30 the option
takes) and its wall time against the uniform 10 mm mesh's. With
--crush-band=L every run regularises the concrete's crushing with 'Crush
band length = L' (doc/adaptivity.md: L = 0.01 keeps the 10 mm mesh's own).
--zone=X0,Y0,Z0:X1,Y1,Z1 adds the 5 mm nose with its 'Full integration
region' shrunk to that box (one-point elements elsewhere); --no-2.5mm
leaves out the two 2.5 mm runs (then the 2.5 mm figures of
doc/adaptivity.md are the reference, printed beside).

Usage: python3 benchmarks/rc_column.py ANVIL [END_TIME_S] [--mesh-study | --whole | --adaptive | --nose [--crush-band=L] [--zone=...] [--no-2.5mm]]
(default end time 0.005 s). Figures, never asserts: timings on shared
machines are noisy; compare the ratios within one run.
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

if len(sys.argv) < 2 or sys.argv[1].startswith("-") or not os.access(sys.argv[1], os.X_OK):
    sys.exit(f"usage: python3 {sys.argv[0]} ANVIL [options in its docstring] (ANVIL: the anvil executable, "
             f"build/anvil; got {sys.argv[1]!r})" if len(sys.argv) > 1 else
             f"usage: python3 {sys.argv[0]} ANVIL [options in its docstring] (ANVIL: the anvil executable, "
             f"build/anvil)")
anvil = os.path.abspath(sys.argv[1])
args = [a for a in sys.argv[2:] if not a.startswith("--")]
end_time = float(args[0]) if args else 0.005
top = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
scene = os.path.join(top, "prm", "rc_column_impact", "rc_column_impact.prm")
work = tempfile.mkdtemp()
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


# The bars in 10 mm trusses (the coarse and refined meshes' studies).
BARS_10MM = """subsection Rebar longitudinal
  set Element length = 0.01
end
subsection Rebar stirrups
  set Element length = 0.01
end
"""


def run(name, np, text, base=scene):
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(f"include {base}\n{text}")
    cmd = ([anvil, prm] if np == 1 else ["mpirun", "-np", str(np), "--oversubscribe", anvil, prm])
    with open(os.path.join(work, name + ".out"), "w+") as out_file:
        child = subprocess.Popen(cmd, cwd=work, stdout=out_file, stderr=subprocess.STDOUT, text=True, env=env)
        # wait4: this child's own peak resident set (kB), not the largest of all children.
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
        out_file.seek(0)
        stdout = out_file.read()
    if child.returncode != 0:
        sys.exit(f"{name}: anvil failed: {stdout.strip()[-300:]}")
    run.peak_kb = usage.ru_maxrss
    out = os.path.join(work, "output", name)
    with open(os.path.join(out, "summary.csv")) as f:
        s = {row["quantity"]: float(row["value"]) for row in csv.DictReader(f)}
    sections = dict((m.group(1).strip(), float(m.group(2)))
                    for m in re.finditer(r"\|\s*([a-z ]+?)\s*\|\s*\d+\s*\|\s*([\d.e+-]+)s", stdout))
    return s, sections, out


def shares(sections):
    total = sum(v for k, v in sections.items() if k not in ("setup",))
    return ", ".join(f"{k} {100 * v / total:.0f} %" for k, v in sorted(sections.items(), key=lambda kv: -kv[1])
                     if k != "setup")


if "--whole" in sys.argv:
    print("rc_column: the production scene (10 mm) as it ships, to its end criterion")
    walls = {}
    for np, rebalance in ((1, False), (2, False), (2, True)):
        name = f"whole_np{np}" + ("_rebalanced" if rebalance else "")
        s, sections, out = run(name, np, """
subsection Simulation
  set Plots = false
""" + ("  set Rebalance interval = 0.001\n" if rebalance else "") + """end
""")
        walls[name] = s["wall_time_s"]
        log = open(os.path.join(work, name + ".out")).read()
        partitions = re.findall(r"elements per process: ([\d ]+)\)", log)
        print(f"  np = {np}{' rebalanced' if rebalance else ''}: ended at {1e3 * s['end_time_s']:.1f} ms, "
              f"{int(s['steps'])} steps, {s['wall_time_s']:.1f} s wall ({s['wall_time_s'] / 60:.2f} min), "
              f"{1e9 * s['wall_time_s'] / (s['elements'] * s['steps']):.0f} ns per element-cycle; "
              f"{shares(sections)}" + (f" (the last partition's part); {len(partitions)} new partitions, "
                                       f"elements per process {', '.join(partitions)}" if rebalance else ""),
              flush=True)
    for name in ("whole_np2", "whole_np2_rebalanced"):
        print(f"  two processes{' rebalanced' if 'rebalanced' in name else ''}: speed-up "
              f"{walls['whole_np1'] / walls[name]:.2f}, parallel efficiency "
              f"{100 * walls['whole_np1'] / (2 * walls[name]):.0f} %")
elif "--nose" in sys.argv:
    print("rc_column: the 5 mm nose against 2.5 mm, fully integrated and one-point, 20 ms, 2 processes")
    common = """
subsection Simulation
  set End time = 0.02
  set End kinetic energy fraction = 0
  set Output interval = 0
  set Plots = false
end
""" + BARS_10MM

    band = [a.split("=", 1)[1] for a in sys.argv if a.startswith("--crush-band=")]
    if band:
        common += f"""
subsection Body column
  subsection Material
    subsection concrete damaged plasticity
      set Crush band length = {band[0]}
    end
  end
end
"""

    def nose(levels, one_point, zone=None):
        return f"""
subsection Body column
  subsection Mesh
    set Subdivisions = 6, 6, 75
  end
  subsection Refinement region
    set Lower corner = -1, -1, 0.3
    set Upper corner = 1, 1, 0.7
    set Levels       = 1
  end
  subsection Refinement region 2
    set Near body = hammer
    set Distance  = 0.07
    set Levels    = {levels}
  end
""" + ("""  subsection Full integration region
    set Lower corner =
    set Upper corner =
  end
""" if one_point else "") + (f"""  subsection Full integration region
    set Lower corner = {zone[0]}
    set Upper corner = {zone[1]}
  end
""" if zone else "") + "end\n"
    rows = {}
    runs = [("uniform 10 mm", common),
            ("5 mm nose, one-point", common + nose(2, True)),
            ("5 mm nose, fully integrated region", common + nose(2, False))]
    zone = [a.split("=", 1)[1].split(":") for a in sys.argv if a.startswith("--zone=")]
    if zone:
        runs.append(("5 mm nose, fully integrated zone " + ":".join(zone[0]), common + nose(2, False, zone[0])))
    if "--no-2.5mm" not in sys.argv:
        runs += [("2.5 mm nose, one-point", common + nose(3, True)),
                 ("2.5 mm nose, fully integrated region", common + nose(3, False))]
    for name, text in runs:
        s, sections, out = run(name.replace(" ", "_").replace(",", "").replace(".", ""), 2, text)
        # (The struck point: the node of the struck face under the nose,
        # what a finer nose resolves; the impact point's section is the
        # member's.)
        rows[name] = row = {"peak": s.get("peak_displacement_struck_face_m", s["peak_displacement_m"]),
                            "force": s["peak_contact_force_N"],
                            "hourglass": s["hourglass_energy_J"] / s["internal_energy_J"],
                            "wall": s["wall_time_s"], "elements": s["elements"], "steps": s["steps"]}
        print(f"  {name}: {int(row['elements'])} elements, {int(row['steps'])} steps, {row['wall']:.1f} s; impact "
              f"point (struck face's node) peak {1e3 * row['peak']:.3f} mm; peak force {1e-3 * row['force']:.1f} kN; hourglass/internal "
              f"{row['hourglass']:.3f}; {shares(sections)}", flush=True)
    uniform = rows["uniform 10 mm"]
    # Without the 2.5 mm runs: doc/adaptivity.md's figures of the 2.5 mm
    # fully integrated nose (struck point, peak force; with and without
    # the crush band of 10 mm).
    reference = rows.get("2.5 mm nose, fully integrated region") or (
        {"peak": 10.062e-3, "force": 77.4e3} if band == ["0.01"] else {"peak": 10.680e-3, "force": 70.0e3})
    if "2.5 mm nose, fully integrated region" not in rows:
        print(f"  (reference: the 2.5 mm fully integrated nose of doc/adaptivity.md, "
              f"{1e3 * reference['peak']:.3f} mm, {1e-3 * reference['force']:.1f} kN)")
    for name, row in rows.items():
        print(f"  {name}: peak {100 * (row['peak'] / reference['peak'] - 1):+.2f} % against the 2.5 mm fully "
              f"integrated nose, force {100 * (row['force'] / reference['force'] - 1):+.1f} %; wall time "
              f"{row['wall'] / uniform['wall']:.2f} of the uniform 10 mm mesh's")
elif "--mesh-study" not in sys.argv and "--adaptive" not in sys.argv:
    print(f"rc_column: production scene (10 mm) to {1e3 * end_time:g} ms")
    for np in (1, 2):
        s, sections, _ = run(f"cost_np{np}", np, f"""
subsection Simulation
  set End time = {end_time!r}
  set End kinetic energy fraction = 0
  set Output interval = 0
  set Plots = false
end
""")
        ns = 1e9 * s["wall_time_s"] / (s["elements"] * s["steps"])
        total = sum(v for k, v in sections.items() if k not in ("setup",))
        share = ", ".join(f"{k} {100 * v / total:.0f} %" for k, v in sorted(sections.items(), key=lambda kv: -kv[1])
                          if k != "setup")
        print(f"  np = {np}: {int(s['steps'])} steps, {s['wall_time_s']:.1f} s wall, {ns:.0f} ns per element-cycle "
              f"(wall x processes: {np * ns:.0f}); 150 ms at this step: "
              f"{s['wall_time_s'] * 0.150 / end_time / 60:.1f} min; {share}")
        if np == 1:
            peak_kb, elements, accounted = run.peak_kb, s["elements"], s
    coarse_scene = os.path.join(top, "prm", "rc_column_impact", "rc_column_impact_coarse.prm")
    s, _, _ = run("memory_coarse", 1, """
subsection Simulation
  set End time = 1e-4
  set Output interval = 0
  set Plots = false
end
""", base=coarse_scene)
    marginal = 1024 * (peak_kb - run.peak_kb) / (elements - s["elements"])
    print(f"  memory (np = 1): peak resident {peak_kb / 1024:.0f} MB, {1024 * peak_kb / elements:.0f} bytes per "
          f"element; marginal {marginal:.0f} bytes per element (against the coarse column's "
          f"{int(s['elements'])} elements, {run.peak_kb / 1024:.0f} MB)")
    parts = [("triangulation", "memory_triangulation_bytes"),
             ("DoF handler", "memory_dof_handler_bytes"), ("nodal vectors", "memory_nodal_vectors_bytes"),
             ("element state", "memory_element_state_bytes")]
    if all(key in accounted for _, key in parts):
        held = sum(accounted[key] for _, key in parts)
        print("  memory held (np = 1, summary.csv), bytes per element: " +
              ", ".join(f"{name} {accounted[key] / elements:.0f}" for name, key in parts) +
              f"; together {held / elements:.0f}, the rest of the marginal {marginal - held / elements:.0f}")
elif "--adaptive" in sys.argv:
    print("rc_column: local refinement against the uniform meshes, bond-slip column to the end criterion, 2 processes")
    common = """
subsection Simulation
  set Output interval = 0
  set Plots = false
end
""" + BARS_10MM
    coarse = """
subsection Body column
  subsection Mesh
    set Subdivisions = 6, 6, 75
  end
end
"""
    region = """
subsection Body column
  subsection Refinement region
    set Lower corner = -1, -1, 0.3
    set Upper corner = 1, 1, 0.7
    set Levels       = 1
  end
end
"""
    during = """
subsection Simulation
  set Adapt interval = 0.002
end
subsection Body column
  subsection Refinement region
    set Near body           = hammer
    set Distance            = 0.15
    set Indicator           = damage
    set Indicator threshold = 0.1
    set Levels              = 1
  end
end
"""
    rows = {}
    for name, text in (("uniform 10 mm", common), ("uniform 20 mm", common + coarse),
                       ("20 mm, 10 mm in 0.3-0.7 m", common + coarse + region),
                       ("20 mm, 10 mm where it works (during the run)", common + coarse + during)):
        s, sections, out = run(name.replace(" ", "_").replace(",", "").replace(".", ""), 2, text)
        with open(os.path.join(out, "probe_back_face.csv")) as f:
            back = [float(r["ux"]) for r in csv.DictReader(f)]
        rows[name] = row = {"peak": s["peak_displacement_m"], "residual": s["residual_displacement_m"],
                            "far face": -min(back), "force": s["peak_contact_force_N"],
                            "wall": s["wall_time_s"], "elements": s["elements"], "steps": s["steps"]}
        print(f"  {name}: {int(row['elements'])} elements, {int(row['steps'])} steps, {row['wall']:.1f} s; impact "
              f"point peak {1e3 * row['peak']:.2f} mm, residual {1e3 * row['residual']:.2f} mm; far face peak "
              f"{1e3 * row['far face']:.2f} mm; peak force {1e-3 * row['force']:.1f} kN; "
              f"{shares(sections)}", flush=True)
    fine = rows["uniform 10 mm"]
    for name in ("20 mm, 10 mm in 0.3-0.7 m", "20 mm, 10 mm where it works (during the run)"):
        local = rows[name]
        print(f"  {name} against uniform 10 mm: " +
              ", ".join(f"{k} {100 * (local[k] / fine[k] - 1):+.1f} %" for k in ("peak", "residual", "far face", "force")) +
              f"; elements at the end {local['elements'] / fine['elements']:.2f}, wall time {local['wall'] / fine['wall']:.2f}"
              f" (per step {(local['wall'] / local['steps']) / (fine['wall'] / fine['steps']):.2f}: each run ends by its"
              f" own end criterion)")
else:
    print("rc_column: mesh study, bond-slip column to the end criterion")
    previous = None
    for h, n, bar in ((20, (6, 6, 75), 0.02), (15, (8, 8, 100), 0.015), (10, (12, 12, 150), 0.01)):
        s, _, out = run(f"mesh_{h}mm", 2, f"""
subsection Simulation
  set Output interval = 0
  set Plots = false
end
subsection Body column
  subsection Mesh
    set Subdivisions = {n[0]}, {n[1]}, {n[2]}
  end
end
subsection Rebar longitudinal
  set Element length = {bar}
end
subsection Rebar stirrups
  set Element length = {bar}
end
""")
        with open(os.path.join(out, "probe_back_face.csv")) as f:
            back = [float(r["ux"]) for r in csv.DictReader(f)]
        row = {"peak": s["peak_displacement_m"], "residual": s["residual_displacement_m"],
               "far face": -min(back), "force": s["peak_contact_force_N"]}
        change = ("" if previous is None else ", change: " +
                  ", ".join(f"{k} {100 * (row[k] / previous[k] - 1):+.1f} %" for k in row))
        print(f"  {h} mm ({int(s['elements'])} elements, {s['wall_time_s']:.0f} s): impact point peak "
              f"{1e3 * row['peak']:.2f} mm, residual {1e3 * row['residual']:.2f} mm; far face peak "
              f"{1e3 * row['far face']:.2f} mm; peak force {1e-3 * row['force']:.1f} kN; hourglass/internal "
              f"{s['hourglass_energy_J'] / s['internal_energy_J']:.3f}{change}")
        previous = row
