/**
 * @file
 * The scene's postprocessors: 'Postprocess/List', each one's entries, and
 * the order their run_after() asks for.
 */
#include <anvil/postprocess/interface.h>
#include <anvil/utilities/text.h>

#include <algorithm>
#include <set>

namespace anvil::Postprocess
{
  void declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("List",
                      "all",
                      dealii::Patterns::Anything(),
                      Registry::documentation(
                        "The postprocessors this scene runs, comma-separated, or 'all' (every "
                        "registered one, those of 'Additional shared libraries' included). "
                        "Each runs after the others it reads where the scene has them. "
                        "Choices:"));
    Registry::declare_parameters(prm, true);
  }


  std::vector<std::unique_ptr<Interface>> create_all(Simulator &simulator, dealii::ParameterHandler &prm)
  {
    std::set<std::string> listed;
    const std::string     list = prm.get("List");
    for (const auto &name : dealii::Utilities::split_string_list(list))
      if (name == "all")
        for (const auto &[n, entry] : Registry::entries())
          listed.insert(n);
      else if (!name.empty())
        {
          Registry::get(name, "entry 'Postprocess/List'");
          listed.insert(name);
        }

    std::vector<std::unique_ptr<Interface>> created;
    for (const auto &name : listed)
      {
        created.push_back(Registry::get(name, "entry 'Postprocess/List'").create(simulator));
        created.back()->plugin_name = name;
        prm.enter_subsection(name);
        created.back()->parse_parameters(prm);
        prm.leave_subsection();
      }

    // Kahn's order: the first by name among those whose run_after() names
    // no postprocessor still waiting (names the scene does not run are
    // ignored). A cycle is a programming error of the plugins named.
    std::vector<std::unique_ptr<Interface>> ordered;
    while (!created.empty())
      {
        auto next = created.end();
        for (auto it = created.begin(); it != created.end() && next == created.end(); ++it)
          {
            const auto after = (*it)->run_after();
            const bool ready = std::none_of(after.begin(), after.end(), [&](const std::string &name) {
              return std::any_of(created.begin(), created.end(),
                                 [&](const auto &p) { return p->plugin_name == name; });
            });
            if (ready)
              next = it;
          }
        if (next == created.end())
          {
            std::vector<std::string> names;
            for (const auto &p : created)
              names.push_back(p->plugin_name);
            throw InputError("entry 'Postprocess/List': the postprocessors " + join(names) +
                             " each wait for another to run first (their run_after() form a cycle)");
          }
        ordered.push_back(std::move(*next));
        created.erase(next);
      }
    return ordered;
  }
} // namespace anvil::Postprocess

template class anvil::Registry<anvil::Postprocess::Interface, anvil::Simulator &>;
