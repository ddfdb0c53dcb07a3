"""PNG plots beside a run's CSV histories (called by anvil at the end of a
run with 'Plots = true', or by hand: python3 anvil_plot.py OUTPUT_DIR).

One figure per file: energies (seed Fig. 10), each probe's displacement
(Fig. 9), each contact pair's force, the support reactions and each rigid
body's velocity. Needs matplotlib; without it, says so and exits 3.
"""
import csv
import glob
import os
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("plots skipped: matplotlib is not installed (Debian: python3-matplotlib)")
    sys.exit(3)


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]} if rows else {}


def figure(path, title, ylabel, curves, scale=1.0, xscale=1e3):
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for label, t, y in curves:
        ax.plot([xscale * v for v in t], [scale * v for v in y], label=label)
    ax.set_xlabel("time (ms)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    if len(curves) > 1:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(directory):
    made = []
    e = read(os.path.join(directory, "energy.csv"))
    if e:
        names = ["kinetic", "internal", "hourglass", "viscous", "damping", "contact", "friction", "eroded",
                 "removed", "bond",
                 "external_work", "total"]
        figure(os.path.join(directory, "energy.png"), "energies", "energy (J)",
               [(n, e["time"], e[n]) for n in names if n in e and max(map(abs, e[n])) > 0])
        made.append("energy.png")
    for path in sorted(glob.glob(os.path.join(directory, "probe_*.csv"))):
        p = read(path)
        name = os.path.basename(path)[6:-4]
        figure(path[:-4] + ".png", f"probe {name}: displacement", "displacement (mm)",
               [(c, p["time"], p[c]) for c in ("ux", "uy", "uz")], scale=1e3)
        made.append(os.path.basename(path)[:-4] + ".png")
    for path in sorted(glob.glob(os.path.join(directory, "contact_*.csv"))):
        p = read(path)
        name = os.path.basename(path)[8:-4]
        figure(path[:-4] + ".png", f"contact pair {name}: force on its first body", "force (kN)",
               [(c, p["time"], p[c]) for c in ("normal_force_x", "normal_force_y", "normal_force_z")],
               scale=1e-3)
        made.append(os.path.basename(path)[:-4] + ".png")
    r = read(os.path.join(directory, "reactions.csv")) if os.path.exists(
        os.path.join(directory, "reactions.csv")) else {}
    if r:
        figure(os.path.join(directory, "reactions.png"), "support reactions (force on the body)",
               "force (kN)", [(c, r["time"], r[c]) for c in r if c != "time"], scale=1e-3)
        made.append("reactions.png")
    for path in sorted(glob.glob(os.path.join(directory, "rigid_*.csv"))):
        p = read(path)
        name = os.path.basename(path)[6:-4]
        figure(path[:-4] + ".png", f"rigid body {name}: velocity", "velocity (m/s)",
               [(c, p["time"], p[c]) for c in ("vx", "vy", "vz")])
        made.append(os.path.basename(path)[:-4] + ".png")
    print("plots: " + ", ".join(made))


if __name__ == "__main__":
    main(sys.argv[1])
