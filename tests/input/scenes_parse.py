"""Every scene in prm/ and every test scene under tests/ parses and sets
up (anvil --check) as a user would run it, every study file and each of its
runs parses (anvil --study --check): examples cannot rot unnoticed."""
import glob
import os
from anvil_test import Checker, arguments, run_anvil

args = arguments()
c = Checker("every prm/ and tests/ scene is valid")
scenes = sorted(glob.glob(os.path.join(args.source_dir, "prm/*/*.prm")))
c.check_true("there are scenes", len(scenes) > 0, f"{len(scenes)} found")
tests = sorted(glob.glob(os.path.join(args.source_dir, "tests/*/*.prm")))
c.check_true("there are test scenes", len(tests) > 0, f"{len(tests)} found")
scenes += tests
checked = []
for prm in scenes:
    libraries = [l.split("=", 1)[1].strip() for l in open(prm) if l.strip().startswith("set Additional shared libraries")]
    missing = [lib for lib in libraries if lib and not os.path.exists(os.path.join(os.path.dirname(prm), lib))]
    if missing:
        # A plugin example's scene: its test builds the plugin and runs it.
        print(f"  (not checked: {os.path.relpath(prm, args.source_dir)} loads {', '.join(missing)}, not built here)")
        continue
    checked.append(prm)
# One process checks them all (anvil --check A.prm B.prm ...): each scene
# prints its own line, "FILE: scene '...' is valid" or "anvil: error: FILE: ...".
code, out, err = run_anvil(args.anvil, checked[0], cwd=args.work_dir, extra_args=["--check"] + checked[1:])
lines = (out + err).splitlines()
for prm in checked:
    valid = any(l.startswith(prm + ": scene ") and " is valid" in l for l in lines)
    why = [l for l in lines if l.startswith("anvil: error: " + prm + ":")]
    c.check_true(os.path.relpath(prm, args.source_dir), valid, why[0] if why else "")
c.check_true("the exit status says whether every scene is valid", (code == 0) == all(
    any(l.startswith(prm + ": scene ") and " is valid" in l for l in lines) for prm in checked), f"exit {code}")
studies = sorted(glob.glob(os.path.join(args.source_dir, "prm/*/studies/*.prm")))
for prm in studies:
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--study", "--check"])
    c.check_true(os.path.relpath(prm, args.source_dir), code == 0, (out + err).strip().splitlines()[-1] if (out + err).strip() else "")
c.finish()
