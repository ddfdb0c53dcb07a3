"""The seed's Fig. 9 from Anvil's runs: horizontal displacement of the impact
point (the centre of mass of the section at the impact height) against
time, bond-slip and common-node columns on one plot, with the struck face's
node under the nose dashed.

Usage (from the top directory, after both scenes have run):
  /usr/bin/python3 prm/rc_column_impact/plot_fig9.py [BOND_DIR COMMON_DIR [OUT.png]]
Defaults: output/rc_column_impact and output/rc_column_impact_common_node,
written to output/rc_column_impact/fig9_couplings.png; the coarse pair with
'--coarse'.
"""
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

args = [a for a in sys.argv[1:] if not a.startswith("--")]
suffix = "_coarse" if "--coarse" in sys.argv else ""
bond = args[0] if len(args) > 0 else f"output/rc_column_impact{suffix}"
common = args[1] if len(args) > 1 else f"output/rc_column_impact_common_node{suffix}"
out = args[2] if len(args) > 2 else os.path.join(bond, "fig9_couplings.png")

fig, ax = plt.subplots(figsize=(7, 4.2))
for (label, d), colour in zip((("bond-slip", bond), ("common node", common)), ("C0", "C1")):
    path = os.path.join(d, "probe_impact_point.csv")
    if not os.path.exists(path):
        print(f"plot_fig9: no {path}; run that scene first")
        continue
    # The impact point (the section's centre of mass), and thin and dashed
    # the struck face's node under the nose where the scene has that probe.
    for name, style, what in (("impact_point", "-", "section"), ("struck_face", "--", "struck face's node")):
        path = os.path.join(d, f"probe_{name}.csv")
        if not os.path.exists(path):
            continue
        with open(path) as f:
            rows = list(csv.DictReader(f))
        ax.plot([1e3 * float(r["time"]) for r in rows], [-1e3 * float(r["ux"]) for r in rows], style,
                color=colour, lw=1.6 if style == "-" else 0.9, label=f"{label}: {what}")
ax.set_xlabel("time (ms)")
ax.set_ylabel("horizontal displacement at the impact height (mm)")
ax.set_title("RC column under the hammer (seed Fig. 9)")
ax.grid(True, alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(out, dpi=110)
print(f"plot_fig9: {out}")
