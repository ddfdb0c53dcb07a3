"""Every scene in prm/ parses and sets up (anvil --check), every study
file and each of its runs parses (anvil --study --check): examples cannot
rot unnoticed."""
import glob
import os
from anvil_test import Checker, arguments, run_anvil

args = arguments()
c = Checker("every prm/ scene is valid")
scenes = sorted(glob.glob(os.path.join(args.source_dir, "prm/*/*.prm")))
c.check_true("there are scenes", len(scenes) > 0, f"{len(scenes)} found")
for prm in scenes:
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
    c.check_true(os.path.relpath(prm, args.source_dir), code == 0, (out + err).strip().splitlines()[-1] if (out + err).strip() else "")
studies = sorted(glob.glob(os.path.join(args.source_dir, "prm/*/studies/*.prm")))
for prm in studies:
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--study", "--check"])
    c.check_true(os.path.relpath(prm, args.source_dir), code == 0, (out + err).strip().splitlines()[-1] if (out + err).strip() else "")
c.finish()
