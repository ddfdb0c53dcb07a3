"""Plot the rod impact (seed Fig. 19) against one-dimensional wave theory.

Usage: python3 doc/figures/plot_rod_impact.py RESULT_DIR OUTPUT.png
RESULT_DIR is the output directory of prm/elastic_rod_impact (or a refined
copy). Needs matplotlib (Debian: python3-matplotlib).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

result, png = sys.argv[1], sys.argv[2]


def read(name):
    with open(f"{result}/{name}") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


v0, c, L = 1.0, 100.0, 10.0
T = 2 * L / c
fa, fb = read("probe_face_a.csv"), read("probe_face_b.csv")
cb = read("probe_centre_b.csv")
contact = read("contact_impact.csv")
t = fb["time"]


def u_face_b(s):
    return v0 / 2 * s if s < T else v0 / 2 * T + v0 * (s - T)


def v_face_b(s):
    return v0 / 2 if s < T else v0


def v_face_a(s):
    return v0 / 2 if s < T else 0.0


def v_centre_b(s):
    return 0.0 if s < L / 2 / c else (v0 / 2 if s < 1.5 * L / c else v0)


fig, ax = plt.subplots(2, 2, figsize=(10, 7))
ax[0, 0].plot(t, [10 + u for u in fb["ux"]], label="rod B face, Anvil")
ax[0, 0].plot(t, [10 + u_face_b(s) for s in t], "k--", label="bar theory")
ax[0, 0].plot(fa["time"], [10 + u for u in fa["ux"]], label="rod A face, Anvil")
ax[0, 0].set_ylabel("x-position of contact face + 10 [m]")
ax[0, 0].legend()
ax[0, 1].plot(t, fb["vx"], label="rod B face, Anvil")
ax[0, 1].plot(t, [v_face_b(s) for s in t], "k--", label="bar theory")
ax[0, 1].plot(fa["time"], fa["vx"], label="rod A face, Anvil")
ax[0, 1].plot(t, [v_face_a(s) for s in t], "k:", label="bar theory, rod A")
ax[0, 1].set_ylabel("velocity of contact face [m/s]")
ax[0, 1].legend()
ax[1, 0].plot(contact["time"], [-f for f in contact["normal_force_x"]], label="Anvil (penalty, f = 0.1)")
ax[1, 0].plot(t, [0.5 if s < T else 0 for s in t], "k--", label="bar theory, rho c A v0 / 2")
ax[1, 0].set_ylabel("contact force on rod B [N]")
ax[1, 0].legend()
ax[1, 1].plot(cb["time"], cb["vx"], label="rod B centre, Anvil")
ax[1, 1].plot(cb["time"], [v_centre_b(s) for s in cb["time"]], "k--", label="bar theory")
ax[1, 1].set_ylabel("velocity at rod B centre [m/s]")
ax[1, 1].legend()
for a in ax.flat:
    a.set_xlabel("time [s]")
    a.grid(alpha=0.3)
fig.suptitle("Two elastic rods (seed section 6.2, Fig. 19): Anvil against bar theory")
fig.tight_layout()
fig.savefig(png, dpi=110)
