"""Crush band: 'Crush band length' l_c regularises the compression curve's
softening by the element's characteristic length h, as the crack band does
in tension.

Closed form at a material point (f'c = 45.4 MPa, MC2010 curves, uniaxial
stress, driven to a compressive strain of 0.01 at 0.1/s): beyond the peak,
a point of length h reads the curve at e_p + (e_in - e_p) h / l_c, where e_in
= |eps| - |sigma| / E is its inelastic strain and e_p that at the peak. So
a point with h = l_c / 4 must carry, at inelastic strain e, the stress the
unregularised point (h = l_c) carries at e_p + (e - e_p) / 4; checked over
the whole softening path (largest difference over the peak stress, 0.5 %),
and the work of the stress on its inelastic strain beyond the peak against
the unregularised point's up to the mapped strain, times l_c / h (the
energy per unit area of a band: 1 %). Without the entry the curve is the unregularised one (to
twice the return's tolerance, 1e-6 of f'c).

Through the solver: the bar of tests/concrete/pulled_bar.prm (100 x 10 x 10
mm, one row weakened to 0.95 so that crushing localises there) pushed at
0.1 m/s until its end has moved 1.2 mm, on 10 and 20 elements along, one
across (a row of 2 x 2 spreads the crushing over three rows), with l_c =
20 mm and without: with the band the energy dissipated (bodies.csv)
agrees within 5 % between the two meshes (measured 1 %); without it the
finer mesh's crushed row dissipates less (6.7 %, printed); np = 2 gives
np = 1's energy (1e-9).
"""
import os
from anvil_test import Checker, arguments, run_anvil, run_material_point, test_scene
import concrete_reference as ref

args = arguments()
c = Checker("crush band: the compression softening regularised by the element length")
l_c = 0.04


def driver(name, h, band):
    extra = f"    set Crush band length = {band}\n" if band else ""
    return run_material_point(c, args, name, ref.material_block(extra=extra), Mode="uniaxial stress",
                              Strain_rate=0.1, Strain_path=-0.01, Strain_increment=2e-6,
                              Characteristic_length=h)


plain = driver("unregularised", l_c, None)
same = driver("band_equal_h", l_c, l_c)
short = driver("band_quarter_h", l_c / 4, l_c)
s_plain = [-x for x in plain["stress_xx"]]
e_plain = [-x for x in plain["strain_xx"]]
E = s_plain[5] / e_plain[5]
peak = max(s_plain)
worst_same = max(abs(a - b) for a, b in zip(plain["stress_xx"], same["stress_xx"])) / peak
# (The same curve by two routes of arithmetic: the returns may stop at
# different iterates, each within the return's tolerance, 1e-6 of f'c, of
# the surface.)
c.check_below("l_c = h against no crush band: largest stress difference / peak", worst_same, 2e-6)


def inelastic(stress, strain):
    return [e - s / E for s, e in zip(stress, strain)]


i_peak = s_plain.index(peak)
ein_plain = inelastic(s_plain, e_plain)
e_p = ein_plain[i_peak]


def inelastic_work(stress, e_in, first, last):
    """The work of the stress on the inelastic strain, sum of sigma de_in
    (trapezoids) over the rows first ... last."""
    return sum(0.5 * (stress[i] + stress[i - 1]) * (e_in[i] - e_in[i - 1]) for i in range(first + 1, last + 1))


def plain_at(e):
    """The unregularised point's stress and its inelastic work beyond the
    peak at inelastic strain e (linear between rows)."""
    for i in range(i_peak + 1, len(ein_plain)):
        if ein_plain[i] >= e:
            w = (e - ein_plain[i - 1]) / (ein_plain[i] - ein_plain[i - 1])
            s = s_plain[i - 1] + w * (s_plain[i] - s_plain[i - 1])
            work = inelastic_work(s_plain, ein_plain, i_peak, i - 1) + 0.5 * (s + s_plain[i - 1]) * (e - ein_plain[i - 1])
            return s, work
    return None, None


s_short = [-x for x in short["stress_xx"]]
ein_short = inelastic(s_short, [-x for x in short["strain_xx"]])
worst, checked = 0.0, 0
for s, e in zip(s_short, ein_short):
    if e > e_p * 1.02:
        expected, _ = plain_at(e_p + (e - e_p) / 4)
        if expected is not None:
            worst = max(worst, abs(s - expected) / peak)
            checked += 1
print(f"  E = {E / 1e9:.2f} GPa, peak {peak / 1e6:.2f} MPa at inelastic strain {e_p:.2e}; "
      f"{checked} rows past the peak compared")
c.check_true("the h = l_c / 4 point softens past the peak (rows compared)", checked > 1000, f"{checked}")
c.check_below("h = l_c / 4: |sigma - sigma_plain(e_p + (e_in - e_p) / 4)| / peak, largest over the softening",
              worst, 0.005)
i_short = s_short.index(max(s_short))
_, w_plain = plain_at(e_p + (ein_short[-1] - e_p) / 4)
w_short = inelastic_work(s_short, ein_short, i_short, len(s_short) - 1)
c.check("h = l_c / 4: work on the inelastic strain beyond the peak (J/m^3) against the unregularised "
        "point's to the mapped strain, times l_c / h (the same energy per unit area of a band)",
        w_short, 4 * w_plain, 0.01, relative=True)

# Through the solver: the weakened bar crushed on two meshes.
v = 0.1
end_time = 1.2e-3 / v
energies = {}
for band, n, np in ((0.02, 10, 1), (0.02, 20, 1), (None, 10, 1), (None, 20, 1), (0.02, 20, 2)):
    name = f"bar_{n}_{'band' if band else 'plain'}" + ("_np2" if np > 1 else "")
    overrides = {**ref.pulled_bar_overrides(n, end_time, end_time / 100, lateral=1),
                 "Boundary condition pull/Velocity": f"{-v}, 0, 0"}
    if band:
        overrides["Body bar/Material/concrete damaged plasticity/Crush band length"] = band
    prm = test_scene(args, "tests/concrete/pulled_bar.prm", name, overrides)
    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"{name}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    with open(os.path.join(args.work_dir, "output", name, "bodies.csv")) as f:
        rows = f.read().splitlines()
    energies[name] = float(dict(zip(rows[0].split(","), rows[1].split(",")))["dissipated_energy"])
spread_band = abs(energies["bar_20_band"] / energies["bar_10_band"] - 1)
spread_plain = abs(energies["bar_20_plain"] / energies["bar_10_plain"] - 1)
print("  dissipated energy (J): " + ", ".join(f"{k} {w:.4g}" for k, w in energies.items()) +
      f"; spread without the band {100 * spread_plain:.1f} %")
c.check_below("crushed bar with l_c = 20 mm: dissipated energy, 20 elements along against 10", spread_band, 0.05)
c.check("crushed bar with l_c = 20 mm, 20 elements along: dissipated energy np = 2 against np = 1",
        energies["bar_20_band_np2"], energies["bar_20_band"], 1e-9, relative=True)
c.finish()
