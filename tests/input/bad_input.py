"""Bad input gets one clear error line and a non-zero exit, never a crash or
a hang, and results of an earlier run are not overwritten silently.

Each case is a small scene with one mistake; the check is the exit status
(2 for input, 3 for a numerical failure during the run), a single line
starting 'anvil: error:' that names the file and the offending entry, and
for the inverted element the time, step, element and position.
"""
import os
import subprocess
from anvil_test import Checker, arguments, run_anvil, write_scene, together

args = arguments()
c = Checker("bad input")
block = """
set Bodies = block
subsection Simulation
  set End time = 0.5
  set Print wall times = false
end
subsection Body block
  subsection Mesh
    set Upper corner = 1, 1, 1
    set Subdivisions = 2, 2, 2
{mesh}
  end
  subsection Material
    subsection elastic
      set Density = 0.01
      set Young's modulus = 100
      set Poisson's ratio = {nu}
    end
  end
{extra}
end
"""
cases = [
    ("unknown_entry", dict(mesh="", nu="0.3", extra="  set Youngs modulus = 5"), 2,
     ["unknown_entry.prm", "Youngs modulus", "--print-parameters"]),
    ("out_of_range", dict(mesh="", nu="0.7", extra=""), 2,
     ["out_of_range.prm", "Poisson's ratio", "0.7", "-1...0.5"]),
    ("missing_mesh", dict(mesh="    set Source = file\n    set File name = no_such_mesh.msh", nu="0.3", extra=""), 2,
     ["missing_mesh.prm", "no_such_mesh.msh", "cannot be opened"]),
    ("unknown_indicator", dict(mesh="", nu="0.3", extra="  subsection Refinement region\n"
                               "    set Indicator = damage\n  end"), 2,
     ["Refinement region", "Indicator", "damage", "its variables: none"]),
]
plastic = """  subsection Material
    set Model = plastic kinematic
    subsection plastic kinematic
      {entries}
    end
  end"""
cases += [
    ("preset_not_number", dict(mesh="", nu="0.3", extra=plastic.format(
        entries="set Preset = Table 1 steel\n      set Yield stress = 335 MPa")), 2,
     ["preset_not_number.prm", "Yield stress", "not a number"]),
    ("no_preset", dict(mesh="", nu="0.3", extra=plastic.format(entries="set Density = 7850")), 2,
     ["no_preset.prm", "Young's modulus", "Preset"]),
    ("tangent_modulus", dict(mesh="", nu="0.3", extra=plastic.format(
        entries="set Preset = Table 1 steel\n      set Tangent modulus = 3e11")), 2,
     ["tangent_modulus.prm", "Tangent modulus", "E_t < E"]),
]
concrete = plastic.replace("plastic kinematic", "concrete damaged plasticity")
cases += [
    ("no_dilation_angle", dict(mesh="", nu="0.3", extra=concrete.format(
        entries="set Compressive strength = 45.4e6")), 2,
     ["no_dilation_angle.prm", "Dilation angle", "0 < psi < 60"]),
    ("weak_concrete", dict(mesh="", nu="0.3", extra=concrete.format(
        entries="set Compressive strength = 10e6\n      set Dilation angle = 36")), 2,
     ["weak_concrete.prm", "Compressive strength", "tabulated"]),
    ("open_tension_table", dict(mesh="", nu="0.3", extra=concrete.format(
        entries="set Compressive strength = 45e6\n      set Dilation angle = 36\n"
                "      set Curves = tabulated\n      set Young's modulus = 3e10\n"
                "      set Compression table = 0:18e6, 0.001:45e6\n"
                "      set Tension table = 0:3e6, 1e-4:1e6")), 2,
     ["open_tension_table.prm", "Tension table", "stress 0"]),
    ("imperfection_elastic", dict(mesh="", nu="0.3", extra="""  subsection Imperfection
    set Lower corner = 0, 0, 0
    set Upper corner = 0.5, 1, 1
  end"""), 2,
     ["imperfection_elastic.prm", "Imperfection", "concrete damaged plasticity"]),
]
# (Two cases at a time, one a core; checked in order.)
runs = together(*[lambda case=case: run_anvil(args.anvil, write_scene(
    os.path.join(args.work_dir, case[0] + ".prm"), text=block.format(**case[1])), cwd=args.work_dir)
    for case in cases], at_once=2)
for (name, fields, status, words), (code, out, err) in zip(cases, runs):
    lines = [l for l in err.splitlines() if l.strip()]
    print(f"    {name}: {lines[-1] if lines else '(no message)'}")
    c.check_true(f"{name}: exit status {status}", code == status, f"got {code}")
    c.check_true(f"{name}: exactly one error line naming {words}",
                 len(lines) == 1 and lines[0].startswith("anvil: error:") and all(w in lines[0] for w in words))

# Unknown body named by a boundary condition.
prm = write_scene(os.path.join(args.work_dir, "unknown_body.prm"),
                  text=block.format(mesh="", nu="0.3", extra="") +
                  "set Boundary conditions = wall\nsubsection Boundary condition wall\n  set Body = blok\nend\n")
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
lines = [l for l in err.splitlines() if l.strip()]
print(f"    unknown_body: {lines[-1] if lines else ''}")
c.check_true("unknown body: exit 2 with one line naming it", code == 2 and len(lines) == 1 and "blok" in lines[0])

# 'Maximum time step' with a comma outside parentheses ('1,2' for 1.2), and
# one that is no expression.
for name, value, words in (("max_dt_comma", "1,2", ["Maximum time step", "comma"]),
                           ("max_dt_garbage", "1e-7 +* t", ["Maximum time step"]),
                           ("capacity_drop_alone", None, ["End capacity drop", "Capacity support"])):
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"),
                      text=block.format(mesh="", nu="0.3", extra="") +
                      (f"subsection Simulation\n  set Maximum time step = {value}\nend\n" if value else
                       "subsection Simulation\n  set End capacity drop = 0.5\nend\n"))
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
    lines = [l for l in err.splitlines() if l.strip()]
    print(f"    {name}: {lines[-1] if lines else ''}")
    c.check_true(f"{name}: exit 2 with one line naming the entry", code == 2 and len(lines) == 1 and
                 all(w in lines[0] for w in words))

# Sizes and numbers out of reach: a subnormal or overflowing number in any
# entry, a mesh or a bar too large for the machine, a list of names too
# long to declare; each refused before anything is allocated.
many = ", ".join(f"b{i}" for i in range(2000))
for name, text, words in (
        ("subnormal", block.format(mesh="", nu="0.3", extra="").replace("0.01", "1e-308"),
         ["Density", "1e-308", "smallest normal"]),
        ("overflow", block.format(mesh="", nu="0.3", extra="").replace("0.01", "1e400"),
         ["Density", "1e400", "largest double"]),
        ("huge_mesh", block.format(mesh="", nu="0.3", extra="").replace("Subdivisions = 2, 2, 2",
                                                                        "Subdivisions = 2000000000, 2, 2"),
         ["Subdivisions", "elements", "GiB"]),
        ("many_names", block.format(mesh="", nu="0.3", extra="").replace("set Bodies = block",
                                                                         "set Bodies = block, " + many),
         ["Bodies", "2001", "at most 1000"])):
    prm = write_scene(os.path.join(args.work_dir, name + ".prm"), text=text)
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
    lines = [l for l in err.splitlines() if l.strip()]
    print(f"    {name}: {lines[-1] if lines else ''}")
    c.check_true(f"{name}: exit 2 with one line naming {words}", code == 2 and len(lines) == 1 and
                 all(w in lines[0] for w in words))

# A penalty factor out of all proportion stops at the first step instead of
# taking the step to zero; the options may follow the scene file.
rod = os.path.join(args.source_dir, "prm", "elastic_rod_impact", "elastic_rod_impact.prm")
r = subprocess.run([args.anvil, rod, "--set", "Contact pair impact/Penalty scale factor=1e308",
                    "--set", "Simulation/Output directory=" + os.path.join(args.work_dir, "output", "stiff")],
                   cwd=args.work_dir, capture_output=True, text=True, timeout=120)
lines = [l for l in r.stderr.splitlines() if l.strip()]
print(f"    stiff penalty: {lines[-1] if lines else ''}")
c.check_true("penalty factor 1e308: exit 3 at step 0 with one line naming the entry",
             r.returncode == 3 and len(lines) == 1 and "step 0" in lines[0] and
             "Penalty scale factor" in lines[0])
r = subprocess.run([args.anvil, os.path.join(args.work_dir, "unknown_body.prm"), "--check"],
                   cwd=args.work_dir, capture_output=True, text=True, timeout=120)
code, err = r.returncode, r.stderr
c.check_true("'anvil SCENE.prm --check' reads the options after the file", code == 2 and "blok" in err, err.strip())
# A malformed line continued over many lines (a stage's changes): one
# error line of at most 600 characters, the quoted line shortened.
prm = write_scene(os.path.join(args.work_dir, "long_line.prm"),
                  text=block.format(mesh="", nu="0.3", extra="") +
                  "subsection Simulation\n  0.5 Simulation/Mass damping=0; \\\n" +
                  "".join(f"    Simulation/End time={k}; \\\n" for k in range(60)) + "    Simulation/Plots=false\nend\n")
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir, extra_args=["--check"])
lines = [l for l in err.splitlines() if l.strip()]
c.check_true("a malformed line of 2,000 characters: exit 2, one line of at most 600 characters naming it",
             code == 2 and len(lines) == 1 and len(lines[0]) <= 600 and "long_line.prm" in lines[0] and
             "could not be parsed" in lines[0], f"{len(lines[0]) if lines else 0} characters: "
             f"{lines[0][:200] if lines else ''}")
# Several scenes checked in one call: the bad one's line, the good one still
# checked, the exit status of the one that failed; a run takes one scene.
r = subprocess.run([args.anvil, "--check", os.path.join(args.work_dir, "unknown_body.prm"), rod],
                   cwd=args.work_dir, capture_output=True, text=True, timeout=120)
c.check_true("'anvil --check BAD.prm GOOD.prm': exit 2, an error line for BAD, GOOD valid",
             r.returncode == 2 and "blok" in r.stderr and (rod + ": scene ") in r.stdout, r.stderr.strip())
r = subprocess.run([args.anvil, rod, rod], cwd=args.work_dir, capture_output=True, text=True, timeout=60)
lines = [l for l in r.stderr.splitlines() if l.strip()]
c.check_true("two scenes to run: exit 2 with one line", r.returncode == 2 and len(lines) == 1 and
             "only --check takes several" in lines[0], r.stderr)
for name, argv in (("unknown option", ["--frobnicate", "x.prm"]), ("no scene file", [])):
    r = subprocess.run([args.anvil, *argv], cwd=args.work_dir, capture_output=True, text=True, timeout=60)
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    print(f"    {name}: {lines[-1] if lines else ''}")
    c.check_true(f"{name}: exit 2 with one line", r.returncode == 2 and len(lines) == 1 and
                 lines[0].startswith("anvil: error:"), r.stderr)
r = subprocess.run([args.anvil, "--version"], capture_output=True, text=True)
c.check_true("--version prints one line", r.returncode == 0 and r.stdout.startswith("anvil ") and
             "deal.II" in r.stdout, r.stdout + r.stderr)

# Includes: a scene that includes itself through another file, and an
# include that names no file; resolved relative to the including file, so
# a scene in another folder includes its neighbour by its bare name.
os.makedirs(os.path.join(args.work_dir, "includes"), exist_ok=True)
write_scene(os.path.join(args.work_dir, "includes", "a.prm"), text="include b.prm\n")
write_scene(os.path.join(args.work_dir, "includes", "b.prm"), text="include a.prm\n")
write_scene(os.path.join(args.work_dir, "includes", "missing.prm"), text="include no_such_scene.prm\n")
write_scene(os.path.join(args.work_dir, "includes", "base.prm"), text=block.format(mesh="", nu="0.3", extra=""))
write_scene(os.path.join(args.work_dir, "includes", "variant.prm"), text="include base.prm\n")
for name, words in (("a", ["includes itself"]), ("missing", ["no_such_scene.prm", "does not exist"])):
    code, out, err = run_anvil(args.anvil, os.path.join("includes", name + ".prm"), cwd=args.work_dir,
                               extra_args=["--check"])
    lines = [l for l in err.splitlines() if l.strip()]
    print(f"    include {name}: {lines[-1] if lines else ''}")
    c.check_true(f"include {name}: exit 2 with one line", code == 2 and len(lines) == 1 and
                 all(w in lines[0] for w in words))
code, out, err = run_anvil(args.anvil, os.path.join("includes", "variant.prm"), cwd=args.work_dir,
                           extra_args=["--check"])
c.check_true("an include relative to the including file, run from another folder", code == 0, err.strip())

# Inverted element during the run: one face driven into the block at 60 m/s
# (half the wave speed), for long enough to turn elements inside out.
prm = write_scene(os.path.join(args.work_dir, "inverted.prm"),
                  text=block.format(mesh="", nu="0.3", extra="") + """
set Boundary conditions = fixed, ram
subsection Boundary condition fixed
  set Body = block
  set Boundary ids = 0
end
subsection Boundary condition ram
  set Body = block
  set Boundary ids = 1
  set Type = velocity
  set Velocity = -60, 0, 0
end
subsection Simulation
  set Energy balance tolerance = 1000
end
""")
code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
lines = [l for l in err.splitlines() if l.strip()]
print(f"    inverted: {lines[-1] if lines else ''}")
c.check_true("inverted element: exit status 3", code == 3, f"got {code}")
c.check_true("inverted element: one line naming time, step, element, position",
             len(lines) == 1 and all(w in lines[0] for w in ("inverted", "t =", "step", "element", "near (")))

# Results of an earlier run are kept.
ok_scene = block.format(mesh="", nu="0.3", extra="")
prm = write_scene(os.path.join(args.work_dir, "twice.prm"), text=ok_scene)
code1, _, err1 = run_anvil(args.anvil, prm, cwd=args.work_dir)
energy = os.path.join(args.work_dir, "output/twice/energy.csv")
before = open(energy).read() if os.path.exists(energy) else None
code2, _, err2 = run_anvil(args.anvil, prm, cwd=args.work_dir)
lines = [l for l in err2.splitlines() if l.strip()]
print(f"    second run: {lines[-1] if lines else ''}")
c.check_true("first run succeeds", code1 == 0, err1.strip())
c.check_true("second run into the same directory: exit 2, one line naming the setting",
             code2 == 2 and len(lines) == 1 and "Overwrite existing output" in lines[0])
c.check_true("earlier results unchanged", before is not None and open(energy).read() == before)

# More processes than elements: one line on stderr and exit 2 (it was
# deal.II's "dummy cell" from the process left without an element).
prm = write_scene(os.path.join(args.work_dir, "few_elements.prm"),
                  text=ok_scene.replace("Subdivisions = 2, 2, 2", "Subdivisions = 1, 1, 1"))
code, out, err = run_anvil(args.anvil, prm, np=2, cwd=args.work_dir)
lines = [l for l in err.splitlines() if l.startswith("anvil:")]
print(f"    one element on two processes: {lines[-1] if lines else ''}")
c.check_true("one element on two processes: exit 2, one line naming the element and process counts",
             code == 2 and len(lines) == 1 and "1 element(s), fewer than the 2 MPI processes" in lines[0],
             err.strip()[-300:])
c.finish()
