#!/usr/bin/env python3
"""Accuracy against cost: four cases with a known answer, each run with one
numerical setting changed at a time from the shipped defaults, error of the
quantity that matters against cost (element-cycles and wall time).

    /usr/bin/python3 benchmarks/accuracy/accuracy.py --anvil build/anvil

Cases (doc/accuracy.md says what each reference is and how it was chosen):
  rod     prm/elastic_rod_impact: contact force rho c A v0 / 2 and its
          duration 2 L / c (bar theory);
  taylor  prm/steel_bar_impact: the bar's shortening and the growth of its
          foot's radius against a fine mesh (Global refinements 3, 256,000
          elements);
  hertz   an elastic quarter sphere on a rigid plane: peak force and contact
          time against Hertz (Johnson, section 11.4);
  column  prm/rc_column_impact, coarse (20 mm) to 30 ms: peak displacement of
          the struck point against the 10 mm column.
Settings varied (one at a time; the others at their defaults): integration
rule (one point with viscous or stiffness hourglass control, full), the
hourglass coefficient, the mesh (three sizes), the time-step safety factor,
the contact penalty factor and the enforcement (penalty or kinematic), the
formulation (updated or total Lagrangian)
and bulk viscosity (on or off); and local refinement (taylor, column: a
static region, and refinement during the run).

Writes OUTPUT/CASE.csv (one row per run), OUTPUT/CASE.png (error against
wall time on one process, the Pareto front joined) and OUTPUT/accuracy_tables.md.
Runs that finished are kept (their summary.csv): a second call reruns
only what is missing ('--rerun' for all). Nothing is asserted: the figures
are what this prints.
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(SOURCE, "tests"))
from anvil_test import read_csv  # noqa: E402


def summary(d):
    s = read_csv(os.path.join(d, "summary.csv"))
    return dict(zip(s["quantity"], s["value"]))


def bodies(d):
    with open(os.path.join(d, "bodies.csv")) as fh:
        rows = fh.read().splitlines()
    head = rows[0].split(",")
    return {r.split(",")[0]: dict(zip(head, r.split(","))) for r in rows[1:]}


# ---------------------------------------------------------------- the cases
class Case:
    """A scene, the bodies whose numerics the settings change, its mesh
    levels, and how its error is measured."""

    name = ""
    deformable = ()
    pairs = ()
    penalty = 0.1

    def scene(self, work):
        raise NotImplementedError

    def mesh(self, level):  # level -1 (coarser), 0 (shipped), +1 (finer)
        raise NotImplementedError

    def measure(self, d):  # -> dict of named quantities
        raise NotImplementedError

    def errors(self, q, reference):  # -> dict of named relative errors
        raise NotImplementedError

    def reference(self, work, run):
        return None

    def variations(self):
        body = lambda entry, value: [f"Body {b}/{entry}={value}" for b in self.deformable]
        pair = lambda value: [a for p in self.pairs for a in (f"Contact pair {p}/Algorithm=penalty",
                                                                f"Contact pair {p}/Penalty scale factor={value}")]
        v = [("defaults", "defaults", [])]
        v += [("integration", "one point, stiffness hourglass", body("Hourglass control/Type", "stiffness")),
              ("integration", "full integration", body("Integration", "full"))]
        v += [("hourglass", f"hourglass coefficient {q}", body("Hourglass control/Coefficient", q))
              for q in (0.03, 0.3)]
        v += [("mesh", "coarser mesh", self.mesh(-1)), ("mesh", "finer mesh", self.mesh(+1))]
        v += [("step", f"safety factor {f}", [f"Simulation/Time step safety factor={f}"]) for f in (0.5, 0.7)]
        v += [("penalty", f"penalty factor {f:.2g}", pair(f)) for f in (self.penalty / 3, self.penalty * 10)]
        v += [("contact", "kinematic contact", [f"Contact pair {p}/Algorithm=kinematic" for p in self.pairs]),
              ("contact", f"penalty contact at {self.penalty:.2g}", pair(self.penalty))]
        v += [("formulation", "total Lagrangian", body("Formulation", "total Lagrangian"))]
        v += [("bulk viscosity", "no bulk viscosity",
               body("Bulk viscosity/Linear coefficient", 0) + body("Bulk viscosity/Quadratic coefficient", 0))]
        v += self.adaptive()
        return v

    def adaptive(self):  # local refinement: [(group, label, overrides)]
        return []


class Rod(Case):
    name, deformable, pairs = "rod", ("rod_a", "rod_b"), ("impact",)
    exact_force, exact_duration = 0.01 * 100.0 * 1.0 / 2, 0.2

    def scene(self, work):
        return os.path.join(SOURCE, "prm", "elastic_rod_impact", "elastic_rod_impact.prm")

    def mesh(self, level):
        n = {-1: "40, 2, 2", 1: "160, 8, 8"}[level]
        return [f"Body {b}/Mesh/Subdivisions={n}" for b in self.deformable]

    def measure(self, d):
        contact = read_csv(os.path.join(d, "contact_impact.csv"))
        t, force = contact["time"], [-f for f in contact["normal_force_x"]]
        plateau = [f for ti, f in zip(t, force) if 0.03 <= ti <= 0.17]
        above = [ti for ti, f in zip(t, force) if f >= 0.5 * self.exact_force]
        return dict(force=sum(plateau) / len(plateau), duration=above[-1] - above[0] if above else 0.0)

    def errors(self, q, reference):
        return dict(force=q["force"] / self.exact_force - 1, duration=q["duration"] / self.exact_duration - 1)


class Taylor(Case):
    name, deformable, pairs = "taylor", ("bar",), ("impact",)
    L0, R0 = 0.05, 0.005

    def scene(self, work):
        return os.path.join(SOURCE, "prm", "steel_bar_impact", "steel_bar_impact.prm")

    def mesh(self, level):
        return [f"Body bar/Mesh/Global refinements={1 + level}"]

    def measure(self, d):
        bar = bodies(d)["bar"]
        return dict(shortening=self.L0 - (float(bar["xmax"]) - float(bar["xmin"])),
                    foot=0.5 * (float(bar["ymax"]) - float(bar["ymin"])) - self.R0)

    def errors(self, q, reference):
        return {k: q[k] / reference[k] - 1 for k in ("shortening", "foot")}

    def adaptive(self):
        # The shipped mesh halved in the 38 mm next to the wall (x > 12 mm),
        # and halved during the run within 4 mm of the wall (a round every
        # 8 us); the shipped kinematic contact on both.
        region = "Body bar/Refinement region/"
        return [("adaptivity", "refined at the impact end",
                 [region + "Lower corner=0.012, -1, -1", region + "Upper corner=1, 1, 1"]),
                ("adaptivity", "refined near the wall during the run",
                 ["Simulation/Adapt interval=8e-6", region + "Near body=wall", region + "Distance=0.004"])]

    def reference(self, work, run):
        # The shipped settings on the finest mesh a run of minutes allows
        # (Global refinements 3: 256,000 elements, 0.1 mm); its own error is
        # estimated from the change between it and the mesh one level
        # coarser (the study's finer mesh). Full integration is no reference
        # for plastic flow: its 2x2x2 points lock against the isochoric
        # plastic strain.
        fine = run("reference", ["Body bar/Mesh/Global refinements=3"])
        half = run("finer_mesh", self.mesh(+1))
        return fine, half


class Hertz(Case):
    name, deformable, pairs, penalty = "hertz", ("ball",), ("hit",), 1.0
    E, nu, rho, R, v = 1e7, 0.3, 1000.0, 0.05, 0.2

    def __init__(self):
        m = self.rho * 4 / 3 * math.pi * self.R ** 3
        Es = self.E / (1 - self.nu ** 2)
        delta = (15 * m * self.v ** 2 / (16 * Es * math.sqrt(self.R))) ** 0.4
        self.exact_force = 4 / 3 * Es * math.sqrt(self.R) * delta ** 1.5
        self.exact_duration = 2.9432 * delta / self.v

    def scene(self, work):
        # tests/contact/hertz_elastic_sphere.prm: the quarter ball of the
        # mesh source 'ball' (12 x 12 x 24, graded 1.15 to the pole) at
        # 0.2 m/s on an exact rigid plane, to 12 ms.
        path = os.path.join(work, "hertz.prm")
        with open(path, "w") as fh:
            fh.write(f"include {os.path.join(SOURCE, 'tests', 'contact', 'hertz_elastic_sphere.prm')}\n"
                     "subsection Simulation\n  set End time = 0.012\n  set History interval = 2e-5\nend\n")
        return path

    def mesh(self, level):
        return [f"Body ball/Mesh/Ball subdivisions={12 + 4 * level}"]

    def measure(self, d):
        contact = read_csv(os.path.join(d, "contact_hit.csv"))
        force = [4 * abs(f) for f in contact["normal_force_z"]]
        on = [t for t, f in zip(contact["time"], force) if f > 0]
        return dict(force=max(force), duration=on[-1] - on[0])

    def errors(self, q, reference):
        return dict(force=q["force"] / self.exact_force - 1, duration=q["duration"] / self.exact_duration - 1)


class Column(Case):
    name, deformable, pairs = "column", ("column",), ("impact",)
    end_time = 0.03

    def scene(self, work):
        return os.path.join(SOURCE, "prm", "rc_column_impact", "rc_column_impact.prm")

    def size(self, h):
        n = round(0.12 / h)
        return [f"Body column/Mesh/Subdivisions={n}, {n}, {round(1.5 / h)}",
                f"Rebar longitudinal/Element length={h}", f"Rebar stirrups/Element length={h}"]

    def common(self):
        return [f"Simulation/End time={self.end_time}"]

    def mesh(self, level):
        return self.size({-1: 0.03, 1: 0.015}[level])

    def measure(self, d):
        return dict(peak_displacement=summary(d)["peak_displacement_m"])

    def errors(self, q, reference):
        return dict(peak_displacement=q["peak_displacement"] / reference["peak_displacement"] - 1)

    def adaptive(self):
        # The 20 mm base halved to 10 mm: in the struck part of the member
        # (0.3-0.7 m, and 0.35-0.65 m), within 0.15 m of the hammer at the
        # start, and during the run within 0.15 m of the hammer and where
        # the damage passes 0.1 (a round every 2 ms).
        region = "Body column/Refinement region/"
        box = lambda lo, hi: [region + f"Lower corner=-1, -1, {lo}", region + f"Upper corner=1, 1, {hi}"]
        near = [region + "Near body=hammer", region + "Distance=0.15"]
        return [("adaptivity", "10 mm in 0.3-0.7 m", box(0.3, 0.7)),
                ("adaptivity", "10 mm in 0.35-0.65 m", box(0.35, 0.65)),
                ("adaptivity", "10 mm near the hammer", near),
                ("adaptivity", "10 mm near the hammer and where damaged, during the run",
                 near + ["Simulation/Adapt interval=0.002", region + "Indicator=damage",
                         region + "Indicator threshold=0.1"])]

    def reference(self, work, run):
        fine = run("reference", self.size(0.01))
        half = run("finer_mesh", self.mesh(+1))
        return fine, half


# Column: the shipped scene is the 10 mm column; the study's base is 20 mm.
def column_variations(case):
    base = case.size(0.02)
    out = []
    for group, label, overrides in Case.variations(case):
        out.append((group, label, overrides if group == "mesh" else base + overrides))
    return out


# ------------------------------------------------------------------ running
def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--anvil", default=os.path.join(SOURCE, "build", "anvil"))
    p.add_argument("--output", default="output/accuracy", help="where runs, tables and plots go")
    p.add_argument("--cases", default="rod,taylor,hertz,column")
    p.add_argument("--rerun", action="store_true", help="run again what finished earlier (not the references)")
    p.add_argument("--rerun-references", action="store_true", help="run the fine references again too")
    p.add_argument("--plots", default="true")
    a = p.parse_args()
    anvil = os.path.abspath(a.anvil)
    out = os.path.abspath(a.output)
    os.makedirs(out, exist_ok=True)
    tables = []
    cases = {c.name: c for c in (Rod(), Taylor(), Hertz(), Column())}
    for name in a.cases.split(","):
        case = cases[name]
        work = os.path.join(out, name)
        os.makedirs(work, exist_ok=True)
        scene = case.scene(work)
        common = getattr(case, "common", lambda: [])()

        done = {}

        def run(label, overrides):
            if label not in done:
                done[label] = run_once(label, overrides)
            return done[label]

        def run_once(label, overrides):
            d = os.path.join(work, "output", label)
            args = ([f"Simulation/Name={label}", "Simulation/Output interval=0", "Simulation/Plots=false",
                     "Simulation/Print wall times=false", "Simulation/Overwrite existing output=true"]
                    + common + overrides)
            stamp = "\n".join(args) + "\n"
            stamp_file = os.path.join(work, label + ".args")
            again = a.rerun_references or (a.rerun and not label.startswith("reference"))
            if (not again and os.path.exists(os.path.join(d, "summary.csv")) and os.path.exists(stamp_file)
                    and open(stamp_file).read() == stamp):
                return d, 0
            cmd = ["mpirun", "-np", "1", anvil, scene]
            for o in args:
                cmd += ["--set", o]
            start = time.time()
            r = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
            print(f"  {name} / {label}: exit {r.returncode}, {time.time() - start:.1f} s", flush=True)
            if r.returncode != 0:
                why = [l for l in r.stderr.splitlines() if l.startswith("anvil:")]
                print("    " + (why[0] if why else r.stderr.strip()[-300:]), flush=True)
                with open(os.path.join(work, label + ".err"), "w") as fh:
                    fh.write(r.stderr)
                return d, r.returncode
            # What --print-cost foresaw for this run, beside what it took.
            cost = subprocess.run(cmd[:4] + ["--print-cost"] + cmd[4:], cwd=work, capture_output=True, text=True)
            m = re.search(r"= ([0-9.e+]+) element-cycles", cost.stdout)
            w = re.search(r"about ([0-9.e+]+) s", cost.stdout)
            with open(os.path.join(d, "foreseen.txt"), "w") as fh:
                fh.write(f"{m.group(1) if m else 'nan'} {w.group(1) if w else 'nan'}\n")
            with open(stamp_file, "w") as fh:
                fh.write(stamp)
            return d, 0

        reference = None
        note = ""
        ref = case.reference(work, run)
        if ref:
            (fine, code_f), (half, code_h) = ref
            if code_f or code_h:
                print(f"{name}: the reference failed; skipped")
                continue
            reference = case.measure(fine)
            coarser = case.measure(half)
            sf, sh = summary(fine), summary(half)
            note = ("reference: " + ", ".join(f"{k} {v:.5g}" for k, v in reference.items())
                    + f" ({sf['elements']:.0f} elements, {sf['steps']:.0f} steps, {sf['wall_time_s']:.0f} s); "
                    + "one level coarser differs by "
                    + ", ".join(f"{k} {coarser[k] / reference[k] - 1:+.2%}" for k in reference))
            print(f"{name}: {note}")

        variations = column_variations(case) if name == "column" else case.variations()
        rows = []
        for group, label, overrides in variations:
            slug = label.replace(" ", "_").replace(",", "")
            d, code = run(slug, overrides)
            row = dict(group=group, label=label, exit=code)
            if code == 0:
                s = summary(d)
                q = case.measure(d)
                e = case.errors(q, reference)
                row.update(q)
                row.update({f"error_{k}": v for k, v in e.items()})
                row["error"] = max(abs(v) for v in e.values())
                row["elements"] = s["elements"]
                row["steps"] = s["steps"]
                row["element_cycles"] = s["elements"] * s["steps"]
                row["wall_time_s"] = s["wall_time_s"]
                row["ns_per_element_cycle"] = 1e9 * s["wall_time_s"] / row["element_cycles"]
                row["balance"] = s["max_balance_error"]
                try:
                    with open(os.path.join(d, "foreseen.txt")) as fh:
                        fc, fw = (float(x) for x in fh.read().split())
                except (OSError, ValueError):
                    fc = fw = float("nan")
                row["foreseen_cycles_ratio"] = fc / row["element_cycles"]
                row["foreseen_time_ratio"] = fw / row["wall_time_s"]
            rows.append(row)
        write_csv(os.path.join(out, name + ".csv"), rows)
        tables.append(table(name, rows, note))
        if a.plots == "true":
            pareto_plot(os.path.join(out, name + ".png"), name, rows)
    with open(os.path.join(out, "accuracy_tables.md"), "w") as fh:
        fh.write("\n".join(tables))
    print("\n".join(tables))


def write_csv(path, rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path + ".tmp", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(keys)
        for r in rows:
            w.writerow([r.get(k, "") for k in keys])
    os.replace(path + ".tmp", path)


def pareto(rows):
    ok = sorted((r for r in rows if r["exit"] == 0), key=lambda r: (r["wall_time_s"], r["error"]))
    front, best = [], math.inf
    for r in ok:
        if r["error"] < best:
            front.append(r)
            best = r["error"]
    return front


def table(name, rows, note):
    base = next((r for r in rows if r["label"] == "defaults" and r["exit"] == 0), None)
    front = {id(r) for r in pareto(rows)}
    errs = [k for k in rows[0] if k.startswith("error_")] if rows[0]["exit"] == 0 else []
    head = ["setting"] + [k[6:] + " error" for k in errs] + ["element-cycles", "cost / defaults", "wall s",
                                                               "ns / el-cycle", "balance",
                                                               "--print-cost / measured", "Pareto"]
    lines = [f"### {name}", ""] + ([note, ""] if note else [])
    lines += ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    for r in rows:
        if r["exit"] != 0:
            lines.append(f"| {r['label']} | stopped (exit {r['exit']}) |" + " |" * (len(head) - 2))
            continue
        cost = r["element_cycles"] / base["element_cycles"] if base else float("nan")
        cells = [r["label"]] + [f"{r[k]:+.2%}" for k in errs] + [
            f"{r['element_cycles']:.3g}", f"{cost:.2f}", f"{r['wall_time_s']:.1f}",
            f"{r['ns_per_element_cycle']:.0f}", f"{r['balance']:.1e}",
            f"{r['foreseen_cycles_ratio']:.2f} / {r['foreseen_time_ratio']:.2f}", "yes" if id(r) in front else ""]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def pareto_plot(path, name, rows):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing (Debian's python3-matplotlib): no plot")
        return
    ok = [r for r in rows if r["exit"] == 0]
    fig, ax = plt.subplots(figsize=(7.5, 5))
    groups = sorted({r["group"] for r in ok})
    markers = dict(zip(groups, "osD^v<>ph*"))
    for g in groups:
        rs = [r for r in ok if r["group"] == g]
        ax.scatter([r["wall_time_s"] for r in rs], [max(r["error"], 1e-5) for r in rs],
                   marker=markers[g], s=50 if g != "defaults" else 90, label=g, zorder=3)
    for r in ok:
        ax.annotate(r["label"], (r["wall_time_s"], max(r["error"], 1e-5)), fontsize=7,
                    xytext=(4, 3), textcoords="offset points")
    front = pareto(rows)
    ax.plot([r["wall_time_s"] for r in front], [max(r["error"], 1e-5) for r in front], "k--", lw=1,
            label="Pareto front", zorder=2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cost: wall time of the run on one process (s)")
    ax.set_ylabel("largest relative error of the measured quantities")
    ax.set_title(f"accuracy against cost: {name}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    os.replace(path + ".tmp.png", path)
    plt.close(fig)


if __name__ == "__main__":
    main()
