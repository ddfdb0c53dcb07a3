"""Bond-slip reinforcement (seed Eq. (68)).

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
from anvil_test import (Checker, arguments, max_relative_difference, read_csv, run_anvil,
                        write_scene)

args = arguments()
c = Checker("bond-slip reinforcement")
G, Smax, h = 5e10, 3.6e-4, 200.0
tau_max = G * Smax


def pullout(name, np, end_time=0.05):
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"), text=f"""
# Pull-out of a bar from an elastic block (bond-slip).
set Bodies = block
set Rebars = bar
set Boundary conditions = bearing
subsection Simulation
  set End time = {end_time}
  set History interval = 2.5e-4
  set Print wall times = false
end
subsection Body block
  subsection Mesh
    set Lower corner = 0, -0.05, -0.05
    set Upper corner = 0.1, 0.05, 0.05
    set Subdivisions = 10, 10, 10
  end
  subsection Material
    set Model = elastic
    subsection elastic
      set Density = 2400
      set Young's modulus = 3e10
      set Poisson's ratio = 0.2
    end
  end
  # The bond loads the block along a line of nodes: one-point elements with
  # viscous hourglass control would let that line creep in hourglass modes.
  set Integration = full
end
subsection Boundary condition bearing
  set Body = block
  set Boundary ids = 1
  set Components = x
end
subsection Rebar bar
  set Host body = block
  set Layout = longitudinal
  set Axis = x
  set Member lower corner = 0.0, -0.05, -0.05
  set Member upper corner = 0.1, 0.05, 0.05
  set Bars per face = 1
  set Diameter = 0.016
  set Element length = 0.01
  set Coupling = bond-slip
  set Pull velocity = 0.02, 0, 0
  set Probe point = 0.055, 0, 0
  # The bar's 10 mm steel elements would set the step (1.98 us against the
  # block's 2.53 us); scaled, the pull-out takes a fifth fewer steps and is
  # as quasi-static (tests/rebar/mass_scaling.py).
  set Mass scaling time step = 2.6e-6
  subsection Material
    set Model = elastic
    subsection elastic
      set Density = 7850
      set Young's modulus = 2e11
      set Poisson's ratio = 0.3
    end
  end
end
""")
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
    bc = """set Boundary conditions = base, top
subsection Boundary condition base
  set Body = prism
  set Boundary ids = 4
  set Components = z
end
subsection Boundary condition top
  set Body = prism
  set Boundary ids = 5
  set Type = velocity
  set Velocity = 0, 0, 0.01
  set Components = z
end""" if pull else ""
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"), text=f"""
# Bar in a prism, {coupling}.
set Bodies = prism
set Rebars = bar
set Probes = mid
{bc}
subsection Simulation
  set End time = {end_time}
  set History interval = 1e-4
  set Print wall times = false
end
subsection Body prism
  subsection Mesh
    set Lower corner = 0, 0, 0
    set Upper corner = 0.1, 0.1, 1
    set Subdivisions = 5, 5, 50
  end
  subsection Material
    set Model = elastic
    subsection elastic
      set Density = 2400
      set Young's modulus = 3e10
      set Poisson's ratio = 0
    end
  end
  set Integration = full
  set Initial velocity = 0, 0, {v0}
end
subsection Rebar bar
  set Host body = prism
  set Axis = z
  set Member lower corner = 0, 0, 0
  set Member upper corner = 0.1, 0.1, 1
  set Bars per face = 1
  set Diameter = 0.02
  set Element length = 0.02
  set Coupling = {coupling}
  set Bond modulus = {G_s}
  set Probe point = 0.05, 0.05, 0.51
  subsection Material
    set Model = elastic
    subsection elastic
      set Density = 7850
      set Young's modulus = 2e11
      set Poisson's ratio = 0.3
    end
  end
end
subsection Probe mid
  set Point = 0.05, 0.05, 0.52
end
""")
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
prm = write_scene(os.path.join(args.work_dir, "free_bar.prm"), text="""
# A free steel bar pulled at one end (truss frequency).
set Bodies = host
set Rebars = bar
subsection Simulation
  set End time = 0.0016
  set History interval = 0
  set Print wall times = false
end
subsection Body host
  subsection Mesh
    set Lower corner = 0, -0.05, -0.05
    set Upper corner = 1, 0.05, 0.05
    set Subdivisions = 2, 1, 1
  end
  subsection Material
    set Model = elastic
    subsection elastic
      set Density = 2400
      set Young's modulus = 3e10
      set Poisson's ratio = 0.2
    end
  end
end
subsection Rebar bar
  set Host body = host
  set Axis = x
  set Member lower corner = 0, -0.05, -0.05
  set Member upper corner = 1, 0.05, 0.05
  set Bars per face = 1
  set Diameter = 0.02
  set Element length = 0.01
  set Coupling = bond-slip
  set Bond modulus = 1e-3
  set Pull velocity = 0.1, 0, 0
  set Probe point = 0.995, 0, 0
  subsection Material
    set Model = elastic
    subsection elastic
      set Density = 7850
      set Young's modulus = 2e11
      set Poisson's ratio = 0.3
    end
  end
end
""")
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
