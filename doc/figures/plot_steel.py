"""Plot the plastic-kinematic steel's material-point curves (Table 1 steel):
uniaxial tension at three strain rates against the closed form, and a
tension-compression cycle for kinematic and isotropic hardening.

Usage: python3 doc/figures/plot_steel.py ANVIL OUTPUT.png
ANVIL is the anvil executable; the driver files are written to a scratch
directory. Needs matplotlib (Debian: python3-matplotlib).
"""
import csv
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

anvil, png = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp()
E, s0, Et, C, P = 206e9, 335e6, 1.2e9, 40.0, 5.0
Ep = E * Et / (E - Et)


def drive(name, rate, path, effects, beta):
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(f"""set Output file = {name}.csv
subsection Material
  set Model = plastic kinematic
  subsection plastic kinematic
    set Preset = Table 1 steel
    set Hardening parameter beta = {beta}
    set Strain rate effects = {effects}
  end
end
subsection Loading
  set Strain rate = {rate}
  set Strain path = {path}
  set Strain increment = 1e-5
end
""")
    subprocess.run([anvil, "--material-point", prm], cwd=work, check=True, capture_output=True)
    with open(os.path.join(work, name + ".csv")) as f:
        rows = list(csv.DictReader(f))
    return [float(r["strain_xx"]) for r in rows], [float(r["stress_xx"]) / 1e6 for r in rows]


fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
for rate, effects, colour in ((1, "false", "k"), (40, "true", "C0"), (400, "true", "C3")):
    e, s = drive(f"t{rate}", rate, "0.05", effects, 0)
    R = 1 + (rate / C) ** (1 / P) if effects == "true" else 1
    label = "rate-free" if effects == "false" else f"{rate} 1/s"
    ax[0].plot([100 * x for x in e], s, colour, label=f"Anvil, {label}")
    ax[0].plot([5], [(R * s0 + Ep * 0.05) / (1 + Ep / E) / 1e6], colour + "o", mfc="none")
ax[0].set_xlabel("logarithmic strain [%]")
ax[0].set_ylabel("Cauchy stress [MPa]")
ax[0].set_title("uniaxial tension (circles: Eq. (63) closed form at 5 %)")
ax[0].legend()
for beta, colour, label in ((0, "C0", "kinematic (beta = 0)"), (1, "C3", "isotropic (beta = 1)")):
    e, s = drive(f"c{beta}", 1, "0.02, -0.02, 0.02", "false", beta)
    ax[1].plot([100 * x for x in e], s, colour, label=label)
ax[1].set_xlabel("logarithmic strain [%]")
ax[1].set_ylabel("Cauchy stress [MPa]")
ax[1].set_title("tension-compression cycle, rate-free")
ax[1].legend()
fig.tight_layout()
fig.savefig(png, dpi=110)
