"""Plot the pull-out verification: bond stress against slip at the bar's
middle node (tests/rebar/bond_slip.py, prm/pull_out) against seed Eq. (68).

Usage: python3 doc/figures/plot_bond_slip.py BUILD_TEST_DIR OUTPUT.png
BUILD_TEST_DIR is the work directory of the ctest run
(build/tests/rebar/bond_slip). Needs matplotlib.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

work, png = sys.argv[1], sys.argv[2]
G, Smax, h = 5e10, 3.6e-4, 200.0
with open(f"{work}/output/pullout/rebar_bar.csv") as f:
    rows = list(csv.DictReader(f))
S = [1000 * float(r["probe_slip"]) for r in rows]
tau = [float(r["probe_bond_stress"]) / 1e6 for r in rows]
s_law = [i * 0.0025 for i in range(401)]
t_law = [G * s / 1000 / 1e6 if s <= 1000 * Smax else G * Smax * math.exp(-h * (s / 1000 - Smax)) / 1e6
         for s in s_law]
fig, ax = plt.subplots(figsize=(6.5, 4))
ax.plot(s_law, t_law, "k", lw=2, label="seed Eq. (68): G_s S, then tau_max exp(-h D)")
ax.plot(S, tau, "C3o", ms=3, label="Anvil, pull-out, bar's middle node")
ax.set_xlabel("slip [mm]")
ax.set_ylabel("bond stress [MPa]")
ax.set_xlim(0, 1.0)
ax.legend()
ax.set_title("16 mm bar pulled from a 0.1 m block")
fig.tight_layout()
fig.savefig(png, dpi=110)
