"""Plot the Hertz verification: contact force against time for a rigid
sphere on an elastic block (tests/contact/hertz_rigid_sphere.py) at its
three speeds and two meshes, against Hertz's impact solution m d''(t) = -K d^(3/2),
K = 4/3 E* R^(1/2) (Johnson, Contact Mechanics, 11.4), integrated by RK4.

Usage: python3 doc/figures/plot_hertz.py BUILD_TEST_DIR OUTPUT.png
BUILD_TEST_DIR is the work directory of the ctest run
(build/tests/contact/hertz_rigid_sphere). Needs matplotlib.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

work, png = sys.argv[1], sys.argv[2]
E, nu, R, m = 1e7, 0.3, 0.05, 1.0
K = 4 / 3 * E / (1 - nu ** 2) * math.sqrt(R)


def hertz(v, h=1e-6):
    """Force against time from first contact, RK4."""
    t, d, w = 0.0, 0.0, v
    ts, fs = [0.0], [0.0]
    acc = lambda dd: -K * max(dd, 0) ** 1.5 / m
    while d >= 0 or t < 1e-4:
        k1 = (w, acc(d))
        k2 = (w + 0.5 * h * k1[1], acc(d + 0.5 * h * k1[0]))
        k3 = (w + 0.5 * h * k2[1], acc(d + 0.5 * h * k2[0]))
        k4 = (w + h * k3[1], acc(d + h * k3[0]))
        d += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        w += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        t += h
        ts.append(t)
        fs.append(K * max(d, 0) ** 1.5)
    return ts, fs


def anvil(n, v):
    with open(f"{work}/output/hertz_{n}_{v}/hertz_rigid_sphere/rigid_ball.csv") as f:
        rows = list(csv.DictReader(f))
    # Time 0 of Hertz is first contact; the sphere starts 10 um above.
    t0 = 1e-5 / v
    return [1e3 * (float(r["time"]) - t0) for r in rows], [4 * float(r["fz"]) for r in rows]


fig, ax = plt.subplots(figsize=(7, 4.2))
for k, v in enumerate((0.05, 0.1, 0.2)):
    ts, fs = hertz(v)
    ax.plot([1e3 * x for x in ts], fs, "k", lw=2, label="Hertz (half-space, rigid sphere)" if k == 0 else None)
    ax.plot(*anvil(24, v), f"C{k}-", label=f"Anvil, {v} m/s, 24^3 graded quarter block")
ax.plot(*anvil(16, 0.1), "C1--", label="Anvil, 0.1 m/s, 16^3")
ax.set_xlabel("time from first contact [ms]")
ax.set_ylabel("contact force [N]")
ax.set_xlim(-0.5, 16)
ax.legend(fontsize=8)
ax.set_title("rigid sphere (R 50 mm, 1 kg) on an elastic block, kinematic contact")
fig.tight_layout()
fig.savefig(png, dpi=110)
