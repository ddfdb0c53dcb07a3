/**
 * @file
 * The mesh source 'file': the cells of an ABAQUS .inp or Gmsh .msh file
 * (MeshSources::Interface), with the file's surfaces as boundary ids and
 * its node sets for the boundary conditions.
 */
#include <anvil/mesh/mesh_file.h>
#include <anvil/mesh/source.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <set>

namespace anvil::MeshSources
{
  class File : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.declare_entry("File name", "", Patterns::Anything(),
                        "File: mesh file (.msh or .inp), relative to the folder of the scene file that "
                        "names it (an included scene's own folder).");
      prm.declare_entry("Region", "", Patterns::Anything(),
                        "File: the cells this body takes, as a comma-separated list of names the file "
                        "gives to groups of cells (ABAQUS: instances, parts, element sets, "
                        "'INSTANCE.SET'; Gmsh: physical volumes by name or number); matched without "
                        "regard to case. Empty: every cell of the file.");
      prm.declare_entry("Scale", "1", Patterns::Double(0.),
                        "File: factor applied to the coordinates read (e.g. 0.001 for a mesh in mm). "
                        "Units: none.");
    }

    void parse_parameters(dealii::ParameterHandler &prm, const Context &context) override
    {
      where     = context.where;
      name      = context.body;
      file_name = prm.get("File name");
      if (!file_name.empty() && file_name[0] != '/')
        file_name = context.scene_directory + "/" + file_name;
      region.clear();
      for (const auto &r : dealii::Utilities::split_string_list(prm.get("Region")))
        if (!r.empty())
          region.push_back(MeshFile::key(r));
      scale = prm.get_double("Scale");
      if (file_name.empty())
        throw InputError(where + ": 'Source = file' needs 'File name'");
      if (!std::ifstream(file_name))
        throw InputError(where + ": mesh file '" + file_name + "' cannot be opened");
    }

    // The cells of the file's 'Region' (all if empty) become the body's
    // mesh, with the file's surfaces as boundary ids on their faces that
    // lie on its boundary.
    void create(dealii::Triangulation<3> &tria, const unsigned int refinements, MeshNames *names) const override
    {
      using namespace dealii;
      const MeshFile::Contents file  = MeshFile::read(file_name);
      const std::string        where = this->where + ": ";
      std::vector<bool>        take(file.cells.size(), region.empty());
      for (const auto &r : region)
        {
          const auto set = file.cell_sets.find(r);
          if (set == file.cell_sets.end())
            throw InputError(where + "'Region' names '" + printable_excerpt(r) +
                             "', which mesh file '" + file_name +
                             "' does not define (its groups of cells: " +
                             MeshFile::names_of(file.cell_sets) + ")");
          for (const unsigned int c : set->second)
            take[c] = true;
        }

      std::vector<unsigned int> index(file.vertices.size(), numbers::invalid_unsigned_int);
      std::vector<Point<3>>     vertices;
      std::vector<CellData<3>>  cells;
      // Faces of the cells taken, by their sorted vertices: a face two cells
      // share is interior and keeps no boundary id.
      std::map<std::array<unsigned int, 4>, unsigned int> face_count;
      auto sorted = [](std::array<unsigned int, 4> v) {
        std::sort(v.begin(), v.end());
        return v;
      };
      for (unsigned int c = 0; c < file.cells.size(); ++c)
        if (take[c])
          {
            CellData<3> cell(8);
            for (unsigned int v = 0; v < 8; ++v)
              {
                const unsigned int g = file.cells[c][v];
                if (index[g] == numbers::invalid_unsigned_int)
                  {
                    index[g] = vertices.size();
                    vertices.push_back(file.vertices[g]);
                  }
                cell.vertices[v] = index[g];
              }
            cells.push_back(cell);
            for (const unsigned int f : GeometryInfo<3>::face_indices())
              {
                std::array<unsigned int, 4> face;
                for (unsigned int v = 0; v < 4; ++v)
                  face[v] = file.cells[c][GeometryInfo<3>::face_to_cell_vertices(f, v)];
                ++face_count[sorted(face)];
              }
          }
      std::map<std::array<unsigned int, 4>, CellData<2>> boundary;
      std::set<unsigned int>                            ids_on_body;
      for (const auto &face : file.faces)
        if (take[face.cell] && face_count[sorted(face.vertices)] == 1)
          {
            CellData<2> quad(4);
            for (unsigned int v = 0; v < 4; ++v)
              quad.vertices[v] = index[face.vertices[v]];
            quad.boundary_id             = face.boundary_id;
            boundary[sorted(face.vertices)] = quad;
            ids_on_body.insert(face.boundary_id);
          }
      SubCellData subcell;
      for (const auto &b : boundary)
        subcell.boundary_quads.push_back(b.second);

      try
        {
          // Every corner of every cell must have a positive Jacobian: a cell
          // written the other way round (all eight negative) is turned, a
          // flat or twisted one (mixed signs, or zero) would have no mass or
          // a negative volume.
          std::vector<unsigned int> taken;
          for (unsigned int c = 0; c < file.cells.size(); ++c)
            if (take[c])
              taken.push_back(c);
          auto corner_signs = [&](const CellData<3> &cell, unsigned int &positive) {
            positive = 0;
            for (unsigned int corner = 0; corner < 8; ++corner)
              {
                Tensor<2, 3> J;
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    const unsigned int bit  = 1u << d;
                    const Tensor<1, 3> edge = vertices[cell.vertices[corner ^ bit]] -
                                              vertices[cell.vertices[corner]];
                    for (unsigned int e = 0; e < 3; ++e)
                      J[e][d] = (corner & bit) ? -edge[e] : edge[e];
                  }
                const double det = determinant(J);
                if (det > 0)
                  ++positive;
                else if (!(det < 0))
                  return false;
              }
            return true;
          };
          for (unsigned int i = 0; i < cells.size(); ++i)
            {
              unsigned int positive = 0;
              bool         nonzero  = corner_signs(cells[i], positive);
              if (nonzero && positive == 0)
                {
                  // Mirrored: swap the two ends along the cell's x.
                  for (unsigned int v = 0; v < 8; v += 2)
                    std::swap(cells[i].vertices[v], cells[i].vertices[v + 1]);
                  nonzero = corner_signs(cells[i], positive);
                }
              if (!nonzero || positive != 8)
                throw InputError("mesh file '" + file_name + "': element " +
                                 std::to_string(file.labels.empty() ? long(taken[i]) :
                                                                      file.labels[taken[i]]) +
                                 " (body '" + name + "') is flat or twisted: the Jacobian "
                                 "is not positive at all its corners");
            }
          GridTools::consistently_order_cells(cells);
          check_size(this->where, "the file's cells and 'Global refinements'", "elements",
                     double(cells.size()) * std::pow(8., refinements), 4096.);
          tria.create_triangulation(vertices, cells, subcell);
        }
      catch (const ExceptionBase &e)
        {
          throw InputError("mesh file '" + file_name + "' (body '" + name +
                           "'): not a valid hexahedral mesh: " + one_line_message(e).substr(0, 300));
        }
      if (scale != 1.)
        GridTools::scale(scale, tria);
      tria.refine_global(refinements);

      if (!names)
        return;
      for (const auto &s : file.surfaces)
        if (ids_on_body.count(s.second))
          names->surfaces[s.first] = s.second;
      for (const auto &s : file.node_sets)
        {
          std::vector<Point<3>> positions;
          for (const unsigned int v : s.second)
            if (index[v] != numbers::invalid_unsigned_int)
              positions.push_back(file.vertices[v] * scale);
          if (!positions.empty())
            names->node_sets[s.first] = positions;
        }
      names->note.clear();
      if (!file.skipped.empty())
        names->note = "mesh file '" + file_name + "': skipped " + file.skipped +
                      " (a scene takes from a mesh file its mesh, sets and surfaces only)";
      if (region.empty() && file.regions.size() > 1)
        {
          std::string list;
          for (const auto &r : file.regions)
            list += (list.empty() ? "" : ", ") + r;
          names->note += std::string(names->note.empty() ? "" : "; ") + "mesh file '" + file_name +
                         "' holds " + std::to_string(file.regions.size()) + " regions (" +
                         printable_excerpt(list) +
                         "), all taken as this one body ('Region' takes one)";
        }
    }

  private:
    std::string where, name, file_name;
    /** Names of the file's cell groups the body takes (all if empty). */
    std::vector<std::string> region;
    double                   scale = 1;
  };


  ANVIL_REGISTER_MESH_SOURCE(File, "file",
                             "ABAQUS .inp with parts, instances, sets and surfaces, or ASCII Gmsh .msh "
                             "2.2/4.1 with physical groups; named surfaces become boundary ids, see "
                             "'Region'.")
} // namespace anvil::MeshSources
