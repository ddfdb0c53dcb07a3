"""Bad input never crashes Anvil: mutated copies of the shipped scenes.

Each case copies prm/ (so that includes resolve), mutates one scene once
and runs 'anvil --check' on it; a few that pass the check also run for a
few steps. The mutations (fixed seed, so every run tries the same cases):
one value of a 'set' line replaced by something a user could write or
paste (empty, signs, 1e308, 1e400, 1e-320, nan, inf, '1,2', lists, words,
10^5 characters, bytes that are no text), a line deleted or doubled, an
'end' removed, the file cut at a random byte, a scene that includes
itself.

Also 32 mutated copies of a keyword deck in fixed columns (some with a
column shifted, so that values run into each other) and 16 of a whole
ABAQUS deck, checked as they come ('anvil --check DECK'), and 24 mutated
copies of an Abaqus/CAE-layout deck (parts, an instance
with translation and rotation, sets, a surface, a step) and 32 of a Gmsh
file (tests/input/two_blocks.geo; when gmsh is installed) through
'--check' of a scene that takes a region, a surface or node set and a
probe from them: a value replaced, a line deleted or doubled, the file cut.
The cases run two at a time.

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
from concurrent.futures import ThreadPoolExecutor
from anvil_test import Checker, arguments

args = arguments()
c = Checker("fuzz: mutated scenes give exit 0 or one error line and exit 2")
rng = random.Random(20261124)
cases_check, cases_run = 32, 8

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


# Mesh files as they come (an Abaqus/CAE-layout deck; a Gmsh file when
# gmsh is installed), mutated line by line like the scenes.
DECK = """*Heading
*Part, name=Bar
*Node
 501, 0., 0., 0.
 502, 10., 0., 0.
 503, 10., 10., 0.
 504, 0., 10., 0.
 505, 0., 0., 10.
 506, 10., 0., 10.
 507, 10., 10., 10.
 508, 0., 10., 10.
*Element, type=C3D8R
1001, 501, 502, 503, 504, 505, 506, 507, 508
*Elset, elset=All, generate
 1001, 1001, 1
*Nset, nset=Tip
 507,
*Elset, elset=_Front_S6, internal
 1001,
*Surface, type=ELEMENT, name=Front
_Front_S6, S6
*End Part
*Assembly, name=Assembly
*Instance, name=Bar-1, part=Bar
  5., 0., 0.
  5., 0., 0., 5., 0., 1., 90.
*End Instance
*Nset, nset=Fixed, instance=Bar-1
 501, 504, 505, 508
*End Assembly
*Material, name=Steel
*Elastic
200000., 0.3
*Step, name=Step-1
*Dynamic, Explicit
, 0.001
*End Step
"""
MESH_SCENE = """set Bodies = bar
subsection Body bar
  subsection Mesh
    set Source = file
    set File name = {mesh}
    set Region = {region}
    set Scale = 0.001
  end
end
set Boundary conditions = support
subsection Boundary condition support
  set Body = bar
  set Selection = {selection}
  set {names_entry} = {names}
end
set Probes = tip
subsection Probe tip
  set Body = bar
  set Node set = {node_set}
end
"""
# Decks that run as they come: a keyword deck in fixed columns (two
# elements, a rigid wall, an initial velocity by part and node by node, a
# constrained set) and the
# ABAQUS deck above made whole (a section, a density, a velocity).
KEYWORD_DECK = """*KEYWORD
*TITLE
two bricks on a wall
*CONTROL_TERMINATION
   1.0-3
*CONTROL_TIMESTEP
       0.0       0.8
*DATABASE_GLSTAT
   1.0-5
*PART
bricks
         1         1         1         0         0
*SECTION_SOLID
         1         1
*MAT_PLASTIC_KINEMATIC
         1    7.85-9  200000.0       0.3     350.0    1000.0       0.0
      40.0       5.0       0.0
*INITIAL_VELOCITY_GENERATION
         1         2       0.0  -10000.0       0.0       0.0
$ centre
*SET_NODE_LIST
         7
      1001      1004      1005      1008
*INITIAL_VELOCITY_NODE
      1001  -10000.0       0.0       0.0
      1002  -10000.0       0.0       0.0
      1003  -10000.0       0.0       0.0
      1004  -10000.0       0.0       0.0
      1005  -10000.0       0.0       0.0
      1006  -10000.0       0.0       0.0
      1007  -10000.0       0.0       0.0
      1008  -10000.0       0.0       0.0
      1009  -10000.0       0.0       0.0
      1010  -10000.0       0.0       0.0
      1011  -10000.0       0.0       0.0
      1012  -10000.0       0.0       0.0
*BOUNDARY_SPC_SET
         7         0         0         1         0         0         0         0
*RIGIDWALL_PLANAR
         0         0         0
      -1.0       0.0       0.0       1.0       0.0       0.0       0.1
*NODE
    1001             0.0             0.0             0.0       0       0
    1002            10.0             0.0             0.0       0       0
    1003            10.0            10.0             0.0       0       0
    1004             0.0            10.0             0.0       0       0
    1005             0.0             0.0            10.0       0       0
    1006            10.0             0.0            10.0       0       0
    1007            10.0            10.0            10.0       0       0
    1008             0.0            10.0            10.0       0       0
    1009            20.0             0.0             0.0       0       0
    1010            20.0            10.0             0.0       0       0
    1011            20.0             0.0            10.0       0       0
    1012            20.0            10.0            10.0       0       0
*ELEMENT_SOLID
       1       1    1001    1002    1003    1004    1005    1006    1007    1008
       2       1    1002    1009    1010    1003    1006    1011    1012    1007
*END
"""
WHOLE_DECK = DECK.replace("*End Part", "*Solid Section, elset=All, material=Steel\n,\n*End Part").replace(
    "*Elastic", "*Density\n7.85e-9,\n*Elastic").replace(
    "*End Assembly", "*Nset, nset=Whole, instance=Bar-1\n 501, 502, 503, 504, 505, 506, 507, 508\n*End Assembly").replace(
    "*Step, name=Step-1", "*Initial Conditions, type=VELOCITY\nWhole, 1, 100.\n*Step, name=Step-1")
msh_text = None
gmsh = shutil.which("gmsh")
if gmsh:
    geo = os.path.join(args.source_dir, "tests", "input", "two_blocks.geo")
    target = os.path.join(args.work_dir, "blocks.msh")
    if subprocess.run([gmsh, "-3", "-format", "msh41", geo, "-o", target],
                      capture_output=True).returncode == 0:
        with open(target, encoding="latin-1") as f:
            msh_text = f.read()
cases_inp, cases_msh = 12, 12 if msh_text else 0
cases_k, cases_whole = 16, 8


def mutate_mesh(lines):
    kind = rng.randrange(5)
    if kind <= 1 and lines:
        i = rng.randrange(len(lines))
        tokens = lines[i].rstrip("\n").replace(",", " , ").split()
        if tokens:
            tokens[rng.randrange(len(tokens))] = rng.choice(values[:-4] + ["-5", "99999", "S9"])
        lines[i] = " ".join(tokens).replace(" , ", ", ") + "\n"
        return "mesh value", lines
    if kind == 2 and lines:
        del lines[rng.randrange(len(lines))]
        return "mesh line deleted", lines
    if kind == 3 and lines:
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
        return "mesh line doubled", lines
    text = "".join(lines)
    return "mesh cut", [text[:rng.randrange(max(1, len(text)))]]


# The cases, drawn in a fixed order, then run two at a time.
work = os.path.join(args.work_dir, "cases")
shutil.rmtree(work, ignore_errors=True)
cases = []
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
         # Staged scenes set their own end times: a step limit ends them too.
         "--set", "Simulation/Maximum number of steps=400",
         "--set", "Simulation/Overwrite existing output=true"]
    cases.append((case, name, kind, checking, cmd))
for n in range(cases_inp + cases_msh):
    case = os.path.join(work, f"mesh{n}")
    os.makedirs(case)
    inp = n < cases_inp
    mesh = "deck.inp" if inp else "blocks.msh"
    kind, lines = mutate_mesh((DECK if inp else msh_text).splitlines(keepends=True))
    with open(os.path.join(case, mesh), "w", encoding="latin-1") as f:
        f.writelines(lines)
    scene = MESH_SCENE.format(mesh=mesh, region="Bar-1" if inp else "Striker",
                              selection="surface" if n % 2 else "node set",
                              names_entry="Surfaces" if n % 2 else "Node sets",
                              names=("Front" if n % 2 else "Fixed") if inp else "7",
                              node_set="Bar-1.Tip" if inp else "7")
    if not inp:
        scene = scene.replace("set Probes = tip", "set Probes =")
        scene = scene[:scene.index("subsection Probe tip")]
    path = os.path.join(case, "scene.prm")
    with open(path, "w") as f:
        f.write(scene)
    cases.append((case, mesh, kind, True, [args.anvil, "--check", path]))


for n in range(cases_k + cases_whole):
    case = os.path.join(work, f"deck{n}")
    os.makedirs(case)
    keyword = n < cases_k
    name = "deck.k" if keyword else "whole.inp"
    kind, lines = mutate_mesh((KEYWORD_DECK if keyword else WHOLE_DECK).splitlines(keepends=True))
    if keyword and rng.random() < 0.3:
        # Fixed columns shifted: values run into their neighbours.
        i = rng.randrange(len(lines))
        at = rng.randrange(max(1, len(lines[i])))
        lines[i] = lines[i][:at] + lines[i][at + 1:]
        kind = "deck column shifted"
    with open(os.path.join(case, name), "w", encoding="latin-1") as f:
        f.writelines(lines)
    cases.append((case, name, kind.replace("mesh", "deck"), True, [args.anvil, "--check", name]))


def execute(case):
    directory, name, kind, checking, cmd = case
    code, err = run(cmd, directory if name.endswith((".inp", ".msh", ".k")) else
                    os.path.dirname(cmd[-1] if checking else cmd[1]))
    return case, code, err


bad, refused, passed, ran = [], {}, 0, 0
with ThreadPoolExecutor(max_workers=2) as pool:
    results = list(pool.map(execute, cases))
for (directory, name, kind, checking, cmd), code, err in results:
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
        shutil.rmtree(directory, ignore_errors=True)

total = len(cases)
print(f"{total} cases: {cases_check} mutated scenes checked and {cases_run} run for 2e-6 s or 400 steps, "
      f"{cases_inp} mutated ABAQUS meshes, {cases_msh} mutated Gmsh files, {cases_k} mutated keyword decks and "
      f"{cases_whole} mutated whole ABAQUS decks checked: {passed} passed, "
      f"{total - passed - len(bad)} refused with one line, {len(bad)} bad")
for kind, line in sorted(refused.items()):
    print(f"  refused ({kind}): {line}")
for b in bad:
    print("  BAD " + b)
c.check_below("cases that crashed, hung, or failed without exactly one error line", len(bad), 0)
c.finish()
