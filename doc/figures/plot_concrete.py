"""Plot the concrete damaged plasticity at a material point (f'c = 45.4 MPa,
MC2010 curves): uniaxial compression with an unloading branch against
MC2010 Eq. (5.1-26), tension for two crack-band lengths (and with the
lateral strains held: the tension cut-off), and compression at
four strain rates.

Usage: python3 doc/figures/plot_concrete.py ANVIL OUTPUT.png
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

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests"))
import concrete_reference as ref  # noqa: E402

anvil, png = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp()
fc = 45.4e6


def drive(name, path, rate=1e-5, h=0.05, extra="", inc=2e-6, mode="uniaxial stress"):
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(f"set Output file = {name}.csv\n{ref.material_block(fc, extra)}"
                f"subsection Loading\n  set Mode = {mode}\n  set Strain rate = {rate}\n  set Strain path = {path}\n"
                f"  set Strain increment = {inc}\n  set Characteristic length = {h}\nend\n")
    subprocess.run([anvil, "--material-point", prm], cwd=work, check=True, capture_output=True)
    with open(os.path.join(work, name + ".csv")) as f:
        rows = list(csv.DictReader(f))
    return [float(r["strain_xx"]) for r in rows], [float(r["stress_xx"]) for r in rows]


fig, ax = plt.subplots(1, 3, figsize=(13, 4))
e, s = drive("c", "-0.0034, -0.0024, -0.005")
ax[0].plot([-x * 1e3 for x in e], [-y / 1e6 for y in s], label="Anvil (driver)")
E_ci, eps_c1, eps_lim, k = ref.mc2010_constants(fc)
xs = [eps_lim * i / 200 for i in range(201)]
ax[0].plot([x * 1e3 for x in xs], [ref.mc2010_compression(fc, x) / 1e6 for x in xs], "k--",
           label="MC2010 Eq. (5.1-26)")
ax[0].set(xlabel="compressive strain (per mille)", ylabel="compressive stress (MPa)",
          title="uniaxial compression, unloading")
ax[0].legend()
G, ft = ref.mc2010_fracture_energy(fc), ref.mc2010_tensile_strength(fc)
for h in (0.02, 0.1):
    e, s = drive(f"t{h}", f"{1.2 * 5 * G / ft / h}", h=h, inc=5 * G / ft / h / 4000)
    ax[1].plot([x * h * 1e3 for x in e], [y / 1e6 for y in s], label=f"h = {h * 1000:.0f} mm")
e, s = drive("t_confined", f"{1.2 * 5 * G / ft / 0.02}", h=0.02, inc=5 * G / ft / 0.02 / 4000,
             mode="uniaxial strain")
ax[1].plot([x * 0.02 * 1e3 for x in e], [y / 1e6 for y in s], "--",
           label="h = 20 mm, lateral strain held")
ax[1].set(xlabel="h x strain (mm): crack opening", ylabel="tensile stress (MPa)",
          title=f"tension, crack band (G_F = {G:.0f} J/m^2)")
ax[1].legend()
for rate in (1e-5, 1.0, 10.0, 100.0):
    e, s = drive(f"r{rate}", "-0.006", rate=rate, extra="    set Strain rate effects = true\n")
    ax[2].plot([-x * 1e3 for x in e], [-y / 1e6 for y in s], label=f"{rate:g} 1/s")
    ax[2].axhline(fc * ref.cdif(rate, fc / 0.8) / 1e6, color="gray", lw=0.5, ls=":")
ax[2].set(xlabel="compressive strain (per mille)", ylabel="compressive stress (MPa)",
          title="rate: peaks at CDIF x f'c (dotted)")
ax[2].legend()
fig.tight_layout()
fig.savefig(png, dpi=110)
