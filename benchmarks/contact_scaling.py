"""Contact search and evaluation cost against surface size.

Two elastic blocks, the upper one pressed into the lower one, each n x n x 1
elements, so the contact pair holds about 4 n^2 surface nodes (all boundary
nodes of both bodies). For two sizes the script runs a few dozen steps on
one process and prints, from Anvil's TimerOutput summary, the contact time
per step, its share of the step (element forces + contact + time
integration), and the contact time per surface node, whose constancy across
the two sizes shows linear scaling.

Usage: python3 benchmarks/contact_scaling.py ANVIL [n1 n2 [steps]]
(defaults 112 158 30: about 5e4 and 1e5 surface nodes). Figures, never
asserts: timings on shared machines are noisy; compare the ratios.
"""
import os
import re
import subprocess
import sys
import tempfile

if len(sys.argv) < 2 or sys.argv[1].startswith("-") or not os.access(sys.argv[1], os.X_OK):
    sys.exit(f"usage: python3 {sys.argv[0]} ANVIL [options in its docstring] (ANVIL: the anvil executable, "
             f"build/anvil; got {sys.argv[1]!r})" if len(sys.argv) > 1 else
             f"usage: python3 {sys.argv[0]} ANVIL [options in its docstring] (ANVIL: the anvil executable, "
             f"build/anvil)")
anvil = sys.argv[1]
sizes = [int(a) for a in sys.argv[2:4]] if len(sys.argv) > 3 else [112, 158]
steps = int(sys.argv[4]) if len(sys.argv) > 4 else 30
work = tempfile.mkdtemp()
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
print(f"contact_scaling: two stacked blocks, {steps} steps, one process")
rows = []
for n in sizes:
    prm = os.path.join(work, f"blocks_{n}.prm")
    h = 1.0 / n
    body = lambda name, z0, z1, v: f"""
subsection Body {name}
  subsection Mesh
    set Lower corner = 0, 0, {z0}
    set Upper corner = 1, 1, {z1}
    set Subdivisions = {n}, {n}, 1
  end
  subsection Material
    set Model = elastic
    subsection elastic
      set Density = 1000
      set Young's modulus = 1e7
      set Poisson's ratio = 0.3
    end
  end
  set Initial velocity = 0, 0, {v}
end
"""
    with open(prm, "w") as f:
        f.write(f"""set Bodies = upper, lower
set Contact pairs = stack
subsection Simulation
  set End time = {steps * 0.6 * h / 116.0}
  set History interval = 1
  set Energy balance tolerance = 1e9
end
{body("upper", 0, h, -1.0)}
{body("lower", -h, 0, 0.0)}
subsection Contact pair stack
  set Algorithm = penalty
  set First body = upper
  set Second body = lower
end
""")
    r = subprocess.run([anvil, prm], cwd=work, capture_output=True, text=True, env=env)
    text = r.stdout + r.stderr
    def section(name):
        m = re.search(r"\| " + name + r"\s+\|\s+(\d+) \|\s+([0-9.e+-]+)s", text)
        return (int(m.group(1)), float(m.group(2))) if m else (0, float("nan"))
    calls, contact = section("contact")
    _, elements = section("element forces")
    _, integration = section("time integration")
    surface = 2 * (2 * (n + 1) ** 2 + 4 * (n + 1) * 2 - 8)
    step = contact + elements + integration
    rows.append((n, surface, contact / max(calls, 1), contact / step, contact / max(calls, 1) / surface))
    print(f"  n = {n}: {surface} surface nodes, {2 * n * n} elements: contact {1e3 * rows[-1][2]:.2f} ms "
          f"per step, {100 * rows[-1][3]:.0f} % of the step, {1e9 * rows[-1][4]:.0f} ns per surface node")
if len(rows) == 2 and rows[0][4] > 0:
    print(f"  surface nodes x{rows[1][1] / rows[0][1]:.2f}: contact time per step "
          f"x{rows[1][2] / rows[0][2]:.2f} (linear: the same factor)")
