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
for prm in scenes:
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
    c.check_true(os.path.relpath(prm, args.source_dir), code == 0, (out + err).strip().splitlines()[-1] if (out + err).strip() else "")
studies = sorted(glob.glob(os.path.join(args.source_dir, "prm/*/studies/*.prm")))
for prm in studies:
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--study", "--check"])
    c.check_true(os.path.relpath(prm, args.source_dir), code == 0, (out + err).strip().splitlines()[-1] if (out + err).strip() else "")
c.finish()
