"""Collapse load of the seed's RC column (coarse, perfect bond) against a
section analysis (tests/verification/rc_column_collapse.prm).

The hammer, given a prescribed motion of 0.5 m/s, pushes the column at the
impact point (0.5 m above the base, a = 0.5 m, b = 1.0 m) to 40 mm; the top
face is held in x and y only, so that the member can lengthen (no arching
against the supports, which a plastic-hinge analysis does not have); rate
effects off (concrete DIF, steel Cowper-Symonds) for a static strength.

Section analysis: the 120 x 120 mm section with 2 bars of 8 mm at each face
(d = 96 mm, d' = 24 mm), steel 335 MPa elastic-perfectly plastic, concrete
in ACI's rectangular block (0.85 f'c over beta_1 c, beta_1 = 0.73 for
45.4 MPa, crushing strain 0.003): M_p from strain compatibility. A
fixed-fixed member with a load at a from one support fails with hinges at
both supports and under the load: P_c = 2 M_p (1/a + 1/b). The mean
contact force while the far face moves from 10 to 30 mm (forces as 1 ms
moving averages: the member's own inertia rings about the static path) must
be within 15 % of P_c (the steel's hardening, E_t = 1.2 GPa, is not in
P_c), and the member must still carry more than half of P_c at 40 mm.
"""
import math
import os
from anvil_test import Checker, arguments, run_anvil, test_scene, read_csv

args = arguments()
c = Checker("RC column: collapse load against a section analysis")

# Section analysis.
b, h, fc, fy, Es = 0.12, 0.12, 45.4e6, 335e6, 206e9
As = 2 * math.pi * 0.004 ** 2
d, dp = h - 0.024, 0.024
beta1, eps_cu = 0.73, 0.003


def forces(cn):
    """Axial force (tension positive) and moment about mid-depth for a
    neutral axis cn below the compressed face."""
    def steel(y):
        eps = eps_cu * (y - cn) / cn          # tension positive
        return max(-fy, min(fy, Es * eps)) * As
    Cc = 0.85 * fc * b * beta1 * cn
    Ft, Fc = steel(d), steel(dp)
    N = Ft + Fc - Cc
    M = Cc * (h / 2 - beta1 * cn / 2) + Ft * (d - h / 2) - Fc * (h / 2 - dp)
    return N, M


lo, hi = 1e-4, h
for _ in range(200):
    mid = 0.5 * (lo + hi)
    if forces(mid)[0] > 0:
        lo = mid
    else:
        hi = mid
cn = 0.5 * (lo + hi)
Mp = forces(cn)[1]
a, bb = 0.5, 1.0
Pc = 2 * Mp * (1 / a + 1 / bb)
print(f"  section: neutral axis {1e3 * cn:.1f} mm, M_p = {1e-3 * Mp:.3f} kN m; P_c = 2 M_p (1/a + 1/b) = "
      f"{1e-3 * Pc:.2f} kN")

prm = test_scene(args, "tests/verification/rc_column_collapse.prm", "collapse")
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if not c.check_true("the push runs to its end", code == 0, err.strip()[-300:]):
    c.finish()
contact = read_csv(os.path.join(args.work_dir, "output", "collapse", "contact_impact.csv"))
back = read_csv(os.path.join(args.work_dir, "output", "collapse", "probe_back_face.csv"))
f = contact["normal_force_x"]
w = 10  # rows of 1e-4 s: a 1 ms window
avg = [sum(f[i - w:i]) / w for i in range(w, len(f))]
u = [-back["ux"][i - w // 2] for i in range(w, len(f))]
plateau = [p for p, x in zip(avg, u) if 0.010 <= x <= 0.030]
mean = sum(plateau) / len(plateau)
print(f"  push: largest force {1e-3 * max(avg):.2f} kN (1 ms mean); mean over 10-30 mm of the back face "
      f"{1e-3 * mean:.2f} kN ({len(plateau)} rows); at the end ({1e3 * u[-1]:.1f} mm) {1e-3 * avg[-1]:.2f} kN")
c.check("mean push force over 10-30 mm against the plastic collapse load (relative)", mean, Pc, 0.15,
        relative=True)
c.check_true("the member keeps its strength to the end (last force above half of P_c)", avg[-1] > 0.5 * Pc,
             f"{1e-3 * avg[-1]:.2f} kN")
c.finish()
