/**
 * @file
 * VTK XML unstructured grids of hexahedra written by Anvil itself: one
 * connected piece per process (points shared by the cells around them,
 * not eight per cell as deal.II's DataOut writes them), global node and
 * element ids, and the time as field data, so that ParaView, VTK and
 * scripts see the mesh a user meshed.
 */
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace anvil::Vtu
{
  /** A named array of point or cell data. */
  struct Array
  {
    enum class Type
    {
      float32,
      float64,
      int64
    };
    std::string         name;
    unsigned int        components = 1;
    Type                type       = Type::float32;
    std::vector<double> values; // components per point or cell (float64, int64)
    /** A float32 array's values as written (half the memory of values,
        which a float32 array leaves empty when it has these). */
    std::vector<float> floats;
  };

  /** What one process writes. */
  struct Piece
  {
    /** x, y, z of each point. */
    std::vector<double>       points;
    /** Eight points per hexahedron, in VTK's order. */
    std::vector<std::int64_t> hexahedra;
    std::vector<Array>        point_data, cell_data;
  };

  /** Bytes of the arrays a file holds and of what it writes of them
      (before base64), summed over the calls it is handed to. */
  struct Bytes
  {
    std::uint64_t raw     = 0;
    std::uint64_t written = 0;
  };

  /** Write the .vtu file of @p piece (inline base64 binary, little
      endian, UInt64 headers), with the field data TIME and CYCLE, to @p out
      array by array (the file's text is never held whole in memory). With
      @p compress each array is cut into blocks of 32 KiB compressed by
      zlib (VTK's vtkZLibDataCompressor: ParaView and VTK read it as they
      read the uncompressed form); @p bytes, if given, adds up what the
      arrays hold and what is written of them. */
  void write_vtu(std::ostream &out, const Piece &piece, double time, unsigned int cycle, bool compress = true,
                 Bytes *bytes = nullptr);

  /** The text of a .pvtu file whose pieces are @p files (relative to it),
      with the arrays of @p layout (its values unused). */
  std::string pvtu_text(const Piece &layout, const std::vector<std::string> &files);

  /** The text of a .pvd collection (ParaView's frame index) of the frames
      @p records (time, file relative to it), times in full precision. */
  std::string pvd_text(const std::vector<std::pair<double, std::string>> &records);
} // namespace anvil::Vtu
