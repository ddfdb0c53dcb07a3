"""Bad input never crashes Anvil: mutated copies of the shipped scenes.

Each case copies prm/ (so that includes resolve), mutates one scene once
and runs 'anvil --check' on it; a few that pass the check also run for a
few steps. The mutations (fixed seed, so every run tries the same cases):
one value of a 'set' line replaced by something a user could write or
paste (empty, signs, 1e308, 1e400, 1e-320, nan, inf, '1,2', lists, words,
10^5 characters, bytes that are no text), a line deleted or doubled, an
'end' removed, the file cut at a random byte, a scene that includes
itself.

Checked for every case: the exit status is 0 or 2 for --check (0, 2 or 3
for a run), never a signal, an abort or a hang (30 s); every failure
prints exactly one line on stderr, starting 'anvil: error:' and at most
600 characters long, whatever the input. Printed: how many cases passed
the check, how many were refused, and an example of each kind of refusal.
"""
import glob
import os
import random
import shutil
import subprocess
from anvil_test import Checker, arguments

args = arguments()
c = Checker("fuzz: mutated scenes give exit 0 or one error line and exit 2")
rng = random.Random(20261124)
cases_check, cases_run = 120, 8

source = os.path.join(args.source_dir, "prm")
scenes = sorted(os.path.relpath(p, source) for p in glob.glob(os.path.join(source, "*", "*.prm")))

values = ["", "-1", "0", "1e308", "-1e308", "1e400", "1e-320", "nan", "inf", "1,2", "1;2", "abc",
          "1, 2, 3, 4, 5, 6, 7", ",,,", "(", "1e", ".", "true", "x" * 100000,
          "1" * 400, "\x00\x01\xff\xfe", "2147483648", "-2147483649", "1e-300"]


def mutate(lines, name):
    kind = rng.randrange(7)
    sets = [i for i, l in enumerate(lines) if l.strip().startswith("set ") and "=" in l]
    if kind <= 2 and sets:
        i = rng.choice(sets)
        head = lines[i].split("=", 1)[0]
        lines[i] = head + "= " + rng.choice(values) + "\n"
        return "value", lines
    if kind == 3 and lines:
        del lines[rng.randrange(len(lines))]
        return "line deleted", lines
    if kind == 4 and lines:
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
        return "line doubled", lines
    if kind == 5:
        ends = [i for i, l in enumerate(lines) if l.strip() == "end"]
        if ends:
            del lines[rng.choice(ends)]
            return "end removed", lines
    if rng.random() < 0.5:
        return "includes itself", ["include " + os.path.basename(name) + "\n"] + lines
    text = "".join(lines)
    return "cut", [text[:rng.randrange(max(1, len(text)))]]


def run(cmd, cwd):
    try:
        r = subprocess.run(cmd, cwd=cwd, capture_output=True, timeout=30)
    except subprocess.TimeoutExpired:
        return None, b""
    return r.returncode, r.stderr


work = os.path.join(args.work_dir, "cases")
shutil.rmtree(work, ignore_errors=True)
bad, refused, passed, ran = [], {}, 0, 0
for n in range(cases_check + cases_run):
    case = os.path.join(work, str(n))
    shutil.copytree(source, case)
    name = rng.choice(scenes)
    path = os.path.join(case, name)
    with open(path, encoding="latin-1") as f:
        lines = f.readlines()
    kind, lines = mutate(lines, name)
    with open(path, "w", encoding="latin-1") as f:
        f.writelines(lines)
    checking = n < cases_check
    cmd = [args.anvil, "--check", path] if checking else \
        [args.anvil, path, "--set", "Simulation/End time=2e-6",
         "--set", "Simulation/Overwrite existing output=true"]
    code, err = run(cmd, os.path.dirname(path))
    err_lines = [l for l in err.decode("latin-1").splitlines() if l.strip()]
    allowed = (0, 2) if checking else (0, 2, 3)
    one_line = code == 0 or (len(err_lines) == 1 and err_lines[0].startswith("anvil: error:")
                             and len(err_lines[0]) <= 600)
    if code not in allowed or not one_line:
        bad.append(f"{name} ({kind}{'' if checking else ', run'}): exit {code}, "
                   f"{len(err_lines)} line(s): {' | '.join(err_lines)[:300]!r}")
    elif code == 0:
        passed += 1
        ran += not checking
    else:
        refused.setdefault(kind, err_lines[0][:200])
    if code in allowed and one_line:
        shutil.rmtree(case, ignore_errors=True)

print(f"{cases_check} mutated scenes checked and {cases_run} run for 2e-6 s: {passed} passed, "
      f"{cases_check + cases_run - passed - len(bad)} refused with one line, {len(bad)} bad")
for kind, line in sorted(refused.items()):
    print(f"  refused ({kind}): {line}")
for b in bad:
    print("  BAD " + b)
c.check_below("cases that crashed, hung, or failed without exactly one error line", len(bad), 0)
c.finish()
