"""The seed's Fig. 16 from an Anvil run of the column: compressive damage on
the struck face, tensile damage on the far face, and tensile damage on the
vertical section through the impact point, from the last VTU frame.

Usage (from the top directory, after the scene has run):
  /usr/bin/python3 prm/rc_column_impact/plot_fig16.py [OUTPUT_DIR [OUT.png]]
Default: output/rc_column_impact, written to OUTPUT_DIR/fig16_damage.png.
Needs matplotlib; reads the VTU pieces of every process.
"""
import glob
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from anvil_vtu import read_vtu  # noqa: E402

directory = sys.argv[1] if len(sys.argv) > 1 else "output/rc_column_impact"
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(directory, "fig16_damage.png")
frames = sorted({os.path.basename(p).split(".")[0] for p in glob.glob(os.path.join(directory, "solution_*.vtu"))})
if not frames:
    sys.exit(f"plot_fig16: no solution_*.vtu in {directory}")
last = frames[-1]
centres, cells = [], {}
for piece in sorted(glob.glob(os.path.join(directory, last + ".*.vtu"))):
    c, v = read_vtu(piece)
    centres += c
    for k, values in v.items():
        cells.setdefault(k, []).extend(values)
column = [i for i, b in enumerate(cells["body"]) if b == 0]
xs = [centres[i][0] for i in column]
x_max, x_min = max(xs), min(xs)
ys = sorted({round(centres[i][1], 6) for i in column})
y_mid = min(ys, key=abs)


def panel(ax, select, horizontal, field, title):
    pts = [i for i in column if select(centres[i])]
    sc = ax.scatter([1e3 * centres[i][horizontal] for i in pts], [1e3 * centres[i][2] for i in pts],
                    c=[cells[field][i] for i in pts], cmap="inferno_r", vmin=0, vmax=1, marker="s", s=18)
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("y (mm)" if horizontal == 1 else "x (mm)")
    ax.set_aspect("auto")
    return sc


fig, axes = plt.subplots(1, 3, figsize=(9, 6), sharey=True)
panel(axes[0], lambda p: p[0] >= x_max - 1e-9, 1, "compressive_damage", "struck face:\ncompressive damage")
panel(axes[1], lambda p: p[0] <= x_min + 1e-9, 1, "tensile_damage", "far face:\ntensile damage")
sc = panel(axes[2], lambda p: abs(p[1] - y_mid) < 1e-9, 0, "tensile_damage",
           "section through the impact point:\ntensile damage")
axes[0].set_ylabel("height z (mm)")
fig.colorbar(sc, ax=axes, shrink=0.6, label="damage")
fig.suptitle(f"RC column, {last} (seed Fig. 16)")
fig.savefig(out, dpi=110)
print(f"plot_fig16: {out}")
