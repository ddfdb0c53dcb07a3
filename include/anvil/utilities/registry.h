/**
 * @file
 * Registry: the one table of plugins that every plugin family uses (material
 * models, contact algorithms, boundary conditions, postprocessors). A plugin
 * registers itself by name from a static initialiser at the bottom of its
 * .cc file (each family's ANVIL_REGISTER_... macro), Anvil's own and those
 * of the shared libraries a scene loads alike; the family then declares
 * the plugins' parameters, offers their names as the choices of a
 * selection, and creates the one a scene names.
 *
 * The table itself lives in the executable: each family's interface.cc
 * instantiates its Registry explicitly, and the family's header declares
 * that instantiation extern, so that a plugin library uses the executable's
 * table instead of a copy of its own.
 */
#pragma once

#include <anvil/utilities/input_error.h>

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace anvil
{
  /**
   * The plugins of one family: @p Base is the family's interface class,
   * @p CreateArgs what creating one needs (e.g. the Simulator for a
   * postprocessor).
   */
  template <typename Base, typename... CreateArgs>
  class Registry
  {
  public:
    struct Entry
    {
      /** One sentence for the parameter documentation. */
      std::string description;
      /** Declares the plugin's own entries in the current subsection
          (empty: it has none). */
      std::function<void(dealii::ParameterHandler &)> declare_parameters;
      std::function<std::unique_ptr<Base>(CreateArgs...)> create;
    };

    /** Every registered plugin, by name (the names' order). */
    static std::map<std::string, Entry> &entries();

    /** Register @p entry under @p name (the last one of a name wins, so
        that a plugin may replace one of Anvil's own); true. */
    static bool add(const std::string &name, Entry entry);

    /** "a|b|c", for Patterns::Selection. */
    static std::string names(const std::string &separator = "|");

    /** @p intro followed by " 'name': description" for each plugin. */
    static std::string documentation(const std::string &intro);

    /** Each plugin's own entries: in a subsection named after it with
        @p in_subsections, else all in the current subsection. */
    static void declare_parameters(dealii::ParameterHandler &prm, bool in_subsections);

    /** The entry of @p name; InputError naming @p where, the name and the
        choices for an unknown one. */
    static const Entry &get(const std::string &name, const std::string &where);
  };


  template <typename Base, typename... CreateArgs>
  std::map<std::string, typename Registry<Base, CreateArgs...>::Entry> &
  Registry<Base, CreateArgs...>::entries()
  {
    // A function-local static: safe to use from the static initialisers of
    // other translation units and of plugins.
    static std::map<std::string, Entry> table;
    return table;
  }


  template <typename Base, typename... CreateArgs>
  bool Registry<Base, CreateArgs...>::add(const std::string &name, Entry entry)
  {
    entries()[name] = std::move(entry);
    return true;
  }


  template <typename Base, typename... CreateArgs>
  std::string Registry<Base, CreateArgs...>::names(const std::string &separator)
  {
    std::string list;
    for (const auto &[name, entry] : entries())
      list += (list.empty() ? "" : separator) + name;
    return list;
  }


  template <typename Base, typename... CreateArgs>
  std::string Registry<Base, CreateArgs...>::documentation(const std::string &intro)
  {
    std::string doc = intro;
    for (const auto &[name, entry] : entries())
      doc += " '" + name + "': " + entry.description;
    return doc;
  }


  template <typename Base, typename... CreateArgs>
  void Registry<Base, CreateArgs...>::declare_parameters(dealii::ParameterHandler &prm,
                                                         const bool                in_subsections)
  {
    for (const auto &[name, entry] : entries())
      if (entry.declare_parameters)
        {
          if (in_subsections)
            prm.enter_subsection(name);
          entry.declare_parameters(prm);
          if (in_subsections)
            prm.leave_subsection();
        }
  }


  template <typename Base, typename... CreateArgs>
  const typename Registry<Base, CreateArgs...>::Entry &
  Registry<Base, CreateArgs...>::get(const std::string &name, const std::string &where)
  {
    const auto it = entries().find(name);
    if (it == entries().end())
      throw InputError(where + ": '" + name + "' is not one of " + names(", "));
    return it->second;
  }
} // namespace anvil
