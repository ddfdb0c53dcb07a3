/**
 * @file
 * The mesh sources' registry, and the entries a scene sets of a source it
 * did not choose.
 */
#include <anvil/mesh/source.h>
#include <anvil/utilities/input_error.h>

#include <map>
#include <set>
#include <sstream>

namespace anvil::MeshSources
{
  namespace
  {
    /** The entries plugin @p entry declares, with their defaults. */
    std::map<std::string, std::string> declared_entries(const Registry::Entry &entry)
    {
      std::map<std::string, std::string> result;
      if (!entry.declare_parameters)
        return result;
      dealii::ParameterHandler prm;
      entry.declare_parameters(prm);
      std::ostringstream text;
      prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
      std::istringstream lines(text.str());
      for (std::string line; std::getline(lines, line);)
        {
          line = dealii::Utilities::trim(line);
          const auto equals = line.find('=');
          if (line.rfind("set ", 0) != 0 || equals == std::string::npos)
            continue;
          result[dealii::Utilities::trim(line.substr(4, equals - 4))] =
            dealii::Utilities::trim(line.substr(equals + 1));
        }
      return result;
    }
  } // namespace


  std::vector<std::string> foreign_entries(const dealii::ParameterHandler &prm,
                                           const std::string              &chosen,
                                           const std::vector<std::string> &shared)
  {
    std::set<std::string> own(shared.begin(), shared.end());
    for (const auto &[name, value] : declared_entries(Registry::get(chosen, "'Source'")))
      own.insert(name);
    std::vector<std::string> found;
    for (const auto &[source, entry] : Registry::entries())
      if (source != chosen)
        for (const auto &[name, default_value] : declared_entries(entry))
          if (own.insert(name).second && dealii::Utilities::trim(prm.get(name)) != default_value)
            found.push_back("'" + name + "' is an entry of 'Source = " + source + "' and is ignored with 'Source = " +
                            chosen + "'");
    return found;
  }
} // namespace anvil::MeshSources

template class anvil::Registry<anvil::MeshSources::Interface>;
