"""The benchmark scripts stay runnable as the code and the test helpers
change: each benchmarks/**/*.py compiles, every name it imports from
tests/anvil_test.py exists there, and every scene or mesh file it names
under the source tree (os.path.join of the source or benchmark folder,
named SOURCE, HERE or top, and strings ending in .prm, .inp, .k or .msh)
exists. (Three scripts once imported
scene builders that the test helpers no longer had, and failed at their
first line.) Each script given '--help' answers without a traceback
(argparse's help, or one usage line and a non-zero exit where the anvil
executable comes first), within 60 s. The C++ benchmark element_throughput
answers bad counts with one line and exit 1."""
import ast
import glob
import os
import subprocess
import sys
import anvil_test
from anvil_test import Checker, arguments

args = arguments()
c = Checker("benchmark scripts import what exists")
scripts = sorted(glob.glob(os.path.join(args.source_dir, "benchmarks", "**", "*.py"), recursive=True))
c.check_true("benchmarks/ has scripts", len(scripts) > 0)
for path in scripts:
    name = os.path.relpath(path, args.source_dir)
    with open(path) as f:
        text = f.read()
    try:
        tree = ast.parse(text, name)
    except SyntaxError as e:
        c.check_true(f"{name} compiles", False, str(e))
        continue
    missing = [alias.name for node in ast.walk(tree)
               if isinstance(node, ast.ImportFrom) and node.module == "anvil_test"
               for alias in node.names if not hasattr(anvil_test, alias.name)]
    c.check_true(f"{name}: its imports from anvil_test exist", not missing, "missing: " + ", ".join(missing))
    # Files named by their path parts in os.path.join(..., "a", "b.prm").
    named = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "join":
            parts = [a.value for a in node.args if isinstance(a, ast.Constant) and isinstance(a.value, str)]
            first = node.args[0] if node.args else None
            rooted = isinstance(first, ast.Name) and first.id.lower() in ("source", "here", "top")
            if rooted and parts and parts[-1].endswith((".prm", ".inp", ".k", ".msh")) and \
                    len(parts) == len(node.args) - 1:
                named.append(os.path.join(*parts))
    absent = [n for n in named if not any(os.path.exists(os.path.join(base, n))
                                          for base in (args.source_dir, os.path.dirname(path)))]
    c.check_true(f"{name}: the scene files it names exist ({len(named)})", not absent, "absent: " + ", ".join(absent))
    env = dict(os.environ, PYTHONPATH=os.path.join(args.source_dir, "tests"))
    try:
        r = subprocess.run([sys.executable, path, "--help"], capture_output=True, text=True, timeout=60,
                           cwd=args.work_dir, env=env)
        answer = r.stdout + r.stderr
        c.check_true(f"{name} --help: usage or help, no traceback",
                     "Traceback" not in answer and ("usage" in answer.lower()), answer.strip()[-300:])
    except subprocess.TimeoutExpired:
        c.check_true(f"{name} --help: answers within 60 s", False)
# The C++ benchmark beside the executable: a bad count is one line and
# exit 1 (it once ran 0 elements and printed inf and nan); a small run
# answers.
throughput = os.path.join(os.path.dirname(args.anvil), "benchmarks", "element_throughput")
if os.path.exists(throughput):
    for bad in (["--help"], ["10", "x"], ["1"], ["10", "0"]):
        r = subprocess.run([throughput] + bad, capture_output=True, text=True, timeout=60)
        c.check_true(f"element_throughput {' '.join(bad)}: one line, exit 1",
                     r.returncode == 1 and r.stdout == "" and len(r.stderr.strip().splitlines()) == 1,
                     f"exit {r.returncode}: {(r.stdout + r.stderr).strip()[-300:]}")
    r = subprocess.run([throughput, "4", "2", "elastic"], capture_output=True, text=True, timeout=60)
    c.check_true("element_throughput 4 2 elastic: runs", r.returncode == 0 and "ns per element-cycle" in r.stdout,
                 (r.stdout + r.stderr).strip()[-300:])
c.finish()
