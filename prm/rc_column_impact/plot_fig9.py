"""The seed's Fig. 9 from Anvil's runs: horizontal displacement of the impact
point against time, bond-slip and common-node columns on one plot.

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
for label, d in (("bond-slip", bond), ("common node", common)):
    path = os.path.join(d, "probe_impact_point.csv")
    if not os.path.exists(path):
        print(f"plot_fig9: no {path}; run that scene first")
        continue
    with open(path) as f:
        rows = list(csv.DictReader(f))
    ax.plot([1e3 * float(r["time"]) for r in rows], [-1e3 * float(r["ux"]) for r in rows], label=label)
ax.set_xlabel("time (ms)")
ax.set_ylabel("horizontal displacement of the impact point (mm)")
ax.set_title("RC column under the hammer (seed Fig. 9)")
ax.grid(True, alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(out, dpi=110)
print(f"plot_fig9: {out}")
