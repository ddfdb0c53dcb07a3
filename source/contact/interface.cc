/**
 * @file
 * The registry of contact algorithms and the entries every pair has.
 */
#include <anvil/contact/interface.h>
#include <anvil/utilities/input_error.h>

namespace anvil::Contact
{
  std::map<std::string, AlgorithmEntry> &algorithm_registry()
  {
    // A function-local static: safe to use from static initialisers of
    // other translation units (and of plugins).
    static std::map<std::string, AlgorithmEntry> algorithms;
    return algorithms;
  }


  bool register_algorithm(const std::string &name, AlgorithmEntry entry)
  {
    algorithm_registry()[name] = std::move(entry);
    return true;
  }


  void declare_parameters(dealii::ParameterHandler &prm)
  {
    std::string pattern, doc = "How the pair's contact is computed. Choices:";
    for (const auto &[name, entry] : algorithm_registry())
      {
        pattern += (pattern.empty() ? "" : "|") + name;
        doc += " '" + name + "': " + entry.description;
      }
    doc += " 'automatic' (the default): 'kinematic' for a pair with a rigid body "
           "(a hammer, a wall, an impactor), 'penalty' between two deformable bodies. "
           "Chosen from the accuracy study (doc/accuracy.md): against a rigid body "
           "kinematic contact brought Hertz's rigid sphere within 1.7 % of its force and "
           "time at 0.05-0.2 m/s (the penalty at 0.1: -34 % / +30 %), the Taylor foot "
           "from -7.2 % to -5.0 %, at the same steps within 5 %; between two deformable "
           "bodies meshed apart (a ball on a block) its node-by-node constraints dimple "
           "one-point elements' faces and lock the surfaces into each other (force "
           "spikes of 10 times the peak at 0.2 m/s), which the penalty's springs do not.";
    prm.declare_entry("Algorithm", "automatic", dealii::Patterns::Selection("automatic|" + pattern), doc);
    prm.declare_entry("First body", "", dealii::Patterns::Anything(), "Name of the first body of the pair.");
    prm.declare_entry("Second body", "", dealii::Patterns::Anything(), "Name of the second body of the pair.");
    for (const auto &[name, entry] : algorithm_registry())
      entry.declare_parameters(prm);
  }


  std::unique_ptr<Algorithm> create(dealii::ParameterHandler                      &prm,
                                    const std::string                             &pair_name,
                                    const std::function<bool(const std::string &)> &is_rigid)
  {
    const std::string first = prm.get("First body"), second = prm.get("Second body");
    if (first.empty() || second.empty())
      throw InputError("subsection 'Contact pair " + pair_name + "': 'First body' and 'Second body' are required");
    if (first == second)
      throw InputError("subsection 'Contact pair " + pair_name +
                       "': self-contact is not supported; name two bodies");
    std::string name = prm.get("Algorithm");
    if (name == "automatic")
      name = is_rigid(first) || is_rigid(second) ? "kinematic" : "penalty";
    auto algorithm         = algorithm_registry().at(name).create();
    algorithm->name        = pair_name;
    algorithm->first_body  = first;
    algorithm->second_body = second;
    algorithm->parse_parameters(prm);
    return algorithm;
  }
} // namespace anvil::Contact
