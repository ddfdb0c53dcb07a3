/**
 * @file
 * The registry of contact algorithms and the entries every pair has.
 */
#include <anvil/contact/interface.h>
#include <anvil/utilities/input_error.h>

namespace anvil::Contact
{
  void declare_parameters(dealii::ParameterHandler &prm)
  {
    std::string doc = Registry::documentation("How the pair's contact is computed. Choices:");
    doc += " 'automatic' (the default): 'kinematic' for every pair, its two passes "
           "solved together against a rigid body (a hammer, a wall, an impactor) and "
           "balanced between two deformable bodies. Chosen from the accuracy study "
           "(doc/accuracy.md), at the same steps within 5 %: against a rigid body "
           "kinematic contact brought Hertz's rigid sphere within 1.7 % of its force and "
           "time at 0.05-0.2 m/s (the penalty at 0.1: -34 % / +30 %), the Taylor foot "
           "from -7.2 % to -5.0 %; between two deformable bodies an elastic ball on an "
           "elastic block within 3.1 % / 2.0 % at 0.2 m/s (the penalty at 0.1: -7.3 % / "
           "+12 %) and two unequal rods' contact time within 0.5 % (the penalty: +4.9 %). "
           "The seed's own contact (section 4.3, Eq. (59)) is 'penalty'; the paper's scenes "
           "(prm/elastic_rod_impact, prm/rc_column_impact) state it.";
    prm.declare_entry("Algorithm", "automatic", dealii::Patterns::Selection("automatic|" + Registry::names()), doc);
    prm.declare_entry("First body", "", dealii::Patterns::Anything(), "Name of the first body of the pair.");
    prm.declare_entry("Second body", "", dealii::Patterns::Anything(), "Name of the second body of the pair.");
    Registry::declare_parameters(prm, false);
  }


  std::unique_ptr<Algorithm> create(dealii::ParameterHandler &prm, const std::string &pair_name)
  {
    const std::string first = prm.get("First body"), second = prm.get("Second body");
    if (first.empty() || second.empty())
      throw InputError("subsection 'Contact pair " + pair_name + "': 'First body' and 'Second body' are required");
    if (first == second)
      throw InputError("subsection 'Contact pair " + pair_name +
                       "': self-contact is not supported; name two bodies");
    std::string name = prm.get("Algorithm");
    if (name == "automatic")
      name = "kinematic";
    auto algorithm         = Registry::get(name, "subsection 'Contact pair " + pair_name + "': entry 'Algorithm'").create();
    algorithm->name        = pair_name;
    algorithm->first_body  = first;
    algorithm->second_body = second;
    algorithm->parse_parameters(prm);
    return algorithm;
  }
} // namespace anvil::Contact

template class anvil::Registry<anvil::Contact::Algorithm>;
