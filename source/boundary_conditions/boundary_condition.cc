#include <anvil/boundary_conditions/boundary_condition.h>
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
                      Patterns::Selection("boundary id|box"),
                      "Which nodes: those on faces with one of 'Boundary "
                      "ids', or those inside the box between 'Box lower "
                      "corner' and 'Box upper corner' (reference "
                      "configuration).");
    prm.declare_entry("Boundary ids",
                      "0",
                      Patterns::List(Patterns::Integer(0, 255)),
                      "Boundary ids of the constrained faces. Units: none.");
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
                      Patterns::Selection("fixed|velocity"),
                      "'fixed': zero velocity; 'velocity': the constant "
                      "'Velocity' from t = 0 on.");
    prm.declare_entry("Velocity",
                      "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Prescribed velocity for 'Type = velocity'. Units: m/s.");
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
    by_box = prm.get("Selection") == "box";
    boundary_ids.clear();
    for (const auto &s : split_string_list(prm.get("Boundary ids")))
      boundary_ids.push_back(dealii::Utilities::string_to_int(s));
    auto vec = [&](const std::string &entry) {
      return three_numbers(prm.get(entry), entry, "subsection 'Boundary condition " + name + "'");
    };
    lower    = dealii::Point<3>(vec("Box lower corner"));
    upper    = dealii::Point<3>(vec("Box upper corner"));
    velocity = (prm.get("Type") == "velocity") ? vec("Velocity") :
                                                 dealii::Tensor<1, 3>();
    const std::string c = prm.get("Components");
    for (unsigned int d = 0; d < 3; ++d)
      components[d] = c.find(std::string(1, char('x' + d))) != std::string::npos;
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
    for (const unsigned int id : ids)
      if (std::find(boundary_ids.begin(), boundary_ids.end(), id) !=
          boundary_ids.end())
        return true;
    return false;
  }
} // namespace anvil
