"""Read the VTU files deal.II's DataOut writes for Anvil (zlib-compressed
binary, UInt32 headers), without VTK: each cell is a patch of its own
vertices, so a point-data array holds every cell's value once per vertex.
Used by the tests and by the figure scripts of prm/."""
import base64
import struct
import xml.etree.ElementTree as ET
import zlib

_SIZES = {"Float32": ("f", 4), "Float64": ("d", 8), "Int32": ("i", 4), "UInt8": ("B", 1)}


def _decode(array):
    text = array.text.strip()
    n_blocks = struct.unpack("<I", base64.b64decode(text[:8])[:4])[0]
    header_chars = 4 * ((4 * (3 + n_blocks) + 2) // 3)
    header = struct.unpack(f"<{3 + n_blocks}I", base64.b64decode(text[:header_chars]))
    data = base64.b64decode(text[header_chars:])
    raw, at = b"", 0
    for size in header[3:]:
        raw += zlib.decompress(data[at:at + size])
        at += size
    code, width = _SIZES[array.get("type")]
    return struct.unpack(f"<{len(raw) // width}{code}", raw)


def read_vtu(path):
    """Return (centres, cells): the centre (x, y, z) of each cell, and
    {name: [value per cell]} for the scalar arrays."""
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    n_points, n_cells = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
    per_cell = n_points // n_cells
    cells = {}
    for array in piece.find("PointData"):
        if int(array.get("NumberOfComponents", "1")) == 1:
            cells[array.get("Name")] = list(_decode(array)[::per_cell])
    xyz = _decode(piece.find("Points/DataArray"))
    centres = []
    for c in range(n_cells):
        block = xyz[3 * per_cell * c:3 * per_cell * (c + 1)]
        centres.append(tuple(sum(block[d::3]) / per_cell for d in range(3)))
    return centres, cells
