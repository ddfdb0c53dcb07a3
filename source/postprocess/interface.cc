/**
 * @file
 * The registry of postprocessors.
 */
#include <anvil/postprocess/interface.h>

#include <algorithm>

namespace anvil::Postprocess
{
  std::map<std::string, RegistryEntry> &registry()
  {
    // A function-local static: safe to use from static initialisers of
    // other translation units (and of plugins).
    static std::map<std::string, RegistryEntry> postprocessors;
    return postprocessors;
  }


  bool register_postprocessor(const std::string &name, RegistryEntry entry)
  {
    registry()[name] = std::move(entry);
    return true;
  }


  std::vector<std::unique_ptr<Interface>> create_all(Simulator &simulator)
  {
    std::vector<std::unique_ptr<Interface>> list;
    for (const auto &[name, entry] : registry())
      {
        list.push_back(entry.create(simulator));
        list.back()->plugin_name = name;
      }
    // By order, then name (the map's order; a stable sort keeps it).
    std::stable_sort(list.begin(), list.end(), [](const auto &a, const auto &b) { return a->order() < b->order(); });
    return list;
  }
} // namespace anvil::Postprocess
