"""Read Anvil's VTU output with the VTK library (Debian's python3-vtk9, the
library ParaView reads it with; run with /usr/bin/python3). Used by the
tests and by the figure scripts of prm/.

Anvil writes one connected piece per process (solution_NNNN.R.vtu) and a
record naming them (solution_NNNN.pvtu): points carry node_id,
displacement and velocity; cells carry element_id, body and the fields;
the field data TIME is the frame's time."""
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def read_grid(path):
    """The vtkUnstructuredGrid of a .vtu piece or of a whole .pvtu frame."""
    reader = (vtk.vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu")
              else vtk.vtkXMLUnstructuredGridReader())
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def arrays(data):
    """{name: numpy array} of a vtkPointData, vtkCellData or vtkFieldData."""
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i))
            for i in range(data.GetNumberOfArrays())}


def read_vtu(path):
    """Return (centres, cells): the centre (x, y, z) of each cell, and
    {name: [value per cell]} for the scalar cell arrays, of a .vtu piece or
    a .pvtu frame."""
    grid = read_grid(path)
    centres = vtk.vtkCellCenters()
    centres.SetInputData(grid)
    centres.Update()
    xyz = vtk_to_numpy(centres.GetOutput().GetPoints().GetData())
    cells = {k: list(v) for k, v in arrays(grid.GetCellData()).items() if v.ndim == 1}
    return [tuple(p) for p in xyz], cells
