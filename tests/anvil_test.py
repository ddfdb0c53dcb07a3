"""Shared helpers of Anvil's scene tests: run the executable, read its CSV
output, and report every check as 'measured / expected / tolerance'."""

import argparse
import bisect
import concurrent.futures
import csv
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from anvil_vtu import read_vtu  # noqa: E402


class Checker:
    """Collects checks; exit status 1 if any failed."""

    def __init__(self, title):
        self.title = title
        self.failed = 0
        self.passed = 0
        print(f"== {title}")

    def check(self, name, measured, expected, tolerance, relative=False):
        """Pass when |measured - expected| <= tolerance (times |expected| if
        relative)."""
        error = abs(measured - expected)
        if relative:
            error /= max(abs(expected), 1e-300)
        ok = error <= tolerance
        kind = "relative" if relative else "absolute"
        print(f"  [{'PASS' if ok else 'FAIL'}] {name}: measured {measured:.6g}, "
              f"expected {expected:.6g}, {kind} error {error:.3g} "
              f"(tolerance {tolerance:.3g})")
        self._count(ok)
        return ok

    def check_below(self, name, measured, limit):
        ok = measured <= limit
        print(f"  [{'PASS' if ok else 'FAIL'}] {name}: measured {measured:.6g} "
              f"(limit {limit:.6g})")
        self._count(ok)
        return ok

    def check_true(self, name, condition, detail=""):
        print(f"  [{'PASS' if condition else 'FAIL'}] {name}{': ' + detail if detail else ''}")
        self._count(condition)
        return condition

    def _count(self, ok):
        if ok:
            self.passed += 1
        else:
            self.failed += 1

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        sys.exit(1 if self.failed else 0)


def arguments():
    p = argparse.ArgumentParser()
    p.add_argument("--anvil", required=True)
    p.add_argument("--source-dir", required=True)
    p.add_argument("--work-dir", required=True)
    a = p.parse_args()
    # Start from a clean slate: anvil refuses to overwrite earlier results.
    for root, dirs, files in os.walk(a.work_dir):
        if os.path.basename(root) == "output":
            shutil.rmtree(root, ignore_errors=True)
    return a


# Command-line modes that run no simulation (and read no 'Simulation'
# entries).
NO_RUN_FLAGS = ("--check", "--translate", "--study", "--print-parameters", "--print-cost",
                "--material-point", "--help", "--version")


def run_anvil(anvil, prm, np=1, cwd=None, extra_args=(), plots=False):
    """Run anvil on prm with np MPI processes; return (exit code, stdout,
    stderr). The run makes its PNG plots only with 'plots' (each costs a
    Python start, about 1.4 s; the tests that check plots ask for them)."""
    extra_args = list(extra_args)
    if not plots and not any(a in NO_RUN_FLAGS for a in extra_args):
        extra_args = ["--set", "Simulation/Plots=false"] + extra_args
    cmd = [anvil, *extra_args, prm]
    if np > 1:
        cmd = ["mpirun", "-np", str(np), "--oversubscribe"] + cmd
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def together(*calls, at_once=None):
    """Call the functions at once (at most 'at_once' at a time) and return
    their results in order. ctest runs one test at a time on a two-core
    machine: two single-process runs of a test (or two chains of them) take
    one run's time this way. Each call must write its own output directory."""
    with concurrent.futures.ThreadPoolExecutor(at_once or len(calls)) as pool:
        futures = [pool.submit(call) for call in calls]
        return [f.result() for f in futures]


def build_plugin(checker, args, example, library):
    """Build doc/examples/EXAMPLE against the CMake package of the Anvil
    under test; return the path of the shared library LIBRARY (a failed
    build is a failed check and ends the test)."""
    source = os.path.join(os.path.abspath(args.source_dir), "doc", "examples", example)
    build = os.path.join(args.work_dir, "plugin_build")
    anvil_dir = os.path.dirname(os.path.abspath(args.anvil))
    r = subprocess.run(["cmake", "-S", source, "-B", build, f"-Danvil_DIR={anvil_dir}", "-DCMAKE_BUILD_TYPE=Release"],
                       capture_output=True, text=True)
    if r.returncode == 0:
        r = subprocess.run(["cmake", "--build", build], capture_output=True, text=True)
    path = os.path.join(build, library)
    if not checker.check_true("the plugin builds against the exported package",
                              r.returncode == 0 and os.path.exists(path), (r.stdout + r.stderr).strip()[-400:]):
        checker.finish()
    return path


def run_material_point(checker, args, name, material, **loading):
    """Drive one material point with 'anvil --material-point': 'material'
    is the driver file's 'subsection Material' text, 'loading' the entries
    of its 'subsection Loading' (keyword with '_' for ' ', e.g.
    Strain_rate=1.0). Writes NAME.prm, returns the columns of NAME.csv;
    a failed run is a failed check and ends the test."""
    prm = os.path.join(args.work_dir, name + ".prm")
    entries = "".join(f"  set {k.replace('_', ' ')} = {v}\n" for k, v in loading.items())
    with open(prm, "w") as f:
        f.write(f"set Output file = {name}.csv\nset Overwrite existing output = true\n"
                f"{material}\nsubsection Loading\n{entries}end\n")
    r = subprocess.run([args.anvil, "--material-point", prm], cwd=args.work_dir,
                       capture_output=True, text=True)
    if not checker.check_true(f"{name}: driver runs", r.returncode == 0, r.stderr.strip()):
        checker.finish()
    return read_csv(os.path.join(args.work_dir, name + ".csv"))


def write_scene(path, include=None, text=""):
    """Write a scene file; 'include' pulls in a real scene from prm/ whose
    entries 'text' then overrides."""
    with open(path, "w") as f:
        if include:
            f.write(f"include {include}\n")
        f.write(text)
    return path


def overrides_text(overrides):
    """Scene-file text that sets OVERRIDES, a dict of 'Subsection/.../Entry':
    value (the form of anvil's --set)."""
    text = ""
    for key, value in overrides.items():
        *sections, entry = key.split("/")
        text += "".join(f"subsection {s}\n" for s in sections) + f"set {entry} = {value}\n" + "end\n" * len(sections)
    return text


def test_scene(args, path, name, overrides=None, text=""):
    """Write NAME.prm into the work directory: the scene PATH (relative to
    the source tree, e.g. tests/contact/friction_block.prm) as a user would
    run it, with OVERRIDES (see overrides_text), then TEXT (scene-file
    text, e.g. a whole material subsection). Its results go to
    output/NAME."""
    return write_scene(os.path.join(args.work_dir, name + ".prm"),
                       include=os.path.join(os.path.abspath(args.source_dir), path),
                       text=overrides_text(overrides or {}) + text)


def read_csv(path):
    """Columns of a CSV file as a dict of lists: floats, or strings for
    columns that are not numbers (names)."""
    with open(path) as f:
        rows = list(csv.DictReader(f))

    def column(k):
        try:
            return [float(r[k]) for r in rows]
        except ValueError:
            return [r[k] for r in rows]
    return {k: column(k) for k in rows[0].keys()}


def read_vtu_cells(path):
    """Cell values of a VTU piece or a PVTU frame of Anvil's, read with VTK:
    {name: [value per cell]} for the scalar arrays (scripts/anvil_vtu.py)."""
    return read_vtu(path)[1]


def max_relative_difference(a, b):
    """Largest difference of two column dicts, each column scaled by its
    largest magnitude (at least 1e-6 of the file's largest: columns that
    are pure round-off noise, like a transverse momentum of 1e-19, are
    compared on the file's scale)."""
    worst = 0.0
    file_max = max(max(abs(x) for x in col) for col in a.values())
    for k in a:
        if k not in b or len(a[k]) != len(b[k]):
            return float("inf")
        scale = max(max(abs(x) for x in a[k]), max(abs(x) for x in b[k]),
                    1e-6 * file_max, 1e-300)
        for x, y in zip(a[k], b[k]):
            worst = max(worst, abs(x - y) / scale)
    return worst


def uniaxial_boundary_conditions(body, velocity):
    """Scene text of the uniaxial-stress box: symmetry planes on the x-, y-
    and z- faces (boundary ids 0, 2, 4) of 'body', its x+ face (id 1) moving
    at 'velocity' in x. Name them in 'Boundary conditions' as
    sym_x, sym_y, sym_z, pull."""
    text = ""
    for name, bid, comp in (("sym_x", 0, "x"), ("sym_y", 2, "y"), ("sym_z", 4, "z")):
        text += (f"subsection Boundary condition {name}\n  set Body = {body}\n"
                 f"  set Boundary ids = {bid}\n  set Components = {comp}\nend\n")
    return text + (f"subsection Boundary condition pull\n  set Body = {body}\n  set Boundary ids = 1\n"
                   f"  set Type = velocity\n  set Velocity = {velocity}, 0, 0\n  set Components = x\nend\n")


def deviation_from_driver(driver, probe, L):
    """Largest |sigma_xx(element) - sigma_xx(driver)| over the driver's peak
    |sigma_xx|, the driver's stress interpolated at the element's
    logarithmic strain ln(1 + u_x / L), over the rows inside the driver's
    strain range (tension or compression), and the element's final strain."""
    strain = [math.log(1 + u / L) for u in probe["ux"]]
    sign = 1.0 if driver["strain_xx"][-1] >= 0 else -1.0
    es = [sign * e for e in driver["strain_xx"]]
    ss = driver["stress_xx"]
    peak = max(abs(s) for s in ss)
    worst = 0.0
    for e, s in zip(strain, probe["stress_xx"]):
        i = bisect.bisect_left(es, sign * e)
        if i == 0 or i >= len(es):
            continue
        e0, e1 = es[i - 1], es[i]
        s_ref = ss[i - 1] + (sign * e - e0) / (e1 - e0) * (ss[i] - ss[i - 1])
        worst = max(worst, abs(s - s_ref) / peak)
    return worst, strain[-1]


# Meshes for contact tests, written as ABAQUS .inp files (C3D8).

def graded(n, r):
    """n + 1 coordinates in [0, 1], each interval r times the one before."""
    sizes = [r ** i for i in range(n)]
    x = [0.0]
    for h in sizes:
        x.append(x[-1] + h / sum(sizes))
    return x


def ball_nodes(R, n, r):
    """Nodes of a quarter ball of radius R (x, y >= 0), n x n x 2n
    hexahedra, finer towards its south pole (0, 0, -R): a graded block
    [0,1]^2 x [-1,1] mapped onto the ball by p -> R p |p|_inf / |p|_2."""
    import math
    xs, zs = graded(n, r), [-1 + 2 * z for z in graded(2 * n, r ** 0.5)]
    nodes = []
    for z in zs:
        for y in xs:
            for x in xs:
                norm = math.sqrt(x * x + y * y + z * z)
                s = R * max(abs(x), abs(y), abs(z)) / norm if norm > 0 else 0.0
                nodes.append((x * s, y * s, z * s))
    return nodes, (n, n, 2 * n)


def lumped_masses(nodes, n, rho):
    """Row-sum lumped masses rho int N_i dV of the structured hexahedra
    (2 x 2 x 2 Gauss points, exact for trilinear elements)."""
    import itertools
    node = lambda i, j, k: i + (n[0] + 1) * (j + (n[1] + 1) * k)
    m = [0.0] * len(nodes)
    g = 1 / 3 ** 0.5
    corners = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
               (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
    for k, j, i in itertools.product(range(n[2]), range(n[1]), range(n[0])):
        ids = [node(i + a, j + b, k + c) for a, b, c in
               ((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))]
        for q in itertools.product((-g, g), repeat=3):
            N = [(1 + c[0] * q[0]) * (1 + c[1] * q[1]) * (1 + c[2] * q[2]) / 8 for c in corners]
            J = [[sum(c[a] * (1 + c[(a + 1) % 3] * q[(a + 1) % 3]) * (1 + c[(a + 2) % 3] * q[(a + 2) % 3])
                      / 8 * nodes[ids[v]][d] for v, c in enumerate(corners)) for d in range(3)]
                 for a in range(3)]
            det = (J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1])
                   - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0])
                   + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]))
            for v in range(8):
                m[ids[v]] += rho * N[v] * abs(det)
    return m


def check_hertz_speeds(c, speeds, hertz, run, tolerance):
    """Hertz's impact at each of 'speeds': run(v) gives (peak force,
    contact time, largest balance error), hertz(v) the closed form's (F_max,
    t_c). Checks each within 'tolerance' (relative), the balance below 1 %
    and the exponents of v between the first and last speed within 0.02 of
    Hertz's 6/5 and -1/5; returns {v: run(v)}."""
    results = {}
    for v in speeds:
        F_max, t_c = hertz(v)
        peak, duration, balance = results[v] = run(v)
        print(f"  {v} m/s: Hertz {F_max:.3f} N, {1000 * t_c:.3f} ms; Anvil {peak:.3f} N "
              f"({peak / F_max - 1:+.4f}), {1000 * duration:.3f} ms ({duration / t_c - 1:+.4f})")
        c.check(f"{v} m/s: peak force [N]", peak, F_max, tolerance, relative=True)
        c.check(f"{v} m/s: contact time [s]", duration, t_c, tolerance, relative=True)
        c.check_below(f"{v} m/s: largest energy balance error", balance, 0.01)
    lo, hi = speeds[0], speeds[-1]
    span = math.log(hi / lo)
    c.check("exponent of v in the peak force", math.log(results[hi][0] / results[lo][0]) / span, 1.2, 0.02)
    c.check("exponent of v in the contact time", math.log(results[hi][1] / results[lo][1]) / span, -0.2, 0.02)
    return results
