"""Decks as users bring them: a small LS-DYNA keyword deck in every field
style, and a small whole ABAQUS deck, each give the run of the equivalent
Anvil scene, bit for bit.

The model: a steel striker (2 x 2 x 3 one-point hexahedra, bilinear
plastic with Cowper-Symonds rate effects) at 50 m/s onto a concrete-like
elastic block (2 x 2 x 2) held at its base, a quarter model with symmetry
planes x = 0 and y = 0, penalty contact with friction between them. The
test writes it
- as keyword decks: fixed columns with the values run together (8-digit
  labels, 16-character reals written without the E, '2.65625000000-01'),
  free format with commas in lower case with '_TITLE' options and the
  mesh in an *INCLUDE file, and long format (*KEYWORD LONG=Y, 20-column
  fields, the two-card element format);
- as a flat ABAQUS deck (*Material with a two-row *Plastic and *Rate
  Dependent power law, *Initial Conditions, *Boundary with symmetry
  names, general contact with *Friction, *Dynamic, Explicit);
- as the two equivalent scenes, on the same mesh written as an ABAQUS .inp
  mesh file.
The striker also as *MAT_PIECEWISE_LINEAR_PLASTICITY (MAT_024), its curve
on a *DEFINE_CURVE and as EPS-ES pairs, against the scene with
'piecewise linear plasticity'; the ABAQUS deck's *Plastic table is read as
that model with the yield stress constant beyond the table.
Checked: every deck's energy history equals its scene's, character for
character; the scene that 'anvil --translate' prints runs the same; a deck
run on two processes writes the probe history of one process (a probe
added with --set); the energy balance below 1 %; each unsupported keyword
or option gives exactly one error line naming it and exit 2.
"""
import os
from anvil_test import Checker, arguments, run_anvil, together

args = arguments()
c = Checker("keyword and ABAQUS decks run as their equivalent scenes")
w = args.work_dir

# The mesh: exact binary coordinates, so that every way of writing them
# reads back the same doubles.
h = 0.125


def block(n, origin, first_node, first_element, pid):
    nodes, elements = [], []
    nid = lambda i, j, k: first_node + i + (n[0] + 1) * (j + (n[1] + 1) * k)
    for k in range(n[2] + 1):
        for j in range(n[1] + 1):
            for i in range(n[0] + 1):
                nodes.append((nid(i, j, k), origin[0] + i * h, origin[1] + j * h, origin[2] + k * h))
    e = first_element
    for k in range(n[2]):
        for j in range(n[1]):
            for i in range(n[0]):
                elements.append((e, pid, [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                                          nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1),
                                          nid(i, j + 1, k + 1)]))
                e += 1
    return nodes, elements


block_nodes, block_elements = block((2, 2, 2), (0, 0, 0), 1, 1, 2)
striker_nodes, striker_elements = block((2, 2, 3), (0, 0, 0.25 + 1 / 1024), 100, 100, 1)
nodes = striker_nodes + block_nodes
elements = striker_elements + block_elements
nodes.sort()
elements.sort()
bottom = [n[0] for n in nodes if n[0] < 100 and n[3] == 0]
xzero = [n[0] for n in nodes if n[1] == 0]
yzero = [n[0] for n in nodes if n[2] == 0]

# The equivalent scenes' mesh file.
with open(os.path.join(w, "mesh.inp"), "w") as f:
    f.write("*NODE\n" + "".join(f"{n[0]}, {n[1]!r}, {n[2]!r}, {n[3]!r}\n" for n in nodes))
    for pid in (2, 1):  # in the order of their labels, as the decks have them
        f.write(f"*ELEMENT, TYPE=C3D8R, ELSET=PART{pid}\n")
        f.write("".join(f"{e[0]}, " + ", ".join(map(str, e[2])) + "\n" for e in elements if e[1] == pid))
    for name, ids in (("BOTTOM", bottom), ("XZERO", xzero), ("YZERO", yzero)):
        f.write(f"*NSET, NSET={name}\n" + "".join(f"{i},\n" for i in ids))

common_scene = """
subsection Simulation
  set End time = 0.0002
  set Time step safety factor = 0.8
  set Output interval = 0.0001
  set History interval = 1e-05
  set Print wall times = false
end
"""


def body(name, region, velocity, hourglass, quadratic, material):
    return f"""
subsection Body {name}
  subsection Mesh
    set Source = file
    set File name = mesh.inp
    set Region = {region}
  end
  set Initial velocity = {velocity}
  set Integration = one point
  subsection Hourglass control
    set Type = viscous
    set Coefficient = {hourglass}
  end
  subsection Bulk viscosity
    set Linear coefficient = 0.06
    set Quadratic coefficient = {quadratic}
  end
  subsection Material
{material}
  end
end
"""


def condition(name, body_, sets, components):
    return f"""
subsection Boundary condition {name}
  set Body = {body_}
  set Selection = node set
  set Node sets = {sets}
  set Components = {components}
end
"""


# Parameters of the model (the decks say the same in their own words).
steel = dict(ro=7850.0, e=2.1e11, pr=0.3, sigy=3.5e8, etan=1e9, src=40.0, srp=5.0)
concrete = dict(ro=2400.0, e=3e10, pr=0.2)

def steel_material(tangent, beta):
    """The striker's bilinear steel with Cowper-Symonds rate effects."""
    return f"""
    set Model = plastic kinematic
    subsection plastic kinematic
      set Density = {steel['ro']}
      set Young's modulus = {steel['e']}
      set Poisson's ratio = {steel['pr']}
      set Yield stress = {steel['sigy']}
      set Tangent modulus = {tangent!r}
      set Hardening parameter beta = {beta}
      set Cowper-Symonds C = 40
      set Cowper-Symonds p = 5
      set Strain rate effects = Cowper-Symonds
    end"""


def tabulated_material(beyond):
    """The striker's steel as a flow curve (the ABAQUS deck's *Plastic
    table, constant beyond it; LS-DYNA's *MAT_024, continued)."""
    return f"""
    set Model = piecewise linear plasticity
    subsection piecewise linear plasticity
      set Density = {steel['ro']}
      set Young's modulus = {steel['e']}
      set Poisson's ratio = {steel['pr']}
      set Flow curve = 0:3.5e+08, 0.5:3.6e+08
      set Beyond the curve = {beyond}
      set Cowper-Symonds C = 40
      set Cowper-Symonds p = 5
    end"""


def concrete_material():
    """The block's elastic material."""
    return f"""
    set Model = elastic
    subsection elastic
      set Density = {concrete['ro']}
      set Young's modulus = {concrete['e']}
      set Poisson's ratio = {concrete['pr']}
    end"""


lsdyna_scene = ("set Bodies = striker, block\n"
                "set Boundary conditions = b1, b2, b3, b4, b5\n"
                "set Contact pairs = pair\n" + common_scene +
                body("striker", "PART1", "0, 0, -50", 0.05, 1.5, steel_material(steel["etan"], 0)) +
                body("block", "PART2", "0, 0, 0", 0.1, 1.5, concrete_material()) +
                condition("b1", "block", "BOTTOM", "x, y, z") + condition("b2", "striker", "XZERO", "x") +
                condition("b3", "block", "XZERO", "x") + condition("b4", "striker", "YZERO", "y") +
                condition("b5", "block", "YZERO", "y") + """
subsection Contact pair pair
  set Algorithm = penalty
  set First body = block
  set Second body = striker
  set Penalty scale factor = 0.1
  set Static friction coefficient = 0.2
  set Dynamic friction coefficient = 0.1
end
""")


# @sect{The keyword decks}
def fortran(x):
    """16 characters, no blank, no E: '2.65625000000-01'."""
    m, e = f"{x:.11e}".split("e")
    return f"{m}{int(e):+03d}"


def keyword_deck(style):
    """The model as a keyword deck in one field style; returns {file: text}."""
    big = 10000000 if style == "fixed" else 0  # 8-digit labels run together
    L = style == "long"
    W = 20 if L else 10

    def card(*values, widths=None):
        if style == "free":
            return ",".join(str(v) for v in values) + "\n"
        widths = widths or [W] * len(values)

        def fit(v, wd):
            # A real too long for its field as LS-DYNA users write it:
            # no E ('1.0+9'), as long as it reads back the same.
            t = str(v)
            if isinstance(v, float) and len(t) > wd:
                m, e = f"{v:.6e}".split("e")
                t = f"{m.rstrip('0')}{int(e):+d}"
                assert float(m) * 10 ** int(e) == v and len(t) <= wd, t
            return t.rjust(wd)
        return "".join(fit(v, wd) for v, wd in zip(values, widths)) + "\n"

    k = (lambda s: s.lower()) if style == "free" else (lambda s: s)
    mesh = k("*NODE") + "\n"
    for n in nodes:
        tc = 1 if n[1] == 0 else 0
        if style == "fixed":
            mesh += f"{n[0] + big:8d}" + "".join(fortran(x) for x in n[1:]) + f"{tc:8d}{0:8d}\n"
        else:
            mesh += card(n[0], repr(n[1]), repr(n[2]), repr(n[3]), tc, 0,
                         widths=[20] * 6 if L else [8, 16, 16, 16, 8, 8])
    mesh += k("*ELEMENT_SOLID") + "\n"
    for e in elements:
        if L:
            mesh += card(e[0], e[1]) + card(*e[2], widths=[20] * 8)
        else:
            mesh += card(e[0] + big, e[1], *[i + big for i in e[2]], widths=[8] * 10)
    mesh += k("*SET_NODE_LIST") + "\n" + card(7)
    for i in range(0, len(bottom), 8):
        mesh += card(*[b + big for b in bottom[i:i + 8]])
    mesh += k("*BOUNDARY_SPC_NODE") + "\n"
    for i in yzero:
        mesh += card(i + big, 0, 0, 1, 0, 0, 0, 0)

    title = "_TITLE" if style == "free" else ""
    deck = "*KEYWORD" + (" LONG=Y" if L else "") + "\n$ a striker on a block\n"
    deck += k("*TITLE") + "\nstriker on block\n"
    deck += k("*CONTROL_TERMINATION") + "\n" + card("2.0-4" if style == "fixed" else "0.0002")
    deck += k("*CONTROL_TIMESTEP") + "\n" + card(0, 0.8)
    deck += k("*CONTROL_BULK_VISCOSITY") + "\n" + card(1.5, 0.06, 1)
    deck += k("*CONTROL_HOURGLASS") + "\n" + card(1, 0.1)
    deck += k("*DATABASE_BINARY_D3PLOT") + "\n" + card("1.0-4" if style == "fixed" else "1e-4")
    deck += k("*DATABASE_GLSTAT") + "\n" + card("1.0-5" if style == "fixed" else "1e-5")
    deck += k("*DATABASE_MATSUM") + "\n" + card("1.0-5")
    deck += k("*PART") + "\nstriker\n" + card(1, 1, 1, 0, 1) + "block\n" + card(2, 1, 2, 0, 0)
    deck += k("*SECTION_SOLID" + title) + "\n" + ("solid\n" if title else "") + card(1, 1)
    deck += k("*HOURGLASS") + "\n" + card(1, 1, 0.05)
    deck += k("*MAT_PLASTIC_KINEMATIC" + title) + "\n" + ("steel\n" if title else "")
    deck += card(1, steel["ro"], "2.1+11" if style == "fixed" else steel["e"], steel["pr"], steel["sigy"],
                 steel["etan"], 0.0) + card(steel["src"], steel["srp"], 0.0, 1.0)
    deck += k("*MAT_ELASTIC") + "\n" + card(2, concrete["ro"], concrete["e"], concrete["pr"])
    deck += k("*INITIAL_VELOCITY_GENERATION") + "\n" + card(1, 2, 0.0, 0.0, 0.0, -50.0) + "\n"
    deck += k("*BOUNDARY_SPC_SET") + "\n" + card(7, 0, 1, 1, 1, 0, 0, 0)
    deck += (k("*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE") + "\n" + card(1, 2, 3, 3) +
             card(0.2, 0.1, 0.0, 0.0, 0.0) + card(1.0, 1.0))
    files = {}
    if style == "free":
        files["deck_free_mesh.k"] = "*KEYWORD\n" + mesh + "*END\n"
        deck += k("*INCLUDE") + "\ndeck_free_mesh.k\n"
    else:
        deck += mesh
    files[f"deck_{style}.k"] = deck + "*END\n"
    return files


def energy(name):
    with open(os.path.join(w, "output", name, "energy.csv")) as f:
        return f.read()


with open(os.path.join(w, "lsdyna_scene.prm"), "w") as f:
    f.write(lsdyna_scene)
styles = ("fixed", "free", "long")
for style in styles:
    for name, text in keyword_deck(style).items():
        with open(os.path.join(w, name), "w") as f:
            f.write(text)
# (The scene and the three decks two at a time, one a core.)
runs = together(*[lambda file=file: run_anvil(args.anvil, file, cwd=w, extra_args=(
    () if file.endswith(".prm") else ("--set", "Simulation/Print wall times=false")))
    for file in ["lsdyna_scene.prm"] + [f"deck_{style}.k" for style in styles]], at_once=2)
code, out, err = runs[0]
if not c.check_true("the equivalent scene runs", code == 0, err.strip()[-300:]):
    c.finish()
reference = energy("lsdyna_scene")
balance = max(abs(float(r.split(",")[-1])) for r in reference.splitlines()[1:])
c.check_below("the scene's largest energy balance error", balance, 0.01)

for style, (code, out, err) in zip(styles, runs[1:]):
    if not c.check_true(f"{style} format: anvil deck_{style}.k exits 0", code == 0, err.strip()[-300:]):
        continue
    c.check_true(f"{style} format: the energy history equals the scene's, character for character",
                 energy(f"deck_{style}") == reference)
    c.check_true(f"{style} format: the warning lists what is only output (*DATABASE_MATSUM)",
                 "*DATABASE_MATSUM" in out)

# *CONTACT_ERODING_SURFACE_TO_SURFACE (its fourth card ISYM EROSOP IADJ):
# Anvil's pairs take in the faces eroded elements expose in any case, so
# the deck runs the scene (no element erodes here).
free_deck = keyword_deck("free")["deck_free.k"]
old_contact = "*contact_automatic_surface_to_surface\n1,2,3,3\n0.2,0.1,0.0,0.0,0.0\n1.0,1.0\n"
assert old_contact in free_deck
with open(os.path.join(w, "eroding.k"), "w") as f:
    f.write(free_deck.replace(old_contact, old_contact.replace("automatic", "eroding") + "0,1,1\n"))
code, out, err = run_anvil(args.anvil, "eroding.k", cwd=w, extra_args=("--set", "Simulation/Print wall times=false"))
c.check_true("*CONTACT_ERODING_SURFACE_TO_SURFACE: the energy history equals the scene's, character for character",
             code == 0 and energy("eroding") == reference, err.strip()[-300:])

# *INITIAL_VELOCITY_NODE (a card a node, as LS-PrePost writes it): the
# striker's nodes at its velocity run the scene; a node left out, or given
# another velocity, is refused (Anvil gives velocities to whole parts).
generation = "*initial_velocity_generation\n1,2,0.0,0.0,0.0,-50.0\n\n"
assert generation in free_deck
striker_ids = sorted({i for e in elements if e[1] == 1 for i in e[2]})
node_cards = {
    "the striker's nodes": [f"{n},0.0,0.0,-50.0\n" for n in striker_ids],
    "a node left out": [f"{n},0.0,0.0,-50.0\n" for n in striker_ids[1:]],
    "a node at another velocity": [f"{n},0.0,0.0,{-49.0 if i == 3 else -50.0}\n" for i, n in enumerate(striker_ids)],
}
for what, cards in node_cards.items():
    with open(os.path.join(w, "node_velocity.k"), "w") as f:
        f.write(free_deck.replace(generation, "*initial_velocity_node\n" + "".join(cards)))
    code, out, err = run_anvil(args.anvil, "node_velocity.k", cwd=w,
                               extra_args=("--set", "Simulation/Print wall times=false"))
    if what == "the striker's nodes":
        c.check_true(f"*INITIAL_VELOCITY_NODE, {what}: the energy history equals the scene's, character for character",
                     code == 0 and energy("node_velocity") == reference, err.strip()[-300:])
    else:
        lines = err.strip().splitlines()
        c.check_true(f"*INITIAL_VELOCITY_NODE, {what}: exit 2 and one line naming the keyword and the part",
                     code == 2 and len(lines) == 1 and "INITIAL_VELOCITY_NODE" in lines[0] and "part 1" in lines[0],
                     err.strip()[:300])

# The translation as a scene of its own.
code, out, err = run_anvil(args.anvil, "deck_fixed.k", cwd=w, extra_args=("--translate",))
with open(os.path.join(w, "translated.prm"), "w") as f:
    f.write(out + "subsection Simulation\n  set Print wall times = false\nend\n")
code, out, err = run_anvil(args.anvil, "translated.prm", cwd=w)
c.check_true("'anvil --translate deck_fixed.k' prints a scene that runs the same", code == 0 and
             energy("translated") == reference, err.strip()[-300:])

# Two processes: a probe added to the deck's scene with --set.
probe = ("--set", "Probes=tip", "--set", "Probe tip/Point=0.25, 0.25, 0.2509765625", "--set", "Probe tip/Body=striker",
         "--set", "Simulation/Print wall times=false")
histories = []
for np_ in (1, 2):
    os.makedirs(os.path.join(w, f"np{np_}"), exist_ok=True)
    code, out, err = run_anvil(args.anvil, os.path.join(w, "deck_fixed.k"), np=np_, cwd=os.path.join(w, f"np{np_}"),
                               extra_args=probe)
    c.check_true(f"np = {np_}: the deck runs with a probe added by --set", code == 0, err.strip()[-300:])
    path = os.path.join(w, f"np{np_}", "output", "deck_fixed", "probe_tip.csv")
    histories.append(open(path).read() if os.path.exists(path) else None)
c.check_true("np = 2 writes the probe history of np = 1 (bitwise)", histories[0] is not None and
             histories[0] == histories[1])

# @sect{*MAT_PIECEWISE_LINEAR_PLASTICITY}
# The striker of the free-format deck as MAT_024 with its flow curve on a
# *DEFINE_CURVE (LCSS) and as EPS-ES pairs: both run the equivalent scene
# with 'piecewise linear plasticity', character for character; SIGY and
# ETAN alone give the bilinear curve (E ETAN / (E - ETAN) its slope).
free = keyword_deck("free")
start = free["deck_free.k"].index("*mat_plastic_kinematic_title")
end = free["deck_free.k"].index("*mat_elastic")
mat024 = {
    "lcss": "*MAT_PIECEWISE_LINEAR_PLASTICITY_TITLE\nsteel\n1,7850.0,2.1e11,0.3,3.5e8,0.0,0.0,0.0\n"
            "40.0,5.0,10,0,1.0\n*DEFINE_CURVE_TITLE\nflow\n10\n0.0,3.5e8\n0.5,3.6e8\n",
    "pairs": "*MAT_024\n1,7850.0,2.1e11,0.3,0.0,0.0,0.0,0.0\n40.0,5.0,0,0,1.0\n0.0,0.5\n3.5e8,3.6e8\n",
    "etan": "*MAT_024\n1,7850.0,2.1e11,0.3,3.5e8,1e9,0.0,0.0\n40.0,5.0,0,0,0.0\n",
}
with open(os.path.join(w, "mat024_scene.prm"), "w") as f:
    f.write(lsdyna_scene.replace(steel_material(steel["etan"], 0), tabulated_material("extrapolate")))
code, out, err = run_anvil(args.anvil, "mat024_scene.prm", cwd=w)
c.check_true("the MAT_024 equivalent scene runs", code == 0, err.strip()[-300:])
for form, card in mat024.items():
    with open(os.path.join(w, f"mat024_{form}.k"), "w") as f:
        f.write(free["deck_free.k"][:start] + card + free["deck_free.k"][end:])
    code, out, err = run_anvil(args.anvil, f"mat024_{form}.k", cwd=w, extra_args=("--translate",))
    if form == "etan":
        eh = 2.1e11 * 1e9 / (2.1e11 - 1e9)
        c.check_true(f"*MAT_024 with SIGY and ETAN: the curve 0:SIGY, 1:SIGY + E ETAN / (E - ETAN) "
                     f"({3.5e8 + eh:.6g}), continued; VP = 0 listed as a difference",
                     code == 0 and "set Model = piecewise linear plasticity" in out and
                     f"set Flow curve = 0:3.5e+08, 1:{3.5e8 + eh!r}" in out and "VP = 0" in out,
                     out[-600:] + err.strip()[-300:])
        continue
    code, out, err = run_anvil(args.anvil, f"mat024_{form}.k", cwd=w,
                               extra_args=("--set", "Simulation/Print wall times=false"))
    if c.check_true(f"*MAT_024 ({form}): the deck runs", code == 0, err.strip()[-300:]):
        c.check_true(f"*MAT_024 ({form}): the energy history equals the scene's, character for character",
                     energy(f"mat024_{form}") == energy("mat024_scene"))

# *MAT_ADD_EROSION: EFFEPS is the same failure strain as MAT_024's FAIL
# (criteria equal to EXCL are bypassed); another criterion, or the keyword
# on an elastic material, is refused.
lcss_deck = open(os.path.join(w, "mat024_lcss.k")).read()
fail_card = "1,7850.0,2.1e11,0.3,3.5e8,0.0,0.0,0.0\n"
assert fail_card in lcss_deck
with open(os.path.join(w, "fail.k"), "w") as f:
    f.write(lcss_deck.replace(fail_card, "1,7850.0,2.1e11,0.3,3.5e8,0.0,0.02,0.0\n"))
add = "*MAT_ADD_EROSION\n1,1234,1234,1234,0.02,1234,1,1\n1234,1234,1234,1234,1234,1234,1234,1234\n"
with open(os.path.join(w, "add_erosion.k"), "w") as f:
    f.write(lcss_deck.replace("*DEFINE_CURVE_TITLE", add + "*DEFINE_CURVE_TITLE"))
runs = {}
for name in ("fail", "add_erosion"):
    code, out, err = run_anvil(args.anvil, f"{name}.k", cwd=w, extra_args=("--set", "Simulation/Print wall times=false"))
    runs[name] = (code, out, err)
code, out, err = run_anvil(args.anvil, "add_erosion.k", cwd=w, extra_args=("--translate",))
c.check_true("*MAT_ADD_EROSION EFFEPS 0.02 (EXCL 1234): 'Failure strain = 0.02', and the run of MAT_024 FAIL = "
             "0.02, character for character", all(r[0] == 0 for r in runs.values()) and
             energy("fail") == energy("add_erosion") and "set Failure strain = 0.02" in out,
             (runs["fail"][2] + runs["add_erosion"][2] + err).strip()[-300:])
for what, deck in (("MXEPS", lcss_deck.replace("*DEFINE_CURVE_TITLE", "*MAT_ADD_EROSION\n1,0,0,0,0.02\n0,0,0,0.3\n"
                                               "*DEFINE_CURVE_TITLE")),
                   ("on *MAT_ELASTIC", lcss_deck.replace("*DEFINE_CURVE_TITLE", "*MAT_ADD_EROSION\n2,0,0,0,0.02\n"
                                                         "*DEFINE_CURVE_TITLE"))):
    with open(os.path.join(w, "bad_add.k"), "w") as f:
        f.write(deck)
    code, out, err = run_anvil(args.anvil, "bad_add.k", cwd=w, extra_args=("--check",))
    c.check_true(f"*MAT_ADD_EROSION {what}: exit 2 and one line naming it", code == 2 and
                 len(err.strip().splitlines()) == 1 and "MAT_ADD_EROSION" in err, err.strip()[:300])
# *CONTROL_SHELL, _SOLID, _ACCURACY change nothing for a deck of hexahedra:
# listed in the warning, the run unchanged.
with open(os.path.join(w, "controls.k"), "w") as f:
    f.write(free_deck.replace("*include", "*control_accuracy\n1,4\n*control_solid\n1\n*control_shell\n20.0\n*include"))
code, out, err = run_anvil(args.anvil, "controls.k", cwd=w, extra_args=("--set", "Simulation/Print wall times=false"))
c.check_true("*CONTROL_ACCURACY, _SOLID, _SHELL: listed in the warning, the scene's run", code == 0 and
             energy("controls") == reference and all(k in out for k in ("*CONTROL_ACCURACY", "*CONTROL_SOLID",
                                                                        "*CONTROL_SHELL")), err.strip()[-300:])

with open(os.path.join(w, "bad_lcss.k"), "w") as f:
    f.write(open(os.path.join(w, "mat024_lcss.k")).read().replace("40.0,5.0,10,", "40.0,5.0,11,"))
code, out, err = run_anvil(args.anvil, "bad_lcss.k", cwd=w, extra_args=("--check",))
c.check_true("*MAT_024 whose LCSS names no curve: exit 2 and one line", code == 2 and
             len(err.strip().splitlines()) == 1 and "LCSS 11" in err, err.strip()[:300])

# @sect{A whole ABAQUS deck}
Et = steel["e"] * ((3.6e8 - 3.5e8) / 0.5) / (steel["e"] + (3.6e8 - 3.5e8) / 0.5)
abaqus_scene = ("set Bodies = striker, block\n"
                "set Boundary conditions = bc1_bottom, bc2_xzero, bc3_xzero, bc4_yzero, bc5_yzero\n"
                "set Contact pairs = pair\n" + common_scene.replace("set Time step safety factor = 0.8\n", "") +
                body("striker", "PART1", "0, 0, -50", 0.1, 1.2, tabulated_material("constant")) +
                body("block", "PART2", "0, 0, 0", 0.1, 1.2, concrete_material()) +
                condition("bc1_bottom", "block", "BOTTOM", "x, y, z") +
                condition("bc2_xzero", "striker", "XZERO", "x") + condition("bc3_xzero", "block", "XZERO", "x") +
                condition("bc4_yzero", "striker", "YZERO", "y") + condition("bc5_yzero", "block", "YZERO", "y") + """
subsection Contact pair pair
  set Algorithm = penalty
  set First body = striker
  set Second body = block
  set Static friction coefficient = 0.2
  set Dynamic friction coefficient = 0.2
end
""")
with open(os.path.join(w, "abaqus_scene.prm"), "w") as f:
    f.write(abaqus_scene)
mesh_text = open(os.path.join(w, "mesh.inp")).read()
striker_list = "\n".join(", ".join(str(n[0]) for n in striker_nodes[i:i + 8]) for i in range(0, len(striker_nodes), 8))
with open(os.path.join(w, "deck.inp"), "w") as f:
    f.write(f"""*Heading
a striker on a block
** the mesh, with the sets
*Include, input=mesh.inp
*Solid Section, elset=PART1, material=STEEL
,
*solid section, ELSET=part2, material=Concrete
,
*Material, name=Steel
*Density
{steel['ro']},
*Elastic
{steel['e']}, {steel['pr']}
*Plastic
3.5e8, 0.
3.6e8, 0.5
*Rate Dependent, type=POWER LAW
40., 5.
*Material, name=Concrete
*Density
{concrete['ro']},
*Elastic
{concrete['e']}, {concrete['pr']}
*Surface Interaction, name=rough
*Friction
0.2,
*Initial Conditions, type=VELOCITY
PART1_NODES, 3, -50.
*Nset, nset=PART1_NODES
{striker_list}
*Step, name=impact, nlgeom=YES
*Dynamic, Explicit
, 0.0002
*Bulk Viscosity
0.06, 1.2
*Boundary
BOTTOM, ENCASTRE
XZERO, XSYMM
YZERO, 2, 2
*Contact
*Contact Inclusions, ALL EXTERIOR
*Contact Property Assignment
 ,  , rough
*Output, field, time interval=0.0001
*Node Output
U,
*Output, history, time interval=1e-05
*Energy Output
ALLKE,
*End Step
""")
code, out, err = run_anvil(args.anvil, "abaqus_scene.prm", cwd=w)
c.check_true("the ABAQUS deck's equivalent scene runs", code == 0, err.strip()[-300:])
code2, out2, err2 = run_anvil(args.anvil, "deck.inp", cwd=w, extra_args=("--set", "Simulation/Print wall times=false"))
c.check_true("anvil deck.inp exits 0", code2 == 0, err2.strip()[-300:])
if code == 0 and code2 == 0:
    c.check_true("the ABAQUS deck's energy history equals its scene's, character for character",
                 energy("deck") == energy("abaqus_scene"))

# The striker as an ABAQUS rigid body: its reference node carries the
# initial velocity and holds the sideways motion and the rotations.
rigid = open(os.path.join(w, "deck.inp")).read()
rigid = rigid.replace("*Solid Section, elset=PART1, material=STEEL",
                      "*Node\n999, 0.125, 0.125, 0.5\n*Nset, nset=RP\n999,\n"
                      "*Rigid Body, ref node=RP, elset=PART1\n*Solid Section, elset=PART1, material=STEEL")
rigid = rigid.replace("PART1_NODES, 3, -50.", "RP, 3, -50.").replace("*Boundary\n", "*Boundary\nRP, 1, 2\nRP, 4, 6\n")
with open(os.path.join(w, "rigid.inp"), "w") as f:
    f.write(rigid)
code, out, err = run_anvil(args.anvil, "rigid.inp", cwd=w, extra_args=("--translate",))
c.check_true("ABAQUS *Rigid Body: a free rigid body, its velocity and constraints from the reference node",
             code == 0 and "set Model = rigid" in out and "set Motion = free" in out and
             "set Initial velocity = 0, 0, -50" in out and "rx, ry, rz" in out, err.strip()[-300:])
code, out, err = run_anvil(args.anvil, "rigid.inp", cwd=w, extra_args=("--set", "Simulation/Print wall times=false"))
if c.check_true("anvil rigid.inp exits 0", code == 0, err.strip()[-300:]):
    rows = energy("rigid").splitlines()[1:]
    c.check_below("rigid.inp: largest energy balance error", max(abs(float(r.split(",")[-1])) for r in rows), 0.01)
    c.check_true("rigid.inp: no warning of keywords the mesh reader skipped", "skipped" not in out)

# Gravity: LS-DYNA's base acceleration (*LOAD_BODY_Z, 9.81 on a constant
# curve, pulls towards -z) and ABAQUS's *Dload GRAV.
g_deck = keyword_deck("free")["deck_free.k"].replace(
    "*include", "*load_body_z\n1,1.0\n*define_curve\n1\n0.0,9.81\n1.0,9.81\n*include")
with open(os.path.join(w, "gravity.k"), "w") as f:
    f.write(g_deck)
code, out, err = run_anvil(args.anvil, "gravity.k", cwd=w, extra_args=("--translate",))
c.check_true("*LOAD_BODY_Z 9.81: 'Gravity = 0, 0, -9.81'", code == 0 and "set Gravity = 0, 0, -9.81" in out,
             err.strip()[-300:])
with open(os.path.join(w, "bad_gravity.k"), "w") as f:
    f.write(g_deck.replace("1.0,9.81\n*include", "1.0,0.0\n*include"))
code, out, err = run_anvil(args.anvil, "bad_gravity.k", cwd=w, extra_args=("--check",))
c.check_true("a gravity curve that is not constant: exit 2, one line", code == 2 and
             len(err.strip().splitlines()) == 1 and "not constant" in err, err.strip()[:300])
with open(os.path.join(w, "gravity.inp"), "w") as f:
    f.write(open(os.path.join(w, "deck.inp")).read().replace("*Bulk Viscosity", "*Dload\n, GRAV, 9.81, 0., 0., -2.\n*Bulk Viscosity"))
code, out, err = run_anvil(args.anvil, "gravity.inp", cwd=w, extra_args=("--translate",))
c.check_true("*Dload GRAV 9.81 towards (0, 0, -2): 'Gravity = 0, 0, -9.81'", code == 0 and
             "set Gravity = 0, 0, -9.81" in out, err.strip()[-300:])

# *MAT_JOHNSON_COOK's VP: 0 (the default) scales the yield stress by the
# total strain rate's factor, 1 is the viscoplastic form (the plastic
# strain rate, solved with the return): 'Rate form = total' / 'plastic'.
for vp, form in (("", "total"), ("0", "total"), ("1.0", "plastic")):
    jc = (f"*mat_johnson_cook\n2,{concrete['ro']},8.0e10,2.06e11,0.3,0.0,{vp},0\n"
          "806e6,614e6,0.168,0.0089,1.1,1540.0,20.0,1.0\n460.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0\n0.0,0.0,0.0\n")
    text = keyword_deck("free")["deck_free.k"]
    start = text.index("*mat_elastic")
    with open(os.path.join(w, "jc.k"), "w") as f:
        f.write(text[:start] + jc + text[text.index("*initial_velocity_generation"):])
    code, out, err = run_anvil(args.anvil, "jc.k", cwd=w, extra_args=("--translate",))
    c.check_true(f"*MAT_JOHNSON_COOK VP = '{vp}': 'Rate form = {form}'",
                 code == 0 and f"set Rate form = {form}" in out and "Model = johnson cook" in out,
                 (out + err).strip()[-300:])
code, out, err = run_anvil(args.anvil, "jc.k", cwd=w, extra_args=("--set", "Simulation/Print wall times=false"))
c.check_true("the deck with *MAT_JOHNSON_COOK runs", code == 0, err.strip()[-300:])

# LS-DYNA's SOFT = 1: the penalty from the nodal masses and the step.
with open(os.path.join(w, "soft.k"), "w") as f:
    f.write(keyword_deck("free")["deck_free.k"].replace("0.2,0.1,0.0,0.0,0.0\n1.0,1.0\n",
                                                        "0.2,0.1,0.0,0.0,0.0\n1.0,1.0\n1,0.2\n", 1))
code, out, err = run_anvil(args.anvil, "soft.k", cwd=w, extra_args=("--translate",))
c.check_true("SOFT = 1, SOFSCL = 0.2: 'Penalty stiffness = nodal mass', 'Mass penalty scale factor = 0.2'",
             code == 0 and "set Penalty stiffness = nodal mass" in out and "set Mass penalty scale factor = 0.2" in out,
             (out + err).strip()[-300:])

# @sect{What is not supported: one line, exit 2}
base = keyword_deck("free")
errors = {
    "an unsupported material": ("*mat_elastic\n", "*MAT_CONCRETE_DAMAGE_REL3\n", "MAT_CONCRETE_DAMAGE_REL3 is not supported"),
    "an unsupported element formulation": ("*section_solid_title\nsolid\n1,1\n", "*section_solid_title\nsolid\n1,10\n",
                                           "ELFORM"),
    "mass scaling": ("*control_timestep\n0,0.8\n", "*control_timestep\n0,0.8,0,0,-1e-6\n", "DT2MS"),
    "SOFT = 2 contact": ("0.2,0.1,0.0,0.0,0.0\n1.0,1.0\n", "0.2,0.1,0.0,0.0,0.0\n1.0,1.0\n2\n", "SOFT"),
    "a bad number": ("*control_termination\n0.0002\n", "*control_termination\n0.0.2\n", "is not a number"),
    "a missing include": ("deck_free_mesh.k\n", "no_such_mesh.k\n", "does not exist"),
}
for what, (old, new, expect) in errors.items():
    text = base["deck_free.k"]
    if what == "an unsupported material":
        text = text.replace("*mat_elastic\n", "*MAT_CONCRETE_DAMAGE_REL3\n")
    else:
        assert old in text, what
        text = text.replace(old, new, 1)
    name = "bad_" + what.replace(" ", "_").replace("=", "").replace("__", "_") + ".k"
    with open(os.path.join(w, name), "w") as f:
        f.write(text)
    code, out, err = run_anvil(args.anvil, name, cwd=w, extra_args=("--check",))
    lines = err.strip().splitlines()
    c.check_true(f"{what}: exit 2 and one line naming it", code == 2 and len(lines) == 1 and
                 lines[0].startswith("anvil: error:") and expect in lines[0], err.strip()[:300])

degenerate = base["deck_free_mesh.k"].replace("\n100,1,100,101,104,103,", "\n100,1,100,100,104,103,", 1)
with open(os.path.join(w, "deck_degenerate_mesh.k"), "w") as f:
    f.write(degenerate)
with open(os.path.join(w, "bad_degenerate.k"), "w") as f:
    f.write(base["deck_free.k"].replace("deck_free_mesh.k", "deck_degenerate_mesh.k"))
code, out, err = run_anvil(args.anvil, "bad_degenerate.k", cwd=w, extra_args=("--check",))
c.check_true("a degenerate hexahedron: exit 2 and one line", code == 2 and len(err.strip().splitlines()) == 1 and
             "8-node hexahedra only" in err, err.strip()[:300])

with open(os.path.join(w, "cases.k"), "w") as f:
    f.write("*CASE\n       101 LOW\n\n1\n" + base["deck_free.k"].replace("*KEYWORD\n", ""))
code, out, err = run_anvil(args.anvil, "cases.k", cwd=w, extra_args=("--check",))
c.check_true("a deck with *CASE and no --case: exit 2 and one line", code == 2 and "--case" in err and
             len(err.strip().splitlines()) == 1, err.strip()[:300])
code, out, err = run_anvil(args.anvil, "cases.k", cwd=w, extra_args=("--check", "--case", "101"))
c.check_true("... with --case 101 it is valid", code == 0, err.strip()[:300])

# @sect{Rigid walls: constraint or penalty (*CONTROL_CONTACT's RWPNAL)}
# A brick and a rigid brick beside it, both in the wall's node set.
WALL_DECK = """*KEYWORD
*CONTROL_TERMINATION
1.0e-4
{control}*PART
brick
1,1,1
*PART
block
2,1,2
*SECTION_SOLID
1,1
*MAT_ELASTIC
1,7850.0,2.1e11,0.3
*MAT_RIGID
2,7850.0,2.1e11,0.3
*SET_NODE_LIST
7
1,2,5,6,9,10
*RIGIDWALL_PLANAR
7,0,0,0.0,0.0,1.0e20,{rwksf}
0.0,-1.0,0.0,0.0,0.0,0.0,0.0
*NODE
1,0.0,0.0,0.0
2,0.1,0.0,0.0
3,0.1,0.1,0.0
4,0.0,0.1,0.0
5,0.0,0.0,0.1
6,0.1,0.0,0.1
7,0.1,0.1,0.1
8,0.0,0.1,0.1
9,0.2,0.0,0.0
10,0.2,0.0,0.1
11,0.2,0.1,0.0
12,0.2,0.1,0.1
*ELEMENT_SOLID
1,1,1,2,3,4,5,6,7,8
2,2,2,9,11,3,6,10,12,7
*END
"""
walls = {
    "RWPNAL = 0 (default)": ("", "1.0"),
    "RWPNAL = 0.5, RWKSF = 2": ("*CONTROL_CONTACT\n0.1,0.5\n", "2.0"),
}
for what, (control, rwksf) in walls.items():
    with open(os.path.join(w, "wall.k"), "w") as f:
        f.write(WALL_DECK.format(control=control, rwksf=rwksf))
    code, out, err = run_anvil(args.anvil, "wall.k", cwd=w, extra_args=("--translate",))
    pairs = [l.split()[-1] for l in out.splitlines() if l.startswith("subsection Contact pair")]
    if control:
        # The rigid block in the set: LS-DYNA's penalty would meet its nodes,
        # and Anvil has no contact between two rigid bodies.
        lines = err.strip().splitlines()
        c.check_true(f"{what}, a rigid part in the wall's set: exit 2 and one line naming it",
                     code == 2 and len(lines) == 1 and "RIGIDWALL_PLANAR" in lines[0] and "rigid part 2" in lines[0],
                     err.strip()[:300])
        with open(os.path.join(w, "wall.k"), "w") as f:
            f.write(WALL_DECK.format(control=control, rwksf=rwksf).replace("1,2,5,6,9,10", "1,4,5,8"))
        code, out, err = run_anvil(args.anvil, "wall.k", cwd=w, extra_args=("--translate",))
        pairs = [l.split()[-1] for l in out.splitlines() if l.startswith("subsection Contact pair")]
        c.check_true(f"{what}: one penalty pair with the brick, factor RWPNAL x RWKSF = 1",
                     code == 0 and pairs == ["wall1_brick"] and "set Algorithm = penalty" in out and
                     "set Penalty scale factor = 1\n" in out, (out + err).strip()[-400:])
    else:
        c.check_true(f"{what}: one kinematic pair with the brick, the rigid block left alone",
                     code == 0 and pairs == ["wall1_brick"] and "set Algorithm = kinematic" in out and
                     "Penalty scale factor" not in out, (out + err).strip()[-400:])

abaqus_errors = {
    "*Concrete Damaged Plasticity": ("*Density\n2400.0,\n", "*Density\n2400.0,\n*Concrete Damaged Plasticity\n"),
    "three rows of *Plastic, hardening=KINEMATIC": ("*Plastic\n3.5e8, 0.\n3.6e8, 0.5\n",
                                                    "*Plastic, hardening=KINEMATIC\n3.5e8, 0.\n3.6e8, 0.5\n"
                                                    "3.7e8, 1.0\n"),
    "a temperature column in *Plastic": ("3.6e8, 0.5\n", "3.6e8, 0.5, 20.\n"),
    "amplitude": ("*Boundary\n", "*Boundary, amplitude=A\n"),
}
for what, (old, new) in abaqus_errors.items():
    text = open(os.path.join(w, "deck.inp")).read()
    assert old in text, what
    with open(os.path.join(w, "bad.inp"), "w") as f:
        f.write(text.replace(old, new, 1))
    code, out, err = run_anvil(args.anvil, "bad.inp", cwd=w, extra_args=("--check",))
    c.check_true(f"ABAQUS, {what}: exit 2 and one line naming the line", code == 2 and
                 len(err.strip().splitlines()) == 1 and "line" in err, err.strip()[:300])
c.finish()
