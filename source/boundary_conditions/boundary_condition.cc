#include <anvil/boundary_conditions/boundary_condition.h>
#include <anvil/mesh/body.h>
#include <anvil/mesh/mesh_file.h>
#include <anvil/utilities/input_error.h>

#include <algorithm>

namespace anvil
{
  void BoundaryCondition::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.declare_entry("Body", "", Patterns::Anything(),
                      "Name of the body whose nodes are constrained.");
    prm.declare_entry("Selection",
                      "boundary id",
                      Patterns::Selection("boundary id|surface|node set|box"),
                      "Which nodes: those on faces with one of 'Boundary "
                      "ids'; those on the faces of the mesh file's named "
                      "'Surfaces'; the nodes of the mesh file's 'Node sets'; "
                      "or those inside the box between 'Box lower "
                      "corner' and 'Box upper corner' (reference "
                      "configuration).");
    prm.declare_entry("Boundary ids",
                      "0",
                      Patterns::List(Patterns::Integer(0, 255)),
                      "Boundary ids of the constrained faces. Units: none.");
    prm.declare_entry("Surfaces",
                      "",
                      Patterns::Anything(),
                      "'Selection = surface': names of surfaces in the body's "
                      "mesh file (ABAQUS *Surface, Gmsh physical surfaces by "
                      "name or number), comma-separated, any case.");
    prm.declare_entry("Node sets",
                      "",
                      Patterns::Anything(),
                      "'Selection = node set': names of node sets in the "
                      "body's mesh file (ABAQUS *Nset, 'INSTANCE.SET'; Gmsh: "
                      "the nodes of a physical surface), comma-separated, any "
                      "case. Only the file's own nodes: those a 'Global "
                      "refinements' adds are not in a set.");
    prm.declare_entry("Box lower corner",
                      "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Lowest corner of the selection box. Units: m.");
    prm.declare_entry("Box upper corner",
                      "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Highest corner of the selection box. Units: m.");
    prm.declare_entry("Type",
                      "fixed",
                      Patterns::Selection(BoundaryConditions::Registry::names()),
                      BoundaryConditions::Registry::documentation(
                        "What the selected components of the selected nodes follow. Choices:"));
    BoundaryConditions::Registry::declare_parameters(prm, false);
    prm.declare_entry("Components",
                      "x, y, z",
                      Patterns::MultipleSelection("x|y|z"),
                      "Constrained velocity components.");
  }


  void BoundaryCondition::parse_parameters(dealii::ParameterHandler &prm,
                                           const std::string        &bc_name)
  {
    using dealii::Utilities::split_string_list;
    name = bc_name;
    body = prm.get("Body");
    if (body.empty())
      throw InputError("subsection 'Boundary condition " + name +
                       "': entry 'Body' is required");
    const std::string selection = prm.get("Selection");
    by_box       = selection == "box";
    by_node_set  = selection == "node set";
    names.clear();
    for (const auto &s :
         split_string_list(prm.get(selection == "surface" ? "Surfaces" : "Node sets")))
      if (!s.empty())
        names.push_back(MeshFile::key(s));
    if ((selection == "surface" || by_node_set) && names.empty())
      throw InputError("subsection 'Boundary condition " + name + "': 'Selection = " + selection +
                       "' needs '" + (by_node_set ? "Node sets" : "Surfaces") + "'");
    boundary_ids.clear();
    for (const auto &s : split_string_list(prm.get("Boundary ids")))
      boundary_ids.push_back(dealii::Utilities::string_to_int(s));
    auto vec = [&](const std::string &entry) {
      return three_numbers(prm.get(entry), entry, "subsection 'Boundary condition " + name + "'");
    };
    lower    = dealii::Point<3>(vec("Box lower corner"));
    upper    = dealii::Point<3>(vec("Box upper corner"));
    const std::string where = "subsection 'Boundary condition " + name + "'";
    auto plugin = BoundaryConditions::Registry::get(prm.get("Type"), where + ": entry 'Type'").create();
    plugin->parse_parameters(prm, where);
    motion = std::move(plugin);
    const std::string c = prm.get("Components");
    for (unsigned int d = 0; d < 3; ++d)
      components[d] = c.find(std::string(1, char('x' + d))) != std::string::npos;
  }


  void BoundaryCondition::resolve_names(const MeshNames &mesh)
  {
    if (names.empty())
      return;
    const std::string where = "subsection 'Boundary condition " + name + "': ";
    if (!by_node_set)
      boundary_ids.clear();
    positions.clear();
    for (const auto &n : names)
      if (by_node_set)
        {
          const auto set = mesh.node_sets.find(n);
          if (set == mesh.node_sets.end())
            throw InputError(where + "'Node sets' names '" + printable_excerpt(n) +
                             "', which body '" + body + "' does not have (its node sets: " +
                             MeshFile::names_of(mesh.node_sets) + ")");
          positions.insert(positions.end(), set->second.begin(), set->second.end());
        }
      else
        {
          const auto surface = mesh.surfaces.find(n);
          if (surface == mesh.surfaces.end())
            throw InputError(where + "'Surfaces' names '" + printable_excerpt(n) +
                             "', which body '" + body + "' does not have (its surfaces: " +
                             MeshFile::names_of(mesh.surfaces) + ")");
          boundary_ids.push_back(surface->second);
        }
    // Sorted by x, for a search by position with a tolerance.
    std::sort(positions.begin(), positions.end(),
              [](const dealii::Point<3> &a, const dealii::Point<3> &b) { return a[0] < b[0]; });
    tolerance = 0;
    for (const auto &x : positions)
      tolerance = std::max(tolerance, x.norm());
    tolerance = 1e-10 * std::max(tolerance, 1e-3);
  }


  bool BoundaryCondition::selects(const std::string               &body_name,
                                  const dealii::Point<3>          &X,
                                  const std::vector<unsigned int> &ids) const
  {
    if (body_name != body)
      return false;
    if (by_box)
      {
        for (unsigned int d = 0; d < 3; ++d)
          if (X[d] < lower[d] - 1e-12 * (1 + std::abs(lower[d])) ||
              X[d] > upper[d] + 1e-12 * (1 + std::abs(upper[d])))
            return false;
        return true;
      }
    if (by_node_set)
      {
        auto at = std::lower_bound(positions.begin(), positions.end(), X[0] - tolerance,
                                   [](const dealii::Point<3> &a, const double x) {
                                     return a[0] < x;
                                   });
        for (; at != positions.end() && (*at)[0] <= X[0] + tolerance; ++at)
          if (at->distance(X) <= tolerance)
            return true;
        return false;
      }
    for (const unsigned int id : ids)
      if (std::find(boundary_ids.begin(), boundary_ids.end(), id) !=
          boundary_ids.end())
        return true;
    return false;
  }
} // namespace anvil
