"""Bond-slip reinforcement (seed Eq. (68)); the scenes are tests/rebar/pullout.prm,
bond_slip_prism.prm (and _free) and free_bar.prm.

1. Pull-out: a 16 mm bar along the axis of an elastic block (0.1 m cube,
   E = 30 GPa, nu = 0.2, full integration: the bond loads a line of nodes,
   which one-point elements with viscous hourglass control let creep)
   bearing on its loaded face; the bar's end is
   pulled at 0.02 m/s (quasi-static: 0.01 m/s gives the same curve to
   5e-6 of tau_max) to 1 mm of slip (the bar's mass scaled so that the
   block's elements set the step). At the bar's middle node the bond
   stress against the slip (relative to the host material point, so the
   block's own deformation is accounted for) follows Eq. (68):
   tau = G_s S (G_s = 50 MPa/mm) up to S_max = 0.36 mm, then
   tau_max exp(-h (S - S_max)) (h = 0.2 per mm) for monotonic slip; largest
   deviation 3 % of tau_max on each branch.
2. np = 2 against np = 1 for the pull-out (to 22.5 ms, past S_max): rebar
   histories within 1e-8.
3. A reinforced block flying at 1 m/s with bond-slip keeps its momentum
   (bars' own nodes included) to 1e-12 and its energy balance below 1 %.
5. A free bar (bond modulus ~ 0) pulled at one end rings at the
   fixed-free truss period 4 L / c with end force +-Z v (2 %).
4. G_s large (1000 x) approaches perfect bond: the composite bar's force
   split N_s / N_c against the perfect-bond value (printed), within 2 %
   (full integration in both, so that only the coupling differs).
"""
import math
import os
from anvil_test import Checker, arguments, max_relative_difference, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("bond-slip reinforcement")
G, Smax, h = 5e10, 3.6e-4, 200.0
tau_max = G * Smax


def pullout(name, np, end_time=0.05):
    prm = test_scene(args, "tests/rebar/pullout.prm", name, {"Simulation/End time": end_time})

    code, out, err = run_anvil(args.anvil, prm, np=np, cwd=args.work_dir)
    if not c.check_true(f"{name}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    return {f: read_csv(os.path.join(args.work_dir, "output", name, f + ".csv")) for f in ("rebar_bar", "energy")}


p1 = pullout("pullout", 1)
S, tau = p1["rebar_bar"]["probe_slip"], p1["rebar_bar"]["probe_bond_stress"]
rise = [abs(t - G * s) / tau_max for s, t in zip(S, tau) if 0.05 * Smax < s < 0.95 * Smax]
decay = [abs(t - tau_max * math.exp(-h * (s - Smax))) / tau_max for s, t in zip(S, tau) if s > 1.05 * Smax]
print(f"  slip reached {1000 * max(S):.3f} mm; {len(rise)} points on the rising branch, {len(decay)} beyond")
c.check_true("the slip passes S_max and the history reaches 2 S_max",
             max(S) > 2 * Smax and len(rise) > 10 and len(decay) > 10)
c.check_below("rising branch: largest |tau - G_s S| / tau_max", max(rise), 0.03)
c.check_below("decay: largest |tau - tau_max exp(-h (S - S_max))| / tau_max", max(decay), 0.03)
c.check_below("pull-out: largest energy balance error (bond column included)", max(p1["energy"]["balance_error"]), 0.01)
# On two processes to 22.5 ms (slip 0.45 mm: past S_max, into the decay),
# compared row by row with the same rows of the one-process run (the last
# row, at the end time of the shorter run, is left out).
p2 = pullout("pullout_np2", 2, end_time=0.0225)
rows = len(p2["rebar_bar"]["time"]) - 1
head = {k: v[:rows] for k, v in p1["rebar_bar"].items()}
c.check_below(f"np = 2 against np = 1: largest relative difference of rebar_bar.csv ({rows} rows, to 22.5 ms)",
              max_relative_difference(head, {k: v[:rows] for k, v in p2["rebar_bar"].items()}), 1e-8)


# A reinforced block flying at 1 m/s, bars with their own nodes: momentum of
# block and bars together.
def composite(name, coupling, G_s=5e10, v0=0.0, pull=True, end_time=0.01):
    prm = test_scene(args, "tests/rebar/bond_slip_prism.prm" if pull else "tests/rebar/bond_slip_prism_free.prm", name,
                     {"Simulation/End time": end_time, "Body prism/Initial velocity": f"0, 0, {v0}",
                      "Rebar bar/Coupling": coupling, "Rebar bar/Bond modulus": G_s})
    code, out, err = run_anvil(args.anvil, prm, np=1, cwd=args.work_dir)
    if not c.check_true(f"{name}: anvil exits 0", code == 0, err.strip()[-300:]):
        c.finish()
    return {f: read_csv(os.path.join(args.work_dir, "output", name, f + ".csv"))
            for f in ("rebar_bar", "probe_mid", "energy", "momentum")}


fly = composite("flying_slip", "bond-slip", v0=1.0, pull=False, end_time=0.002)
p = fly["momentum"]["pz"]
c.check_below("flying block, bond-slip: momentum drift / p0", max(abs(x - p[0]) for x in p) / p[0], 1e-12)
mass = 2400 * 0.01 + 7850 * math.pi / 4 * 0.02 ** 2
c.check("flying block, bond-slip: momentum / (block + bar mass) x 1 m/s", p[0], mass, 1e-9 * mass)
c.check_below("flying block, bond-slip: largest energy balance error", max(fly["energy"]["balance_error"]), 0.01)

ratios = {}
for name, coupling, G_s in (("stiff_bond", "bond-slip", 5e13), ("perfect", "perfect bond", 5e10)):
    r = composite(name, coupling, G_s=G_s)
    ratios[name] = r["rebar_bar"]["probe_axial_force"][-1] / (r["probe_mid"]["stress_zz"][-1] * 0.01)
print(f"  N_s / N_c: bond-slip with G_s = 5e13 Pa/m {ratios['stiff_bond']:.5f}, "
      f"perfect bond {ratios['perfect']:.5f}")
c.check("G_s large: force split / perfect bond's", ratios["stiff_bond"], ratios["perfect"], 0.02, relative=True)

# A free bar (bond modulus ~ 0) pulled at one end at constant velocity v:
# the fixed-free truss rings at its fundamental period 4 L / c, the force
# at the pulled end switching between +Z v and -Z v every 2 L / c
# (Z = rho c A).
prm = test_scene(args, "tests/rebar/free_bar.prm", "free_bar")

code, out, err = run_anvil(args.anvil, prm, np=1, cwd=args.work_dir)
if c.check_true("free bar: anvil exits 0", code == 0, err.strip()[-300:]):
    r = read_csv(os.path.join(args.work_dir, "output", "free_bar", "rebar_bar.csv"))
    t, N = r["time"], r["probe_axial_force"]
    cs = math.sqrt(2e11 / 7850)
    Z = 7850 * cs * math.pi / 4 * 0.02 ** 2
    crossings = [t[i] for i in range(1, len(t)) if N[i - 1] > 0 >= N[i] or N[i - 1] < 0 <= N[i]]
    half = 2 * 1.0 / cs
    c.check("free bar: first sign change of the end force [s] (2 L / c)", crossings[0], half, 0.02 * half)
    c.check("free bar: period [s] (4 L / c)", crossings[2] - crossings[0], 2 * half, 0.02 * 2 * half)
    plateau = [n for ti, n in zip(t, N) if 0.25 * half < ti < 0.75 * half]
    c.check("free bar: end force on the first plateau [N] (Z v)", sum(plateau) / len(plateau), Z * 0.1,
            0.02, relative=True)

c.finish()
