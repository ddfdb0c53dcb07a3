/**
 * @file
 * Writing VTK XML unstructured grids (see the header).
 */
#include <anvil/utilities/vtu_file.h>

#include <zlib.h>

#include <cstring>
#include <stdexcept>
#include <vector>
#include <iomanip>
#include <limits>
#include <sstream>

namespace anvil::Vtu
{
  namespace
  {
    const char *const alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

    // Base64 of a byte stream, written to @p out as it comes (three bytes
    // make four characters): no copy of an array in bytes or in text.
    class Base64
    {
    public:
      explicit Base64(std::ostream &out)
        : out(out)
      {}

      void put(const void *data, const std::size_t size)
      {
        const auto *bytes = static_cast<const unsigned char *>(data);
        for (std::size_t i = 0; i < size; ++i)
          {
            triple[held++] = bytes[i];
            if (held == 3)
              {
                const unsigned int v = (triple[0] << 16) | (triple[1] << 8) | triple[2];
                text[used++]         = alphabet[(v >> 18) & 63];
                text[used++]         = alphabet[(v >> 12) & 63];
                text[used++]         = alphabet[(v >> 6) & 63];
                text[used++]         = alphabet[v & 63];
                held                 = 0;
                if (used == sizeof(text))
                  flush();
              }
          }
      }

      /** The last one or two bytes, padded with '='. */
      void finish()
      {
        if (held > 0)
          {
            const unsigned int v = (triple[0] << 16) | (held > 1 ? triple[1] << 8 : 0);
            text[used++]         = alphabet[(v >> 18) & 63];
            text[used++]         = alphabet[(v >> 12) & 63];
            text[used++]         = held > 1 ? alphabet[(v >> 6) & 63] : '=';
            text[used++]         = '=';
            held                 = 0;
          }
        flush();
      }

    private:
      void flush()
      {
        out.write(text, used);
        used = 0;
      }

      std::ostream &out;
      unsigned char triple[3] = {};
      unsigned int  held      = 0;
      char          text[4096];
      std::size_t   used = 0;
    };

    // The bytes of one DataArray, base64 as they come (uncompressed: a
    // UInt64 byte count, then the values, in one stream) or, compressed,
    // cut into blocks of 32 KiB that zlib compresses as they fill; at the
    // end VTK's header (number of blocks, block size, size of the last
    // block, compressed size of each) in one base64 stream and the
    // compressed blocks in another.
    class ArrayBytes
    {
    public:
      ArrayBytes(std::ostream &out, const std::uint64_t size, const bool compress, Bytes *bytes)
        : out(out)
        , compress(compress)
        , bytes(bytes)
        , text(out)
      {
        if (!compress)
          text.put(&size, 8);
        if (bytes != nullptr)
          bytes->raw += size, bytes->written += compress ? 0 : size + 8;
      }

      void put(const void *data, const std::size_t size)
      {
        if (!compress)
          {
            text.put(data, size);
            return;
          }
        const auto *p = static_cast<const unsigned char *>(data);
        for (std::size_t i = 0; i < size; ++i)
          {
            block[used++] = p[i];
            if (used == block_size)
              compress_block();
          }
      }

      void finish()
      {
        if (!compress)
          {
            text.finish();
            return;
          }
        // The size of a partial last block (0: every block full).
        const std::uint64_t last = used;
        if (used > 0)
          compress_block();
        std::vector<std::uint64_t> header = {blocks.size(), block_size, last};
        for (const auto &b : blocks)
          header.push_back(b.size());
        text.put(header.data(), 8 * header.size());
        text.finish();
        std::uint64_t written = 8 * header.size();
        Base64 data(out);
        for (const auto &b : blocks)
          {
            data.put(b.data(), b.size());
            written += b.size();
          }
        data.finish();
        if (bytes != nullptr)
          bytes->written += written;
      }

    private:
      static constexpr std::uint64_t block_size = 32768;

      // zlib's fastest level: on the column's frames twice the speed of
      // its default (6) for arrays 2-3 % larger (doc/performance.md).
      void compress_block()
      {
        uLongf size = compressBound(used);
        blocks.emplace_back(size);
        if (compress2(blocks.back().data(), &size, block, used, Z_BEST_SPEED) != Z_OK)
          throw std::runtime_error("zlib could not compress a VTU array");
        blocks.back().resize(size);
        used = 0;
      }

      std::ostream                            &out;
      const bool                               compress;
      Bytes                                   *bytes;
      Base64                                   text;
      unsigned char                            block[block_size];
      std::size_t                              used = 0;
      std::vector<std::vector<unsigned char>> blocks;
    };

    const char *type_name(const Array::Type type)
    {
      return type == Array::Type::float32 ? "Float32" :
             type == Array::Type::float64 ? "Float64" :
                                            "Int64";
    }

    // One DataArray element: a UInt64 byte count, then the values, in one
    // base64 stream (VTK's 'binary' inline format without compression).
    // @p value(i) gives the i-th of @p n values, as double or float.
    template <typename Value>
    void data_array(std::ostream &xml, const std::string &name, const Array::Type type,
                    const unsigned int components, const std::size_t n, const Value &value,
                    const bool compress, Bytes *bytes, const bool field_data = false)
    {
      const std::size_t   width = type == Array::Type::float32 ? 4 : 8;
      const std::uint64_t size  = n * width;
      xml << "        <DataArray type=\"" << type_name(type) << "\" Name=\"" << name << "\"";
      if (components > 1)
        xml << " NumberOfComponents=\"" << components << "\"";
      if (field_data)
        xml << " NumberOfTuples=\"" << n << "\"";
      xml << " format=\"binary\">\n          ";
      ArrayBytes text(xml, size, compress, bytes);
      for (std::size_t i = 0; i < n; ++i)
        if (type == Array::Type::float32)
          {
            const float v = static_cast<float>(value(i));
            text.put(&v, 4);
          }
        else if (type == Array::Type::float64)
          {
            const double v = value(i);
            text.put(&v, 8);
          }
        else
          {
            const std::int64_t v = static_cast<std::int64_t>(value(i));
            text.put(&v, 8);
          }
      text.finish();
      xml << "\n        </DataArray>\n";
    }

    void data_array(std::ostream &xml, const Array &a, const bool compress, Bytes *bytes)
    {
      if (a.type == Array::Type::float32 && !a.floats.empty())
        data_array(xml, a.name, a.type, a.components, a.floats.size(),
                   [&](const std::size_t i) { return a.floats[i]; }, compress, bytes);
      else
        data_array(xml, a.name, a.type, a.components, a.values.size(),
                   [&](const std::size_t i) { return a.values[i]; }, compress, bytes);
    }
  } // namespace


  void write_vtu(std::ostream &xml, const Piece &piece, const double time, const unsigned int cycle,
                 const bool compress, Bytes *bytes)
  {
    const std::size_t n_points = piece.points.size() / 3, n_cells = piece.hexahedra.size() / 8;
    xml << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\""
        << (compress ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n"
        << "  <UnstructuredGrid>\n"
        << "    <FieldData>\n";
    const double time_value = time, cycle_value = cycle;
    data_array(xml, "TIME", Array::Type::float64, 1, 1, [&](std::size_t) { return time_value; }, compress,
               bytes, true);
    data_array(xml, "CYCLE", Array::Type::int64, 1, 1, [&](std::size_t) { return cycle_value; }, compress,
               bytes, true);
    xml << "    </FieldData>\n"
        << "    <Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\"" << n_cells
        << "\">\n      <Points>\n";
    data_array(xml, "Points", Array::Type::float64, 3, piece.points.size(),
               [&](const std::size_t i) { return piece.points[i]; }, compress, bytes);
    xml << "      </Points>\n      <Cells>\n";
    data_array(xml, "connectivity", Array::Type::int64, 1, piece.hexahedra.size(),
               [&](const std::size_t i) { return double(piece.hexahedra[i]); }, compress, bytes);
    data_array(xml, "offsets", Array::Type::int64, 1, n_cells,
               [](const std::size_t c) { return 8. * (c + 1); }, compress, bytes);
    // VTK wants UInt8 types; Int64 is read as well, but keep to the format.
    {
      xml << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">\n          ";
      ArrayBytes          text(xml, n_cells, compress, bytes);
      const unsigned char hexahedron = 12;
      for (std::size_t c = 0; c < n_cells; ++c)
        text.put(&hexahedron, 1);
      text.finish();
      xml << "\n        </DataArray>\n";
    }
    xml << "      </Cells>\n      <PointData>\n";
    for (const auto &a : piece.point_data)
      data_array(xml, a, compress, bytes);
    xml << "      </PointData>\n      <CellData>\n";
    for (const auto &a : piece.cell_data)
      data_array(xml, a, compress, bytes);
    xml << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  }


  std::string pvtu_text(const Piece &layout, const std::vector<std::string> &files)
  {
    std::ostringstream xml;
    auto declare = [&](const Array &a) {
      xml << "      <PDataArray type=\"" << type_name(a.type) << "\" Name=\"" << a.name << "\"";
      if (a.components > 1)
        xml << " NumberOfComponents=\"" << a.components << "\"";
      xml << "/>\n";
    };
    xml << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n"
        << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
        << "    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
        << "    </PPoints>\n    <PPointData>\n";
    for (const auto &a : layout.point_data)
      declare(a);
    xml << "    </PPointData>\n    <PCellData>\n";
    for (const auto &a : layout.cell_data)
      declare(a);
    xml << "    </PCellData>\n";
    for (const auto &f : files)
      xml << "    <Piece Source=\"" << f << "\"/>\n";
    xml << "  </PUnstructuredGrid>\n</VTKFile>\n";
    return xml.str();
  }


  std::string pvd_text(const std::vector<std::pair<double, std::string>> &records)
  {
    std::ostringstream xml;
    xml << std::setprecision(17)
        << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (const auto &[time, file] : records)
      xml << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << file
          << "\"/>\n";
    xml << "  </Collection>\n</VTKFile>\n";
    return xml.str();
  }
} // namespace anvil::Vtu
