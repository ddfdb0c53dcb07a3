"""doc/parameters.prm is what 'anvil --print-parameters' prints: the
parameter reference cannot fall behind the code (regenerate it with
scripts/make-parameter-doc). Also checks that every entry's documentation
states its units or is a name, list or selection."""
import os
import re
import subprocess
from anvil_test import Checker, arguments

args = arguments()
c = Checker("parameter reference is current and documents units")
# The documented defaults are a user's: without the test suite's own.
env = {k: v for k, v in os.environ.items() if k != "ANVIL_DEFAULT_PLOTS"}
printed = subprocess.run([args.anvil, "--print-parameters"], capture_output=True, text=True, env=env).stdout
with open(os.path.join(args.source_dir, "doc/parameters.prm")) as f:
    stored = f.read()
c.check_true("doc/parameters.prm equals anvil --print-parameters", printed == stored,
             "run scripts/make-parameter-doc" if printed != stored else "")
driver = subprocess.run([args.anvil, "--print-parameters", "--material-point"],
                        capture_output=True, text=True, env=env).stdout
with open(os.path.join(args.source_dir, "doc/material_point_parameters.prm")) as f:
    c.check_true("doc/material_point_parameters.prm equals anvil --print-parameters --material-point",
                 driver == f.read(), "run scripts/make-parameter-doc")
printed += driver
study = subprocess.run([args.anvil, "--print-parameters", "--study"], capture_output=True, text=True, env=env).stdout
with open(os.path.join(args.source_dir, "doc/study_parameters.prm")) as f:
    c.check_true("doc/study_parameters.prm equals anvil --print-parameters --study",
                 study == f.read() and "Variable NAME" in study, "run scripts/make-parameter-doc")
printed += study

# Every numeric entry (pattern Double or Integer) must say 'Units:'.
missing = []
doc = []
for line in printed.splitlines():
    s = line.strip()
    if s.startswith("#"):
        doc.append(s)
    elif s.startswith("set "):
        name = s[4:].split("=")[0].strip()
        text = " ".join(doc)
        numeric = re.search(r"\b(\d|0\.\d)", s.split("=", 1)[1]) is not None
        if numeric and "Units:" not in text and "Names" not in text:
            missing.append(name)
        doc = []
    else:
        doc = []
c.check_true("every numeric entry documents its units", not missing, ", ".join(sorted(set(missing))))
c.finish()
