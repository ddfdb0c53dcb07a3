"""Nominal stress-strain curve of a concrete_cylinder run:

    python3 nominal_stress_strain.py output/concrete_cylinder_slow

reads rigid_platen.csv (platen force) and probe_top_centre.csv (the
specimen's top face), writes nominal_stress_strain.csv (strain = top face
travel / 300 mm, stress = platen force / the mesh's section, both positive
in compression; the section is the specimen's reference volume from
bodies.csv over 300 mm: the faceted hull's polygon, 2.55 % below
pi 75^2 mm^2 for the 16-gon of the shipped mesh; the platen's own travel
also counts the penalty contact's compliance) next to it, and prints
the peak stress and the strain at which it occurs. Standard library only.
"""
import csv
import os
import sys

directory = sys.argv[1] if len(sys.argv) > 1 else "output/concrete_cylinder_slow"
length = 0.3
with open(os.path.join(directory, "bodies.csv")) as f:
    section = next(float(b["reference_volume"]) for b in csv.DictReader(f)
                   if b["body"] == "specimen") / length
with open(os.path.join(directory, "rigid_platen.csv")) as f:
    rows = list(csv.DictReader(f))
with open(os.path.join(directory, "probe_top_centre.csv")) as f:
    top = list(csv.DictReader(f))
curve = [(float(r["time"]), -float(p["ux"]) / length, float(r["fx"]) / section)
         for r, p in zip(rows, top)]
with open(os.path.join(directory, "nominal_stress_strain.csv"), "w") as f:
    f.write("time,nominal_strain,nominal_stress\n")
    for t, e, s in curve:
        f.write(f"{t:.9g},{e:.9g},{s:.9g}\n")
t, e, s = max(curve, key=lambda c: c[2])
print(f"{directory}: peak nominal stress {s / 1e6:.2f} MPa at nominal strain {e * 1e3:.3f} per mille "
      f"(t = {t * 1e3:.3f} ms)")
