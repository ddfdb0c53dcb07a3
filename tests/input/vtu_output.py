"""The VTU output as ParaView sees it, read with the VTK library (Debian's
python3-vtk9, the library ParaView uses) from the .pvtu record of each
frame (tests/input/vtu_two_bodies.prm and vtu_block.prm).

- A connected mesh: each frame has one point per mesh node on one process
  (87 for a 4x3x2 and a 2x2x2 block, not 8 per cell), every node_id once,
  element_id 0 ... 31 once each, body 0 or 1;
- a free block thrown at v0: every one of its nodes has displacement
  v0 t and velocity v0 (rigid translation, exact to round-off);
- TIME, and the frame index solution.pvd, hold the frame's time in full
  (an end time with 13 digits);
- np = 2 against np = 1, matched by node_id and element_id: the same
  displacements and stresses (the ids do not depend on the partition);
  on two processes the interface nodes appear in both pieces, with the
  same values;
- 'Output compression = zlib' (the default) and 'none' write the same
  arrays as VTK reads them, bit for bit, for a 32^3 block whose arrays
  span many 32 KiB blocks and end on a block boundary (the cell types:
  32,768 bytes, element_id: 8 blocks exactly) as well as inside one; the
  compressed pieces name the compressor and are smaller (ratio printed)."""
import os
import numpy as np
from anvil_test import Checker, arguments, run_anvil, test_scene

import vtk
from vtk.util.numpy_support import vtk_to_numpy

args = arguments()
c = Checker("VTU output read with VTK: connected mesh, global ids, TIME")

end_time = 1.234567890123e-5
v0 = np.array([1.5, -0.5, 0.25])

def read(path):
    reader = vtk.vtkXMLPUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    point = {grid.GetPointData().GetArrayName(i): vtk_to_numpy(grid.GetPointData().GetArray(i))
             for i in range(grid.GetPointData().GetNumberOfArrays())}
    cell = {grid.GetCellData().GetArrayName(i): vtk_to_numpy(grid.GetCellData().GetArray(i))
            for i in range(grid.GetCellData().GetNumberOfArrays())}
    return grid, point, cell


frames = {}
for np_ in (1, 2):
    prm = test_scene(args, "tests/input/vtu_two_bodies.prm", f"vtu_np{np_}")
    code, out, err = run_anvil(args.anvil, prm, np=np_, cwd=args.work_dir)
    if not c.check_true(f"np = {np_}: runs", code == 0, err.strip()):
        continue
    frames[np_] = read(os.path.join(args.work_dir, f"output/vtu_np{np_}/solution_0001.pvtu"))
    piece = vtk.vtkXMLUnstructuredGridReader()
    piece.SetFileName(os.path.join(args.work_dir, f"output/vtu_np{np_}/solution_0001.0.vtu"))
    piece.Update()
    time = vtk_to_numpy(piece.GetOutput().GetFieldData().GetArray("TIME"))[0]
    c.check(f"np = {np_}: TIME field data against the end time [s]", time, end_time, 0)
    pvd = open(os.path.join(args.work_dir, f"output/vtu_np{np_}/solution.pvd")).read()
    stamps = [float(x.split('"')[0]) for x in pvd.split('timestep="')[1:]]
    c.check(f"np = {np_}: solution.pvd's last timestep against the end time [s]", stamps[-1],
            end_time, 0)

if 1 in frames:
    grid, point, cell = frames[1]
    c.check("np = 1: points (nodes of both blocks: 5x4x3 + 3x3x3)", grid.GetNumberOfPoints(), 87, 0)
    c.check("np = 1: distinct node_id", len(set(point["node_id"])), 87, 0)
    c.check_true("np = 1: element_id is 0 ... 31, each once",
                 sorted(cell["element_id"]) == list(range(32)))
    c.check_true("np = 1: body 0 for the 24 cells of 'held', 1 for the 8 of 'free'",
                 sorted(cell["body"]) == [0] * 24 + [1] * 8)
    # The free block: rigid translation, from the nodes of body 1's cells.
    ids = vtk.vtkIdList()
    free_points = set()
    for i in range(grid.GetNumberOfCells()):
        if cell["body"][i] == 1:
            grid.GetCellPoints(i, ids)
            free_points.update(ids.GetId(k) for k in range(ids.GetNumberOfIds()))
    free_points = sorted(free_points)
    u = point["displacement"][free_points]
    v = point["velocity"][free_points]
    c.check("free block: nodes", len(free_points), 27, 0)
    c.check("free block: largest |u - v0 t| over its nodes [m]",
            float(np.abs(u - v0 * end_time).max()), 0.0, 1e-12 * np.linalg.norm(v0) * end_time)
    c.check("free block: largest |v - v0| over its nodes [m/s]",
            float(np.abs(v - v0).max()), 0.0, 1e-12 * np.linalg.norm(v0))

if 1 in frames and 2 in frames:
    (g1, p1, c1), (g2, p2, c2) = frames[1], frames[2]
    c.check_true("np = 2: the two pieces hold every node (distinct node_id: 87)",
                 len(set(p2["node_id"])) == 87, f"{g2.GetNumberOfPoints()} points in all")
    c.check_true("np = 2: element_id 0 ... 31, each once", sorted(c2["element_id"]) == list(range(32)))
    by_node_1 = {int(n): p1["displacement"][i] for i, n in enumerate(p1["node_id"])}
    worst = 0.0
    for i, n in enumerate(p2["node_id"]):  # interface nodes twice: both must match
        worst = max(worst, float(np.abs(p2["displacement"][i] - by_node_1[int(n)]).max()))
    scale = float(np.abs(p1["displacement"]).max())
    c.check("np = 2 against np = 1 by node_id: largest displacement difference [m]", worst, 0.0,
            1e-9 * scale)
    order1, order2 = np.argsort(c1["element_id"]), np.argsort(c2["element_id"])
    s1, s2 = c1["stress_xx"][order1], c2["stress_xx"][order2]
    c.check("np = 2 against np = 1 by element_id: largest stress_xx difference [Pa]",
            float(np.abs(s1 - s2).max()), 0.0, 1e-6 * float(np.abs(s1).max()))
    c.check_true("the held block is loaded (stress_xx not zero)", float(np.abs(s1).max()) > 0)

# Compressed and uncompressed pieces hold the same arrays.
def arrays_of(path):
    grid, point, cell = read(path)
    out = {"points": vtk_to_numpy(grid.GetPoints().GetData())}
    out.update({"point " + k: v for k, v in point.items()})
    out.update({"cell " + k: v for k, v in cell.items()})
    return out


got, sizes = {}, {}
for compression in ("zlib", "none"):
    prm = test_scene(args, "tests/input/vtu_block.prm", f"block_{compression}",
                     {"Simulation/Output compression": compression})
    code, out, err = run_anvil(args.anvil, prm, cwd=args.work_dir)
    if not c.check_true(f"32^3 block, compression {compression}: runs", code == 0, err.strip()):
        continue
    piece = os.path.join(args.work_dir, f"output/block_{compression}/solution_0001.0.vtu")
    got[compression] = arrays_of(os.path.join(args.work_dir, f"output/block_{compression}/solution_0001.pvtu"))
    sizes[compression] = os.path.getsize(piece)
    c.check_true(f"compression {compression}: the piece names vtkZLibDataCompressor only when compressed",
                 ("vtkZLibDataCompressor" in open(piece).read(2000)) == (compression == "zlib"))
if len(got) == 2:
    c.check_true("zlib and none: the same array names", sorted(got["zlib"]) == sorted(got["none"]))
    differing = [k for k in got["none"] if k in got["zlib"] and
                 (got["zlib"][k].shape != got["none"][k].shape or
                  not np.array_equal(got["zlib"][k], got["none"][k]))]
    c.check_true("zlib and none: every array bit for bit", not differing, ", ".join(differing))
    print(f"  32^3 block: piece {sizes['none'] / 1e6:.2f} MB uncompressed, {sizes['zlib'] / 1e6:.2f} MB "
          f"with zlib (ratio {sizes['none'] / sizes['zlib']:.2f})")
    c.check_below("zlib piece size / uncompressed piece size", sizes["zlib"] / sizes["none"], 1.0)
c.finish()
