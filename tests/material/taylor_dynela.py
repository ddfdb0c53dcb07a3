"""A public Abaqus deck's Taylor bar run by Anvil with the Johnson-Cook
metal: the quarter bar of 42CrMo4 of pantale/DynELA-v3.0
(../shared/decks/dynela-taylor/Taylor.inp, its mesh read as it is; the
scene, doc/examples/dynela_taylor/taylor.prm, says what the deck's keywords
say),
32.4 mm long, 6.4 mm in diameter, at 287 m/s onto a rigid frictionless
wall (the impact face held in y), 80 us, adiabatic.

Against what Abaqus/Explicit computes for the same deck, as the DynELA
documentation states it (Documentation/ImpactSamples.tex, "3D Taylor
impact": L_f 26.55 mm, D_f 11.22 mm, T 597.01 degrees C, eps_p 1.84 at the
centre of the impact face):
- final length within 1 %, final diameter of the impact face within 2 %;
- the largest temperature and effective plastic strain within 3 % (the
  centre element's, where both peak);
- the energy balance below 1 %;
- np = 2 writes np = 1's probe history (bitwise).
Anvil's elements are one-point (C3D8R): the deck's C3D8 is ABAQUS's
selectively reduced hexahedron, and Anvil's full integration has no
selective reduction (it would lock in plastic flow).
"""
import os
from anvil_test import Checker, arguments, read_csv, run_anvil, write_scene
from anvil_vtu import arrays, read_grid  # (anvil_test puts scripts/ on the path)
from vtk.util.numpy_support import vtk_to_numpy
import numpy as np

args = arguments()
c = Checker("the DynELA Taylor bar (Abaqus deck) with Johnson-Cook")
deck = os.path.join(os.path.abspath(args.source_dir), "..", "shared", "decks", "dynela-taylor", "Taylor.inp")
if not c.check_true(f"the deck is there ({deck})", os.path.exists(deck)):
    c.finish()
example = os.path.join(os.path.abspath(args.source_dir), "doc", "examples", "dynela_taylor", "taylor.prm")
overrides = f"""
subsection Simulation
  set Output interval = 8e-5
  set Print wall times = false
end
subsection Body bar
  subsection Mesh
    set File name = {deck}
  end
end
"""
results = {}
for np_ in (1, 2):
    name = f"taylor_np{np_}"
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"), include=example, text=overrides)
    code, out, err = run_anvil(args.anvil, prm, np=np_, cwd=args.work_dir)
    if not c.check_true(f"np = {np_}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    results[np_] = os.path.join(args.work_dir, "output", name)

d = results[1]
grid = read_grid(os.path.join(d, "solution_0001.pvtu"))
X = vtk_to_numpy(grid.GetPoints().GetData())
x = X + arrays(grid.GetPointData())["displacement"]
cells = arrays(grid.GetCellData())
base = X[:, 1] < 1e-9
L_f = 1e3 * x[:, 1].max()
D_f = 2e3 * np.sqrt(x[base, 0] ** 2 + x[base, 2] ** 2).max()
print(f"  Anvil: L_f {L_f:.2f} mm, D_f {D_f:.2f} mm, T {cells['temperature'].max():.1f} C, "
      f"eps_p {cells['effective_plastic_strain'].max():.3f} (Abaqus: 26.55, 11.22, 597.01, 1.84)")
c.check("final length against Abaqus's [mm]", L_f, 26.55, 0.01, relative=True)
c.check("final diameter of the impact face against Abaqus's [mm]", D_f, 11.22, 0.02, relative=True)
c.check("largest temperature against Abaqus's [C]", cells["temperature"].max(), 597.01, 0.03, relative=True)
c.check("largest effective plastic strain against Abaqus's", cells["effective_plastic_strain"].max(), 1.84, 0.03,
        relative=True)

e = read_csv(os.path.join(d, "energy.csv"))
c.check_below("largest energy balance error", max(abs(v) for v in e["balance_error"]), 0.01)
p1 = open(os.path.join(results[1], "probe_top.csv")).read()
p2 = open(os.path.join(results[2], "probe_top.csv")).read()
c.check_true("np = 2 writes the probe history of np = 1 (bitwise)", p1 == p2)
c.finish()
