"""The tutorial plugin of doc/extending.md, built outside Anvil's tree
against the exported CMake package and loaded at run time with
'Additional shared libraries', checked against the Johnson-Cook closed form.

- Material-point driver, uniaxial stress to 20 % at 1 and 100 1/s: at
  every row the stress equals (A + B eps_p^n)(1 + C ln max(eps_p_dot, 1))
  and eps_p = eps - sigma / E (J2 plasticity in uniaxial stress); at
  100 1/s the flow stress stands 1 + C ln 100 above the rate-free curve.
- The same model in the solver: one hexahedron in uniaxial stress at
  100 1/s gives the driver's stress.
- A library that does not exist: one line, exit 2.
"""
import math
import os
import subprocess
from anvil_test import Checker, arguments, build_plugin, read_csv, run_anvil, test_scene

args = arguments()
c = Checker("Johnson-Cook plugin (doc/extending.md)")
library = build_plugin(c, args, "johnson_cook", "libjohnson_cook.so")

A, B, n, C, E = 350e6, 275e6, 0.36, 0.022, 2.1e11


def drive(name, rate):
    path = os.path.join(args.work_dir, name + ".prm")
    with open(path, "w") as f:
        f.write(f"set Additional shared libraries = {library}\nset Output file = {name}.csv\n"
                "set Overwrite existing output = true\nsubsection Material\n  set Model = Johnson-Cook\nend\n"
                f"subsection Loading\n  set Mode = uniaxial stress\n  set Strain rate = {rate}\n"
                "  set Strain path = 0.2\n  set Strain increment = 1e-4\nend\n")
    r = subprocess.run([args.anvil, "--material-point", path], cwd=args.work_dir, capture_output=True, text=True)
    c.check_true(f"{name}: the driver loads the plugin and runs", r.returncode == 0, r.stderr.strip())
    return read_csv(os.path.join(args.work_dir, name + ".csv"))


for rate in (1.0, 100.0):
    d = drive(f"rate_{rate:g}", rate)
    worst_stress, worst_split = 0.0, 0.0
    t, eps_p, sig, eps = d["time"], d["effective_plastic_strain"], d["stress_xx"], d["strain_xx"]
    for i in range(1, len(t)):
        if eps_p[i] <= eps_p[i - 1]:
            continue
        rate_p = (eps_p[i] - eps_p[i - 1]) / (t[i] - t[i - 1])
        expected = (A + B * eps_p[i] ** n) * (1 + C * math.log(max(rate_p, 1.0)))
        worst_stress = max(worst_stress, abs(sig[i] - expected) / expected)
        worst_split = max(worst_split, abs(eps_p[i] - (eps[i] - sig[i] / E)))
    c.check_below(f"{rate:g} 1/s: stress against (A + B eps_p^n)(1 + C ln eps_p_dot), largest relative error",
                  worst_stress, 1e-6)
    c.check_below(f"{rate:g} 1/s: eps_p against eps - sigma / E, largest difference", worst_split, 1e-9)
    ratio = sig[-1] / (A + B * eps_p[-1] ** n)
    c.check(f"{rate:g} 1/s: flow stress over the rate-free curve at 20 %", ratio,
            1 + C * math.log(max(rate, 1.0)), 2e-3, relative=True)
    if rate == 100.0:
        reference = d

# The solver: one hexahedron at 100 1/s to 10 %.
L, rate, target = 0.01, 100.0, 0.1
end_time = (math.exp(target) - 1) / rate
prm = test_scene(args, "tests/material/uniaxial_cube.prm", "cube",
                 {"Additional shared libraries": library, "Simulation/End time": end_time,
                  "Simulation/History interval": 1e-5, "Body cube/Material/Model": "Johnson-Cook",
                  "Boundary condition pull/Velocity": f"{rate * L}, 0, 0"})
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
if c.check_true("the scene loads the plugin and runs", code == 0, err.strip()):
    probe = read_csv(os.path.join(args.work_dir, "output", "cube", "probe_corner.csv"))
    strain = math.log(1 + probe["ux"][-1] / L)
    i = min(range(len(reference["strain_xx"])), key=lambda k: abs(reference["strain_xx"][k] - strain))
    c.check(f"solver against the driver: stress at {strain:.4f} strain", probe["stress_xx"][-1],
            reference["stress_xx"][i], 0.01, relative=True)

prm = test_scene(args, "tests/material/uniaxial_cube.prm", "missing",
                 {"Additional shared libraries": "no_such_plugin.so", "Body cube/Material/Model": "Johnson-Cook"})
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
c.check_true("a missing library: exit 2, one line naming it", code == 2 and len(err.strip().splitlines()) == 1 and
             "no_such_plugin.so" in err and "Additional shared libraries" in err, err.strip())
c.finish()
