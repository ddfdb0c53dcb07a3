"""Erosion of cracked concrete: the bar of tests/concrete/pulled_bar.prm (100 x
10 x 10 mm, 20 x 2 x 2 elements, weakened row just beyond mid-length) pulled
at 5 mm/s with 'Erosion principal strain' = 0.02.

Only the weakened row cracks, and its elements hold all the stretch once the
rest unloads, so they fail together when the row's logarithmic strain
reaches eps_f: at the end displacement u_f = h (exp(eps_f) - 1) + sigma (L -
h) / E (row opening plus the elastic stretch of the rest at the stress
sigma the probe reads then), i.e. at t_f = u_f / v.

Checks:
- exactly the weakened row erodes (2 x 2 elements, centres within it);
- the erosion time against t_f (2 %);
- the force at the fixed end is zero after erosion (mean over the last 20 %
  of the run, the separated halves ring);
- the energy balance with the energy of the eroded elements in its own
  column (1 %, from 5 % of the erosion time on: before, the impulsive start
  of the pulled face dominates energies of micro-joules), and that column
  against the sum over erosion.csv;
- the VTU fields read back: exactly those cells flagged 'eroded', with
  max_principal_strain >= eps_f and tensile_damage > 0.95; no tensile
  damage anywhere else;
- 'Erosion damage' = 0.99 instead: the same elements, with d >= 0.99;
- np = 2 erodes the same elements, with the same energy history (1e-8).
"""
import math
import os
from anvil_test import (Checker, arguments, max_relative_difference, read_csv, read_vtu_cells, run_anvil,
                        test_scene)
import concrete_reference as ref

args = arguments()
c = Checker("erosion of cracked concrete")
fc = 45.4e6
L, n = 0.1, 20
dx = L / n
eps_f = 0.02
v = 0.005
end_time = 1.5 * dx * (math.exp(eps_f) - 1) / v
cdp = "Body bar/Material/concrete damaged plasticity/"
overrides = {**ref.pulled_bar_overrides(n, end_time, end_time / 300, lateral=2), cdp + "Erosion": "true",
             cdp + "Erosion principal strain": eps_f}
results = {}
for np in (1, 2):
    name = f"concrete_erosion_np{np}"
    prm = test_scene(args, "tests/concrete/pulled_bar.prm", name, overrides)
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"np = {np}: anvil exits 0", code == 0, err.strip()):
        c.finish()
    d = os.path.join(args.work_dir, "output", name)
    erosion_file = os.path.join(d, "erosion.csv")
    if not c.check_true(f"np = {np}: erosion.csv written", os.path.exists(erosion_file)):
        c.finish()
    results[np] = (read_csv(os.path.join(d, "energy.csv")), read_csv(erosion_file),
                   read_csv(os.path.join(d, "probe_end.csv")))

energy, erosion, probe = results[1]
x_row = (0.5 * L, 0.5 * L + dx)
c.check("eroded elements", len(erosion["element"]), 4, 0)
c.check_true("every eroded element lies in the weakened row",
             all(x_row[0] < x < x_row[1] for x in erosion["x"]), str(erosion["x"]))
t_e = min(erosion["time"])
c.check_below("spread of the erosion times of the row / t_e", (max(erosion["time"]) - t_e) / t_e, 0.01)
# The stress the rest of the bar carries when the row fails.
i_e = min(range(len(probe["time"])), key=lambda i: abs(probe["time"][i] - t_e))
E = ref.mc2010_elastic_limit(fc)[1]
sigma = probe["stress_xx"][i_e]
t_f = (dx * (math.exp(eps_f) - 1) + sigma * (L - dx) / E) / v
print(f"  stress carried at erosion {sigma / 1e6:.3f} MPa")
c.check("erosion time (s) against u_f / v", t_e, t_f, 0.02, relative=True)
peak = max(probe["stress_xx"])
tail = probe["stress_xx"][-60:]
c.check_below("stress at the fixed end over the last 20 % of the run (mean) / peak",
              abs(sum(tail) / len(tail)) / peak, 0.02)
c.check("eroded energy column / sum over erosion.csv", energy["eroded"][-1], sum(erosion["energy"]),
        1e-9, relative=True)
# The pulled face starts impulsively at v: the first steps' balance is
# measured against energies of 1e-9 J; judged from 5 % of t_e on.
late = [b for t, b in zip(energy["time"], energy["balance_error"]) if t > 0.05 * t_e]
c.check_below("largest energy balance error from 0.05 t_e on (with eroded energy)", max(late), 0.01)

# The field output at the end: the 'eroded' flag, damage and the largest
# principal strain per element, read back from the VTU file.
cells = read_vtu_cells(os.path.join(args.work_dir, "output", "concrete_erosion_np1", "solution_0001.0.vtu"))
eroded = [i for i, f in enumerate(cells["eroded"]) if f > 0.5]
intact = [i for i in range(len(cells["eroded"])) if i not in eroded]
c.check("VTU: cells flagged 'eroded'", len(eroded), 4, 0)
c.check_below("VTU: largest tensile_damage of the intact cells (they never cracked)",
              max(cells["tensile_damage"][i] for i in intact), 0.0)
c.check_below("VTU: eps_f - smallest max_principal_strain of the eroded cells",
              eps_f - min(cells["max_principal_strain"][i] for i in eroded), 1e-6)
c.check_below("VTU: 0.95 - smallest tensile_damage of the eroded cells (cracks past w_1)",
              0.95 - min(cells["tensile_damage"][i] for i in eroded), 0.0)

# The other criterion: 'Erosion damage' = 0.99 instead of the strain.
name = "concrete_erosion_damage"
prm = test_scene(args, "tests/concrete/pulled_bar.prm", name,
                 {**overrides, cdp + "Erosion principal strain": 0, cdp + "Erosion damage": 0.99})
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if c.check_true("damage criterion: anvil exits 0", code == 0, err.strip()):
    d = os.path.join(args.work_dir, "output", name)
    erosion_d = read_csv(os.path.join(d, "erosion.csv"))
    cells_d = read_vtu_cells(os.path.join(d, "solution_0001.0.vtu"))
    eroded_d = [i for i, f in enumerate(cells_d["eroded"]) if f > 0.5]
    c.check_true("damage criterion: the same 4 elements erode",
                 sorted(erosion_d["element"]) == sorted(erosion["element"]), str(erosion_d["element"]))
    c.check_below("damage criterion: 0.99 - smallest damage of the eroded cells (VTU, single precision)",
                  0.99 - min(cells_d["damage"][i] for i in eroded_d), 1e-6)
    c.check_true("damage criterion: erodes before the strain criterion",
                 max(erosion_d["time"]) < t_e, f"{max(erosion_d['time']):.5g} s against {t_e:.5g} s")

energy2, erosion2, _ = results[2]
c.check_below("np = 2 against np = 1: largest relative difference of energy.csv",
              max_relative_difference(energy, energy2), 1e-8)
c.check_true("np = 2 erodes the same elements", sorted(erosion2["element"]) == sorted(erosion["element"]),
             f"{len(erosion2['element'])} against {len(erosion['element'])}")
c.finish()
