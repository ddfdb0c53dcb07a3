"""Reinforcement with perfect bond: a steel bar embedded in an elastic
concrete prism under axial load (seed sections 5.1, 5.3).

Prism 0.1 x 0.1 x 1 m (tests/rebar/composite_bar.prm; E_c = 30 GPa, nu = 0,
so that the section deforms uniaxially), one 20 mm bar along its axis (E_s = 200 GPa), base held in z,
top pulled at 0.01 m/s. With perfect bond the bar and the concrete around it
share the strain, so the axial forces split as E A:
  N_s / N_c = E_s A_s / (E_c A_c),  A_c = 0.01 m^2 (the embedded bar
overlaps the host, as ABAQUS's embedded elements do),
checked at mid-height (truss element and concrete element there) within
1 %, for a mesh with nodes on the bar (4 x 4 across: conforming, the bar on
a node line) and one without (5 x 5: the bar through element centres).
The last rebar_bar_NNNN.vtu (line cells) is read back and agrees with
rebar_bar.csv. The same bar read from a polyline file carries the same
force (1e-9, the segments' round-off), and a stirrup layout (10 ties at
0.1 m) prints the transverse ratio 2 A_s / (b s). Also: a reinforced block flying at 1 m/s keeps its momentum to round-off
(rebar mass and forces go to the host through the shape functions), and
np = 2 gives the composite bar's histories of np = 1 (relative 1e-8), the
bar crossing the partition.
"""
import os
from anvil_test import Checker, arguments, max_relative_difference, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("composite bar with perfect bond")
Es, Ec, d = 200e9, 30e9, 0.02
As = 3.141592653589793 / 4 * d * d
Ac = 0.1 * 0.1


def scene(name, n, pull=True, v0=0.0, end_time=0.01):
    overrides = {"Simulation/End time": end_time, "Body prism/Mesh/Subdivisions": f"{n}, {n}, 50",
                 "Body prism/Initial velocity": f"0, 0, {v0}"}
    return test_scene(args, "tests/rebar/composite_bar.prm" if pull else "tests/rebar/composite_bar_free.prm", name,
                      overrides)


def run(name, np=1, **kw):
    code, out, err = run_anvil(args.anvil, scene(name, **kw), np=np, cwd=args.work_dir)
    if not c.check_true(f"{name} (np = {np}): anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    print("   " + next((l for l in out.splitlines() if "rebar 'bar'" in l), "").strip())
    d_ = os.path.join(args.work_dir, "output", name)
    return {f: read_csv(os.path.join(d_, f + ".csv")) for f in ("rebar_bar", "probe_mid", "energy", "momentum")}


expected = Es * As / (Ec * Ac)
results = {}
for label, n in (("conforming (4 x 4, bar on a node line)", 4), ("non-conforming (5 x 5)", 5)):
    r = run(f"composite_{n}", n=n)
    results[n] = r
    Ns = r["rebar_bar"]["probe_axial_force"][-1]
    # The probe node (0.05, 0.05, 0.52) reports the stress of its element
    # with the smallest id: the one below it, z in [0.50, 0.52], like the
    # probed truss element.
    Nc = r["probe_mid"]["stress_zz"][-1] * Ac
    c.check(f"{label}: N_s / N_c at mid-height", Ns / Nc, expected, 0.01, relative=True)
    # The top starts at 0.01 m/s at t = 0: the impulsive start leaves an
    # O(m v^2) offset that is 3 % of the tiny energies of the first steps;
    # the balance is checked once they have grown (t >= 2 ms).
    late = [b for t, b in zip(r["energy"]["time"], r["energy"]["balance_error"]) if t >= 2e-3]
    c.check_below(f"{label}: largest energy balance error after 2 ms", max(late), 0.01)

# The rebar field output: line cells with the axial force, read back.
import glob
import xml.etree.ElementTree as ET
vtus = sorted(glob.glob(os.path.join(args.work_dir, "output", "composite_5", "rebar_bar_*.vtu")))
piece = ET.parse(vtus[-1]).getroot().find("UnstructuredGrid/Piece")
forces = [float(v) for v in piece.find("CellData/DataArray[@Name='axial_force']").text.split()]
c.check("rebar_bar_NNNN.vtu: line cells", float(piece.get("NumberOfCells")), 50, 0)
c.check("rebar_bar_NNNN.vtu: largest axial force / rebar_bar.csv", max(forces),
        results[5]["rebar_bar"]["max_axial_force"][-1], 1e-9, relative=True)

# The same bar from a polyline file, and a stirrup layout's ratios.
with open(os.path.join(args.work_dir, "bar.txt"), "w") as f:
    f.write("0.05 0.05 0\n0.05 0.05 0.5\n0.05 0.05 1\n")
prm = test_scene(args, "tests/rebar/composite_bar.prm", "composite_poly",
                 {"Body prism/Mesh/Subdivisions": "5, 5, 50", "Rebar bar/Layout": "polylines",
                  "Rebar bar/File name": "bar.txt"})
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if c.check_true("polyline layout: anvil exits 0", code == 0, err.strip()[-300:]):
    r = read_csv(os.path.join(args.work_dir, "output", "composite_poly", "rebar_bar.csv"))
    c.check("polyline layout: largest axial force / longitudinal layout's", r["max_axial_force"][-1],
            results[5]["rebar_bar"]["max_axial_force"][-1], 1e-9, relative=True)
prm = test_scene(args, "tests/rebar/composite_bar.prm", "stirrups",
                 {"Body prism/Mesh/Subdivisions": "5, 5, 50", "Rebar bar/Layout": "stirrups", "Rebar bar/Spacing": 0.1,
                  "Rebar bar/Cover": 0.01})
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir,
                           extra_args=["--check"])
line = next((l for l in out.splitlines() if "stirrups of" in l), "")
print("   " + line.strip())
c.check_true("stirrups: 10 ties at 0.1 m", "10 stirrups of 20 mm" in line, line.strip())
ratio = float(line.split("transverse ratios ")[1].split(" %")[0])
c.check("stirrups: transverse ratio 2 A_s / (b s) [%]", ratio, 100 * 2 * As / (0.1 * 0.1), 0.01, relative=True)

par = run("composite_5_np2", np=2, n=5)
c.check_below("np = 2 against np = 1: largest relative difference of rebar_bar.csv",
              max_relative_difference(results[5]["rebar_bar"], par["rebar_bar"]), 1e-8)

fly = run("flying", n=5, pull=False, v0=1.0, end_time=0.002)
p = fly["momentum"]["pz"]
c.check_below("free reinforced block at 1 m/s: momentum drift / p0", max(abs(x - p[0]) for x in p) / p[0], 1e-12)
mass = 2400 * Ac * 1.0 + 7850 * As * 1.0
c.check("momentum / (host + bar mass) x 1 m/s", p[0], mass * 1.0, 1e-9 * mass, relative=False)
c.finish()
