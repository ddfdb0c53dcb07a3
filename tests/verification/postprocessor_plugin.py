"""The postprocessor plugin of doc/extending.md ('A postprocessor as a
plugin'), built outside Anvil's tree against the exported CMake package,
loaded with 'Additional shared libraries' and run in
tests/verification/centre_of_mass.prm (prm/elastic_rod_impact:
two free rods, 0.1 kg each, rod A at 1 m/s into rod B at rest): its
centre_of_mass.csv against momentum conservation.

- The mass it sums equals 2 rho V = 0.2 kg (to 1e-12).
- The centre of mass moves at V_c = (m_A v_A + m_B v_B) / M = 0.5 m/s from
  x_c(0) = 0 through the whole contact, whatever the step sizes: the
  largest |x_c(t) - 0.5 t| over the run, relative to the rods' length, is
  at round-off (below 1e-10).
- np = 2 writes the rows of np = 1 (relative difference below 1e-9: the
  nodal positions are bitwise the same, the sums over processes are not).
- The file is listed in anvil_files.txt (a later run deletes exactly it).
- The plugin's own parameter, 'Postprocess/centre of mass/Bodies = rod_b':
  the mass it sums is rod B's 0.1 kg, and rod B's centre of mass ends
  where bar theory puts it: pushed by rho c A v0 / 2 = 0.5 N for
  2L/c = 0.2 s, then moving at 1 m/s, x_c(0.3 s) = 5 + 0.1 + 0.1 m. An
  unknown body in that entry stops the run with one line naming the entry.
"""
import os
from anvil_test import Checker, arguments, build_plugin, max_relative_difference, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("centre-of-mass postprocessor plugin (doc/extending.md)")
library = build_plugin(c, args, "centre_of_mass", "libcentre_of_mass.so")

rows = {}
for np in (1, 2):
    prm = test_scene(args, "tests/verification/centre_of_mass.prm", f"rods_{np}",
                     {"Additional shared libraries": library, "Simulation/Output directory": f"output/np{np}"})

    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"np = {np}: the scene loads the plugin and runs", code == 0, err.strip()[-400:]):
        c.finish()
    directory = os.path.join(args.work_dir, "output", f"np{np}", f"rods_{np}")
    rows[np] = read_csv(os.path.join(directory, "centre_of_mass.csv"))
    listed = open(os.path.join(directory, "anvil_files.txt")).read().split()
    c.check_true(f"np = {np}: centre_of_mass.csv is listed as the run's file", "centre_of_mass.csv" in listed)

d = rows[1]
c.check("total mass of the two rods, 2 rho V", max(d["mass"]), 0.2, 1e-12, relative=True)
c.check("smallest total mass over the run", min(d["mass"]), 0.2, 1e-12, relative=True)
c.check_true("the run covers the contact (0.3 s)", d["time"][-1] > 0.29, f"last row at {d['time'][-1]}")
worst = max(abs(x - 0.5 * t) for t, x in zip(d["time"], d["x"])) / 10.0
c.check_below("largest |x_c(t) - V_c t| over the rods' length", worst, 1e-10)
worst_yz = max(max(abs(v) for v in d["y"]), max(abs(v) for v in d["z"]))
c.check_below("largest |y_c|, |z_c| (m)", worst_yz, 1e-10)
c.check_below("np = 2 against np = 1, centre of mass rows", max_relative_difference(rows[2], rows[1]), 1e-9)

# The plugin's own parameter.
for bodies, name in (("rod_b", "rod_b_only"), ("rod_b, rod_c", "unknown_body")):
    prm = test_scene(args, "tests/verification/centre_of_mass.prm", name,
                     {"Additional shared libraries": library, "Simulation/Output directory": f"output/{name}",
                      "Postprocess/centre of mass/Bodies": bodies})

    code, out, err = run_anvil(args.anvil, prm, np=1, cwd=args.work_dir)
    if name == "unknown_body":
        lines = [l for l in err.strip().splitlines() if l.startswith("anvil: error")]
        c.check_true("'Bodies = rod_b, rod_c': exit 2 and one line naming the entry",
                     code == 2 and len(lines) == 1 and "Postprocess/centre of mass/Bodies" in lines[0]
                     and "rod_c" in lines[0], err.strip()[-300:])
        continue
    if not c.check_true("'Bodies = rod_b': the run ends", code == 0, err.strip()[-400:]):
        c.finish()
    b = read_csv(os.path.join(args.work_dir, "output", name, name, "centre_of_mass.csv"))
    c.check("rod B's mass, rho V", max(b["mass"]), 0.1, 1e-12, relative=True)
    c.check("rod B's centre of mass at the start (m)", b["x"][0], 5.0, 1e-12)
    c.check("rod B's centre of mass moved by 0.3 s, against bar theory's 0.2 m", b["x"][-1] - 5.0, 0.2, 0.05,
            relative=True)
c.finish()
