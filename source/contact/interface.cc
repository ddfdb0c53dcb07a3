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
    prm.declare_entry("Algorithm", "penalty", dealii::Patterns::Selection(pattern), doc);
    prm.declare_entry("First body", "", dealii::Patterns::Anything(), "Name of the first body of the pair.");
    prm.declare_entry("Second body", "", dealii::Patterns::Anything(), "Name of the second body of the pair.");
    for (const auto &[name, entry] : algorithm_registry())
      entry.declare_parameters(prm);
  }


  std::unique_ptr<Algorithm> create(dealii::ParameterHandler &prm, const std::string &pair_name)
  {
    auto algorithm         = algorithm_registry().at(prm.get("Algorithm")).create();
    algorithm->name        = pair_name;
    algorithm->first_body  = prm.get("First body");
    algorithm->second_body = prm.get("Second body");
    if (algorithm->first_body.empty() || algorithm->second_body.empty())
      throw InputError("subsection 'Contact pair " + pair_name + "': 'First body' and 'Second body' are required");
    if (algorithm->first_body == algorithm->second_body)
      throw InputError("subsection 'Contact pair " + pair_name +
                       "': self-contact is not supported; name two bodies");
    algorithm->parse_parameters(prm);
    return algorithm;
  }
} // namespace anvil::Contact
