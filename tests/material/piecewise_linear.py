"""Piecewise linear plasticity (LS-DYNA *MAT_024, ABAQUS *Plastic with a
table) at one material point, driven by 'anvil --material-point', against
closed forms.

Flow curve 0:300, 0.01:350, 0.03:380, 0.05:370 MPa (hardening, a kink,
softening), E = 200 GPa, uniaxial stress to 10 % strain in steps of 1e-4:
- in uniaxial stress the effective plastic strain is eps - sigma/E, so the
  stress solves sigma = sigma_y(eps - sigma/E): the script solves it by
  bisection for every row and the driver's stress must match it within
  1e-9 of the stress (the return is exact on each piece of the curve,
  whichever pieces a step crosses);
- beyond the last point, 'extrapolate' continues the last slope (-500
  MPa) and 'constant' keeps 370 MPa: both closed forms at 10 %;
- the model's own state: sigma = sigma_y(eps_p of its history) at every
  plastic row, 1e-9;
- plastic work density = the integral of sigma d eps_p (trapezoids over
  the rows), 1e-3;
- Cowper-Symonds (C = 40 1/s, p = 5) at 100 1/s: sigma = (1 + (r / C)^(1/p))
  sigma_y(eps_p), with r and eps_p the history's effective plastic strain
  rate and strain, at every plastic row (the return's tolerance, 1e-9),
  and r within 1 % of the axial rate's plastic share at 5 %;
- a one-point curve is perfectly plastic (300 MPa at 10 %, 1e-9);
- erosion at 'Failure strain': the quarter bar of steel_erosion.prm pulled
  to failure erodes elements, each at f_s or beyond, with the energy
  balance below 1 %;
- bad curves (not increasing, no point at 0, a slope below -3G, text) and
  C without p: exit 2 with one line naming the entry.
"""
import os
import subprocess
from anvil_test import Checker, arguments, read_csv, run_anvil, run_material_point, test_scene

args = arguments()
c = Checker("piecewise linear plasticity at a material point")
E, nu = 200e9, 0.3
curve = [(0.0, 300e6), (0.01, 350e6), (0.03, 380e6), (0.05, 370e6)]


def material(points, extra=""):
    text = ", ".join(f"{e:g}:{s:g}" for e, s in points)
    return f"""subsection Material
  set Model = piecewise linear plasticity
  subsection piecewise linear plasticity
    set Density = 7850
    set Young's modulus = {E}
    set Poisson's ratio = {nu}
    set Flow curve = {text}
    {extra}
  end
end"""


def flow(points, eps, extrapolate=True):
    if len(points) == 1:
        return points[0][1]
    for (e0, s0), (e1, s1) in zip(points, points[1:]):
        if eps <= e1:
            return s0 + (s1 - s0) * (eps - e0) / (e1 - e0)
    if not extrapolate:
        return points[-1][1]
    (e0, s0), (e1, s1) = points[-2], points[-1]
    return max(0.0, s1 + (s1 - s0) * (eps - e1) / (e1 - e0))


def uniaxial(points, eps, extrapolate=True):
    """sigma = sigma_y(eps - sigma/E), or E eps while elastic."""
    if E * eps <= points[0][1]:
        return E * eps
    lo, hi = 0.0, E * eps
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid - flow(points, eps - mid / E, extrapolate) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def drive(name, text, rate=1.0):
    return run_material_point(c, args, name, text, Mode="uniaxial stress", Strain_rate=rate,
                              Strain_path="0.1", Strain_increment="1e-4")


for beyond in ("extrapolate", "constant"):
    d = drive(f"tension_{beyond}", material(curve, f"set Beyond the curve = {beyond}"))
    extrapolate = beyond == "extrapolate"
    worst = max(abs(s - uniaxial(curve, e, extrapolate)) for e, s in zip(d["strain_xx"], d["stress_xx"]))
    c.check_below(f"{beyond}: |sigma - closed form| / 300 MPa over the path (every row)", worst / 300e6, 1e-9)
    c.check(f"{beyond}: stress at 10 % [Pa]", d["stress_xx"][-1], uniaxial(curve, 0.1, extrapolate), 1e-9,
            relative=True)
    plastic = [i for i, ep in enumerate(d["effective_plastic_strain"]) if ep > 0]
    own = max(abs(d["stress_xx"][i] - flow(curve, d["effective_plastic_strain"][i], extrapolate)) for i in plastic)
    c.check_below(f"{beyond}: |sigma - sigma_y(eps_p of the history)| / 300 MPa", own / 300e6, 1e-9)
    ep, s = d["effective_plastic_strain"], d["stress_xx"]
    work = sum(0.5 * (s[i] + s[i + 1]) * (ep[i + 1] - ep[i]) for i in range(len(ep) - 1))
    c.check(f"{beyond}: plastic work density against the integral of sigma d eps_p [J/m^3]",
            d["plastic_work_density"][-1], work, 1e-3, relative=True)

d = drive("perfectly_plastic", material([(0.0, 300e6)]))
c.check("one-point curve: stress at 10 % [Pa]", d["stress_xx"][-1], 300e6, 1e-9, relative=True)

C, P, rate = 40.0, 5.0, 100.0
d = drive("cowper_symonds", material(curve, f"set Cowper-Symonds C = {C}\n    set Cowper-Symonds p = {P}"), rate)
plastic = [i for i, ep in enumerate(d["effective_plastic_strain"]) if ep > 0]
worst = max(abs(d["stress_xx"][i] - (1 + (d["effective_plastic_strain_rate"][i] / C) ** (1 / P)) *
                flow(curve, d["effective_plastic_strain"][i])) for i in plastic)
c.check_below("Cowper-Symonds: |sigma - R(rate) sigma_y(eps_p)| / 300 MPa at every plastic row", worst / 300e6, 1e-9)
i5 = min(range(len(d["strain_xx"])), key=lambda i: abs(d["strain_xx"][i] - 0.05))
share = rate * (1 - (d["stress_xx"][i5 + 1] - d["stress_xx"][i5 - 1]) / (
    d["strain_xx"][i5 + 1] - d["strain_xx"][i5 - 1]) / E)
c.check("Cowper-Symonds: effective plastic strain rate at 5 % against the axial rate's plastic share [1/s]",
        d["effective_plastic_strain_rate"][i5], share, 0.01, relative=True)
R = 1 + (d["effective_plastic_strain_rate"][i5] / C) ** (1 / P)
print(f"  rate factor at 5 %: {R:.4f} (stress {d['stress_xx'][i5] / 1e6:.2f} MPa against the static "
      f"{flow(curve, d['effective_plastic_strain'][i5]) / 1e6:.2f})")

# Erosion at 'Failure strain' (LS-DYNA's FAIL): the quarter bar of
# tests/material/steel_erosion.prm pulled to failure at its held end, with
# this model (Table 1 steel's bilinear curve, f_s = 0.12).
fs = 0.12
prm = test_scene(args, "tests/material/steel_erosion.prm", "erosion", text=f"""
subsection Body bar
  subsection Material
    set Model = piecewise linear plasticity
    subsection piecewise linear plasticity
      set Density = 7850
      set Young's modulus = 206e9
      set Poisson's ratio = 0.3
      set Flow curve = 0:335e6, 1:{335e6 + 206e9 * 1.2e9 / (206e9 - 1.2e9)!r}
      set Failure strain = {fs}
    end
  end
end
""")
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if c.check_true("erosion scene: anvil exits 0", code == 0, err.strip()[-300:]):
    d = os.path.join(args.work_dir, "output", "erosion")
    erosion = read_csv(os.path.join(d, "erosion.csv"))
    energy = read_csv(os.path.join(d, "energy.csv"))
    c.check_true("erosion scene: elements eroded", len(erosion.get("element", [])) > 0)
    c.check_below("erosion scene: f_s - smallest effective plastic strain of an eroded element",
                  fs - min(erosion["effective_plastic_strain"]), 0.0)
    c.check_below("erosion scene: largest energy balance error (with the eroded energy)",
                  max(energy["balance_error"]), 0.01)

bad = {
    "not increasing": material([(0.0, 300e6), (0.02, 350e6), (0.01, 360e6)]),
    "no point at 0": material([(0.01, 300e6), (0.02, 350e6)]),
    "a slope below -3G": material([(0.0, 300e6), (1e-6, 1e6)]),
    "text": material([(0.0, 300e6)]).replace("0:3e+08", "0:3e+08, abc"),
    "C without p": material(curve, "set Cowper-Symonds C = 40"),
}
for what, text in bad.items():
    prm = os.path.join(args.work_dir, "bad.prm")
    with open(prm, "w") as f:
        f.write(f"set Output file = bad.csv\nset Overwrite existing output = true\n{text}\n"
                "subsection Loading\n  set Strain path = 0.01\nend\n")
    r = subprocess.run([args.anvil, "--material-point", prm], cwd=args.work_dir, capture_output=True, text=True)
    lines = r.stderr.strip().splitlines()
    c.check_true(f"bad curve ({what}): exit 2 and one line naming the entry", r.returncode == 2 and len(lines) == 1
                 and ("Flow curve" in lines[0] or "Cowper-Symonds" in lines[0]), r.stderr.strip()[-300:])
c.finish()
