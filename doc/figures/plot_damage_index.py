"""The damage index D = 1 - P_residual / P_intact over the hammer-mass and
hammer-velocity studies (the paper's criterion, Shi, Hao and Li 2008), and
the axial push of each run's last stage.

Usage: python3 doc/figures/plot_damage_index.py STUDY_DIR OUTPUT.png
STUDY_DIR holds the output directories hammer_mass_coarse/ and
hammer_velocity_coarse/ of `anvil --study prm/rc_column_impact/studies/
hammer_{mass,velocity}_coarse.prm` (each run: impact, settle, capacity).
Needs matplotlib (Debian: python3-matplotlib).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

studies, png = sys.argv[1], sys.argv[2]


def study(name):
    with open(os.path.join(studies, name, "study.csv")) as f:
        return list(csv.DictReader(f))


def reactions(name, run):
    with open(os.path.join(studies, name, run, "capacity", "reactions.csv")) as f:
        rows = list(csv.DictReader(f))
    t0 = float(rows[0]["time"])
    return ([1e3 * (float(r["time"]) - t0) * 0.25 for r in rows],
            [-1e-3 * float(r["top_fz"]) for r in rows])


fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
for lo, hi, label, colour in ((0, 0.2, "low", "#e8f5e9"), (0.2, 0.5, "medium", "#fff8e1"),
                              (0.5, 0.8, "high", "#ffebee"), (0.8, 1.0, "collapse", "#eceff1")):
    a.axhspan(lo, hi, color=colour, zorder=0)
    a.text(1290, 0.5 * (lo + hi), label, va="center", ha="right", fontsize=8, color="0.35")
for name, marker, what in (("hammer_mass_coarse", "o", "mass 220 / 270 / 310 kg at 2 m/s"),
                           ("hammer_velocity_coarse", "s", "velocity 1 / 2 / 3 m/s, 270 kg")):
    rows = study(name)
    energy = [float(r["initial_energy_J"]) for r in rows]
    D = [float(r["damage_index"]) for r in rows]
    a.plot(energy, D, marker + "-", label=what)
    for r in rows:
        t, p = reactions(name, r["run"])
        b.plot(t, p, label=f"{what.split()[0]} {r[[k for k in r if k.endswith('_plot_value')][0]]}")
a.set_xlabel("impact energy 1/2 m v^2 (J)")
a.set_ylabel("D = 1 - P_residual / P_intact")
a.set_xlim(0, 1300)
a.set_ylim(0, 1)
a.legend(fontsize=8, loc="upper left")
a.set_title("damage index (coarse column, bond-slip)")
b.axhline(880.0, color="k", lw=0.8, ls="--")
b.text(0.2, 880, "P_intact", fontsize=8)
b.set_xlabel("shortening of the push (mm)")
b.set_ylabel("axial load at the top (kN)")
b.set_title("stage 'capacity': axial push of the settled column")
b.legend(fontsize=7, ncol=2)
for ax in (a, b):
    ax.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(png, dpi=110)
