"""Two elastic rods colliding (seed section 6.2), against bar theory.

Rod A (10 m, 1 m x 1 m, E = 100 Pa, rho = 0.01 kg/m^3) hits rod B at rest at
v0 = 1 m/s. One-dimensional wave theory: c = sqrt(E/rho) = 100 m/s, the
contact force is rho c A v0 / 2 = 0.5 N for 2L/c = 0.2 s, then rod A rests
and rod B moves at v0.

Tolerances: 2 % on force, duration and velocities (the issue's figures; the
3D rods carry lateral inertia that bar theory neglects, and the penalty
spring softens the force rise); energy balance 1 %; momentum to round-off
(1e-12 relative): the penalty forces are equal and opposite by construction.
The contact's approach (the rods' centres of mass towards each other,
summary.csv) is bar theory's v0 L / 2c = 0.05 m within the springs' own
compression (the deepest penetration) plus 1 %, and the run's last lines
note the penetration's share of it (8 %: above 1 %, so named measurable).
The scene is the real one from prm/, with field output off.
"""
import os
from anvil_test import Checker, arguments, run_anvil, write_scene, read_csv

args = arguments()
scene = os.path.join(args.source_dir, "prm/elastic_rod_impact/elastic_rod_impact.prm")
prm = write_scene(os.path.join(args.work_dir, "rod_impact.prm"), include=scene, text="""
subsection Simulation
  set Output interval = 0
  set Print wall times = false
end
""")
c = Checker("elastic rod impact against bar theory")
code, out, err = run_anvil(args.anvil, prm, np=1, cwd=args.work_dir)
print(out[-800:])
if not c.check_true("anvil exits 0", code == 0, err.strip()):
    c.finish()

d = os.path.join(args.work_dir, "output/rod_impact")
contact = read_csv(os.path.join(d, "contact_impact.csv"))
energy = read_csv(os.path.join(d, "energy.csv"))
momentum = read_csv(os.path.join(d, "momentum.csv"))
t = contact["time"]
force = [-f for f in contact["normal_force_x"]]  # force on rod B, +x

rho, c0, area, v0, length = 0.01, 100.0, 1.0, 1.0, 10.0
f_exact = rho * c0 * area * v0 / 2
plateau = [f for ti, f in zip(t, force) if 0.03 <= ti <= 0.17]
c.check("mean contact force over the plateau [N]", sum(plateau) / len(plateau), f_exact, 0.02, relative=True)

half = 0.5 * f_exact
above = [ti for ti, f in zip(t, force) if f >= half]
duration = above[-1] - above[0] if above else 0.0
c.check("contact duration (force above half the plateau) [s]", duration, 2 * length / c0, 0.02, relative=True)

mass = rho * area * length
c.check("final velocity of rod A [m/s]", momentum["rod_a_px"][-1] / mass, 0.0, 0.02 * v0)
c.check("final velocity of rod B [m/s]", momentum["rod_b_px"][-1] / mass, v0, 0.02, relative=True)

c.check_below("largest energy balance error", max(energy["balance_error"]), 0.01)
p0 = mass * v0
drift = max(abs(p - p0) for p in momentum["px"]) / p0
c.check_below("relative drift of total momentum", drift, 1e-12)
lateral = max(max(abs(p) for p in momentum["py"]), max(abs(p) for p in momentum["pz"])) / p0
c.check_below("transverse momentum / initial momentum", lateral, 1e-12)

# The contact's approach (the rods' centres of mass towards each other,
# for the penalty's note): bar theory's v0 L / 2c at the middle of the
# contact, plus at most the springs' own compression (the penetration).
summary = dict(zip(*[read_csv(os.path.join(d, "summary.csv"))[k] for k in ("quantity", "value")]))
approach = float(summary["contact_impact_max_approach"])
depth = float(summary["contact_impact_max_penetration"])
print(f"  approach {approach:.5f} m (bar theory {v0 * length / (2 * c0):.5f} m), deepest penetration "
      f"{depth:.5f} m, their ratio {float(summary['contact_impact_penetration_over_approach']):.4f}")
c.check_below("|approach - v0 L / 2c| - deepest penetration [m]",
              abs(approach - v0 * length / (2 * c0)) - depth, 0.01 * v0 * length / (2 * c0))
c.check_true("the end of the run notes the springs' share of the approach (above 1 %)",
             "of the contact's approach" in out and "measurable share" in out)
c.finish()
