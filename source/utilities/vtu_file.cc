/**
 * @file
 * Writing VTK XML unstructured grids (see the header).
 */
#include <anvil/utilities/vtu_file.h>

#include <cstring>
#include <iomanip>
#include <limits>
#include <sstream>

namespace anvil::Vtu
{
  namespace
  {
    const char *const alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

    void append_base64(const std::vector<unsigned char> &bytes, std::string &out)
    {
      std::size_t i = 0;
      for (; i + 2 < bytes.size(); i += 3)
        {
          const unsigned int v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
          out += alphabet[(v >> 18) & 63];
          out += alphabet[(v >> 12) & 63];
          out += alphabet[(v >> 6) & 63];
          out += alphabet[v & 63];
        }
      if (i < bytes.size())
        {
          const unsigned int v =
            (bytes[i] << 16) | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0);
          out += alphabet[(v >> 18) & 63];
          out += alphabet[(v >> 12) & 63];
          out += i + 1 < bytes.size() ? alphabet[(v >> 6) & 63] : '=';
          out += '=';
        }
    }

    const char *type_name(const Array::Type type)
    {
      return type == Array::Type::float32 ? "Float32" :
             type == Array::Type::float64 ? "Float64" :
                                            "Int64";
    }

    // One DataArray element: a UInt64 byte count, then the values, in one
    // base64 stream (VTK's 'binary' inline format without compression).
    void data_array(std::ostream &xml, const std::string &name, const Array::Type type,
                    const unsigned int components, const std::vector<double> &values,
                    const bool field_data = false)
    {
      const std::size_t             width = type == Array::Type::float32 ? 4 : 8;
      const std::uint64_t           size  = values.size() * width;
      std::vector<unsigned char>    bytes(8 + size);
      std::memcpy(bytes.data(), &size, 8);
      for (std::size_t i = 0; i < values.size(); ++i)
        {
          unsigned char *at = bytes.data() + 8 + i * width;
          if (type == Array::Type::float32)
            {
              const float v = static_cast<float>(values[i]);
              std::memcpy(at, &v, 4);
            }
          else if (type == Array::Type::float64)
            std::memcpy(at, &values[i], 8);
          else
            {
              const std::int64_t v = static_cast<std::int64_t>(values[i]);
              std::memcpy(at, &v, 8);
            }
        }
      std::string text;
      text.reserve(bytes.size() * 4 / 3 + 4);
      append_base64(bytes, text);
      xml << "        <DataArray type=\"" << type_name(type) << "\" Name=\"" << name << "\"";
      if (components > 1)
        xml << " NumberOfComponents=\"" << components << "\"";
      if (field_data)
        xml << " NumberOfTuples=\"" << values.size() << "\"";
      xml << " format=\"binary\">\n          " << text << "\n        </DataArray>\n";
    }
  } // namespace


  void write_vtu(std::ostream &xml, const Piece &piece, const double time, const unsigned int cycle)
  {
    const std::size_t n_points = piece.points.size() / 3, n_cells = piece.hexahedra.size() / 8;
    xml << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <FieldData>\n";
    data_array(xml, "TIME", Array::Type::float64, 1, {time}, true);
    data_array(xml, "CYCLE", Array::Type::int64, 1, {double(cycle)}, true);
    xml << "    </FieldData>\n"
        << "    <Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\"" << n_cells
        << "\">\n      <Points>\n";
    data_array(xml, "Points", Array::Type::float64, 3, piece.points);
    xml << "      </Points>\n      <Cells>\n";
    std::vector<double> connectivity(piece.hexahedra.begin(), piece.hexahedra.end());
    std::vector<double> offsets(n_cells);
    for (std::size_t c = 0; c < n_cells; ++c)
      offsets[c] = 8. * (c + 1);
    data_array(xml, "connectivity", Array::Type::int64, 1, connectivity);
    data_array(xml, "offsets", Array::Type::int64, 1, offsets);
    // VTK wants UInt8 types; Int64 is read as well, but keep to the format.
    {
      std::vector<unsigned char> bytes(8 + n_cells, 12);
      const std::uint64_t        size = n_cells;
      std::memcpy(bytes.data(), &size, 8);
      std::string text;
      append_base64(bytes, text);
      xml << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">\n          "
          << text << "\n        </DataArray>\n";
    }
    xml << "      </Cells>\n      <PointData>\n";
    for (const auto &a : piece.point_data)
      data_array(xml, a.name, a.type, a.components, a.values);
    xml << "      </PointData>\n      <CellData>\n";
    for (const auto &a : piece.cell_data)
      data_array(xml, a.name, a.type, a.components, a.values);
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
