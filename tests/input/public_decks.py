"""Real public decks run as they come (../shared/decks, README.md there),
with what their sources state where they state it, and closed forms where
they do not.

- The Abaqus/CAE Taylor bar of pantale/DynELA-v3.0 (Taylor.inp: parts,
  instance, sets, Johnson-Cook with rate term and adiabatic heating, C3D8,
  symmetry boundaries, mm-tonne-s units), run as 'anvil Taylor.inp':
  against what Abaqus/Explicit computes for the same deck as the DynELA
  documentation states it (L_f 26.55 mm, D_f 11.22 mm, T 597.01 C,
  eps_p 1.84): length within 1 %, diameter within 2 %, temperature and
  plastic strain within 3 %; the energy balance below 1 %.
- The LS-DYNA Taylor bar of Ansys's pydyna examples (input.k with the
  LS-PrePost mesh in the ten-nodes format through *INCLUDE, a box-selected
  *RIGIDWALL_PLANAR, *INITIAL_VELOCITY_GENERATION in a *DEFINE_COORDINATE_
  SYSTEM; t-mm-s): its source states no result, so: the energy balance
  below 1 %; the bar stops at the wall (RWPNAL = 0, the nodes constrained:
  its end not beyond the plane, and no more steps than the elements alone
  need); the wall takes the bar's momentum (the bar's kinetic energy at the
  end below 1 % of the start); np = 2 writes np = 1's probe history. With
  *CONTROL_CONTACT's RWPNAL = 1 added, a penalty wall: its end no further
  than 2 % of an element beyond the plane, the penetration reported.
- The LSTC projectile and plate (projectile.k, *CASE blocks, *INCLUDE,
  g-cm-us; its contact cards are commented out, so the projectile passes
  through the plate): case 101 translates the projectile rigidly, its
  displacement v t within 1e-9 and its kinetic energy kept to 1e-12, no
  internal energy; case 102 starts at rest and stays there.
"""
import os
from anvil_test import Checker, arguments, read_csv, run_anvil
from anvil_vtu import arrays, read_grid  # (anvil_test puts scripts/ on the path)
from vtk.util.numpy_support import vtk_to_numpy
import numpy as np

args = arguments()
c = Checker("public decks run as they come")
decks = os.path.join(os.path.abspath(args.source_dir), "..", "shared", "decks")
quiet = ("--set", "Simulation/Print wall times=false")
if not c.check_true(f"the decks are there ({decks})", os.path.isdir(decks)):
    c.finish()


def run(deck, np_=1, extra=(), sub=""):
    cwd = os.path.join(args.work_dir, sub) if sub else args.work_dir
    os.makedirs(cwd, exist_ok=True)
    code, out, err = run_anvil(args.anvil, os.path.join(decks, deck), np=np_, cwd=cwd, extra_args=quiet + extra)
    ok = c.check_true(f"anvil {deck} {' '.join(extra)} (np = {np_}) exits 0", code == 0, err.strip()[-300:])
    return ok, out, os.path.join(cwd, "output", os.path.splitext(os.path.basename(deck))[0])


# DynELA's Abaqus Taylor bar.
ok, out, d = run("dynela-taylor/Taylor.inp", extra=("--set", "Simulation/Output interval=8e-5"))
if ok:
    grid = read_grid(os.path.join(d, "solution_0001.pvtu"))
    X = vtk_to_numpy(grid.GetPoints().GetData())
    x = X + arrays(grid.GetPointData())["displacement"]
    cells = arrays(grid.GetCellData())
    base = X[:, 1] < 1e-9
    L_f = x[:, 1].max()
    D_f = 2 * np.sqrt(x[base, 0] ** 2 + x[base, 2] ** 2).max()
    print(f"  Anvil: L_f {L_f:.2f} mm, D_f {D_f:.2f} mm, T {cells['temperature'].max():.1f} C, "
          f"eps_p {cells['effective_plastic_strain'].max():.3f} (Abaqus: 26.55, 11.22, 597.01, 1.84)")
    c.check("Taylor.inp: final length against Abaqus's [mm]", L_f, 26.55, 0.01, relative=True)
    c.check("Taylor.inp: final diameter against Abaqus's [mm]", D_f, 11.22, 0.02, relative=True)
    c.check("Taylor.inp: largest temperature against Abaqus's [C]", cells["temperature"].max(), 597.01, 0.03,
            relative=True)
    c.check("Taylor.inp: largest effective plastic strain against Abaqus's",
            cells["effective_plastic_strain"].max(), 1.84, 0.03, relative=True)
    e = read_csv(os.path.join(d, "energy.csv"))
    c.check_below("Taylor.inp: largest energy balance error", max(abs(v) for v in e["balance_error"]), 0.01)
    c.check_true("Taylor.inp: the warning says where Anvil differs (C3D8 as one-point elements)", "C3D8" in out)

# pydyna's LS-DYNA Taylor bar. Its wall constrains the nodes (RWPNAL = 0,
# LS-DYNA's default): Anvil's kinematic contact, which never lowers the
# step. The same deck with *CONTROL_CONTACT's RWPNAL = 1 (written here
# beside a copy of the deck) meets the wall by a penalty instead.
energies = []
for np_ in (1, 2):
    ok, out, d = run("pydyna-taylor/input.k", np_=np_, sub=f"pydyna_np{np_}",
                     extra=("--set", "Probes=tail", "--set", "Probe tail/Point=0, 10, 0", "--set", "Probe tail/Body=bar"))
    if not ok:
        continue
    energies.append(open(os.path.join(d, "probe_tail.csv")).read())
    if np_ == 1:
        e = read_csv(os.path.join(d, "energy.csv"))
        c.check_below("input.k: largest energy balance error", max(abs(v) for v in e["balance_error"]), 0.01)
        c.check_below("input.k: the bar's kinetic energy at the end over the start", e["kinetic"][-1] / e["kinetic"][0],
                      0.01)
        b = read_csv(os.path.join(d, "bodies.csv"))
        bar = b["body"].index("bar")
        print(f"  Anvil: the bar's length at the end {b['ymax'][bar] - b['ymin'][bar]:.2f} mm (30 mm at the start; "
              f"its source states no result)")
        # The constraint leaves no node behind the plane y = 40.1 mm
        # (round-off of mm coordinates: 1e-9 of them).
        c.check_below("input.k (RWPNAL = 0): the bar's end beyond the wall at y = 40.1 mm [mm]",
                      b["ymax"][bar] - 40.1, 40.1e-9)
        summary = dict(l.strip().split(",", 1) for l in open(os.path.join(d, "summary.csv")) if "," in l)
        steps, alone = float(summary["steps"]), float(summary["steps_elements_only"])
        print(f"  steps {steps:.0f}, the elements alone {alone:.1f}")
        # (The step is held while it stays within 1 % of the stable one:
        # time_integration.cc. A penalty wall at factor 1 takes 1.064.)
        c.check_below("input.k (RWPNAL = 0): steps over those the elements alone need", steps / alone, 1.01)
        c.check_below("input.k (RWPNAL = 0): the deepest penetration left at a step's end (summary.csv) [mm]",
                      float(summary["contact_wall1_bar_max_penetration"]), 40.1e-9)
        c.check_true("input.k: the run's last line names the kinematic wall and its penetration",
                     "contact pair 'wall1_bar' (kinematic): deepest penetration left at a step's end" in out)
if len(energies) == 2:
    c.check_true("input.k: np = 2 writes the probe history of np = 1 (a probe added with --set; bitwise)",
                 energies[0] == energies[1])

deck = open(os.path.join(decks, "pydyna-taylor", "input.k")).read()
at = deck.upper().index("*RIGIDWALL_PLANAR")
penalty_dir = os.path.join(args.work_dir, "pydyna_rwpnal")
os.makedirs(penalty_dir, exist_ok=True)
for f in os.listdir(os.path.join(decks, "pydyna-taylor")):
    if f != "input.k" and f.endswith(".k"):
        dst = os.path.join(penalty_dir, f)
        if not os.path.exists(dst):
            os.symlink(os.path.join(decks, "pydyna-taylor", f), dst)
with open(os.path.join(penalty_dir, "input.k"), "w") as f:
    f.write(deck[:at] + "*CONTROL_CONTACT\n$   slsfac    rwpnal\n       0.1       1.0\n" + deck[at:])
code, out, err = run_anvil(args.anvil, "input.k", cwd=penalty_dir, extra_args=quiet)
if c.check_true("input.k with RWPNAL = 1 exits 0", code == 0, err.strip()[-300:]):
    d = os.path.join(penalty_dir, "output", "input")
    e = read_csv(os.path.join(d, "energy.csv"))
    c.check_below("input.k (RWPNAL = 1): largest energy balance error", max(abs(v) for v in e["balance_error"]), 0.01)
    b = read_csv(os.path.join(d, "bodies.csv"))
    bar = b["body"].index("bar")
    # Elements are about 1 mm long along the bar.
    c.check_below("input.k (RWPNAL = 1): the bar's end beyond the wall at y = 40.1 mm [mm]", b["ymax"][bar] - 40.1,
                  0.02)
    # The contact's own error, in summary.csv and a line at the end:
    # the run's deepest penetration is at least any history row's.
    summary = dict(l.strip().split(",", 1) for l in open(os.path.join(d, "summary.csv")) if "," in l)
    history = read_csv(os.path.join(d, "contact_wall1_bar.csv"))
    deepest = float(summary.get("contact_wall1_bar_max_penetration", "nan"))
    c.check_true("input.k (RWPNAL = 1): summary.csv's deepest penetration is the run's (>= every history row's, > 0)",
                 deepest >= max(history["max_penetration"]) > 0,
                 f"{deepest} against {max(history['max_penetration'])}")
    c.check_true("input.k (RWPNAL = 1): the run's last lines give the penetration and the springs' energy",
                 "contact pair 'wall1_bar': deepest penetration" in out and "% of the initial energy" in out)
    print(f"  RWPNAL = 1: steps {summary['steps']}, the elements alone {float(summary['steps_elements_only']):.1f}")

# The LSTC projectile, both cases.
ok, out, d = run("lstc-projectile-plate/projectile.k", extra=("--case", "101"), sub="case101")
if ok:
    e = read_csv(os.path.join(d, "energy.csv"))
    b = read_csv(os.path.join(d, "bodies.csv"))
    p = b["body"].index("projectile")
    c.check("case 101: kinetic energy kept (rigid translation)", e["kinetic"][-1], e["kinetic"][0], 1e-12,
            relative=True)
    c.check_below("case 101: largest internal energy over the kinetic", max(e["internal"]) / e["kinetic"][0], 1e-12)
    # 0.0623 cm/us along x for 70 us; the nodes' x range moves with it.
    ok0, out0, d0 = run("lstc-projectile-plate/projectile.k", extra=("--case", "102"), sub="case102")
    if ok0:
        b0 = read_csv(os.path.join(d0, "bodies.csv"))
        c.check("case 101: the projectile's displacement against v t [cm]", b["xmin"][p] - b0["xmin"][p],
                0.0623 * 70, 1e-9, relative=True)
        e0 = read_csv(os.path.join(d0, "energy.csv"))
        c.check_below("case 102: the largest kinetic energy (at rest)", max(e0["kinetic"]), 0.0)
c.finish()
