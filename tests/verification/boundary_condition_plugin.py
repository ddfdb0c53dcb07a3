"""The boundary-condition plugin of doc/extending.md ('A boundary condition
as a plugin', doc/examples/harmonic_motion), built outside Anvil's tree
against the exported CMake package and loaded with 'Additional shared
libraries', on tests/verification/harmonic_motion.prm: the bar of
velocity_ramp.prm with its top shaken instead of ramped, 'Type = harmonic',
A = 0.1 mm along z, f = 1 kHz.

- The top's displacement against A sin(2 pi f t) at every row over two
  periods (the held nodes take v at each half step: the midpoint rule of
  A omega cos, exact to O((omega dt)^2)).
- Its velocity at every row against A omega cos(omega t).
- 'Frequency = 0' stops with one line naming the entry and exit 2; a scene
  that asks for 'harmonic' without loading the library gets one line that
  lists the boundary conditions there are.
"""
import math
import os
from anvil_test import Checker, arguments, build_plugin, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("boundary-condition plugin 'harmonic' (doc/extending.md)")
library = build_plugin(c, args, "harmonic_motion", "libharmonic_motion.so")
A, f = 1e-4, 1000.0
omega = 2 * math.pi * f


def shaken(name, frequency, load=True):
    prm = test_scene(args, "tests/verification/harmonic_motion.prm", name,
                     {"Additional shared libraries": library if load else "",
                      "Boundary condition top/Frequency": frequency})
    return run_anvil(args.anvil, prm, np=1, cwd=args.work_dir)


code, out, err = shaken("shaken", f)
if not c.check_true("the scene loads the plugin and runs", code == 0, err.strip()[-400:]):
    c.finish()
p = read_csv(os.path.join(args.work_dir, "output", "shaken", "probe_top.csv"))
c.check_true("two periods", p["time"][-1] >= 2 / f - 1e-12, f"last row at {p['time'][-1]}")
worst_u = max(abs(u - A * math.sin(omega * t)) for t, u in zip(p["time"], p["uz"])) / A
c.check_below("top displacement against A sin(omega t), largest error over A", worst_u, 1e-3)
worst_v = max(abs(v - A * omega * math.cos(omega * t)) for t, v in zip(p["time"], p["vz"])) / (A * omega)
c.check_below("top velocity against A omega cos(omega t), largest error over A omega", worst_v, 1e-10)

code, out, err = shaken("no_frequency", 0)
lines = [l for l in err.strip().splitlines() if l.startswith("anvil: error")]
c.check_true("'Frequency = 0': exit 2 and one line naming the entry",
             code == 2 and len(lines) == 1 and "'Frequency'" in lines[0], err.strip()[-300:])
code, out, err = shaken("not_loaded", f, load=False)
lines = [l for l in err.strip().splitlines() if l.startswith("anvil: error")]
c.check_true("'harmonic' without the library: exit 2 and one line naming 'Type'",
             code == 2 and len(lines) == 1 and "Type" in lines[0], err.strip()[-300:])
c.finish()
