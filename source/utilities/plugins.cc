#include <anvil/utilities/input_error.h>
#include <anvil/utilities/plugins.h>

#include <deal.II/base/utilities.h>

#include <dlfcn.h>

#include <filesystem>

namespace anvil
{
  void load_shared_libraries(const std::string &list, const std::string &directory, const std::string &where)
  {
    for (const auto &name : dealii::Utilities::split_string_list(list, ','))
      {
        if (name.empty())
          continue;
        std::filesystem::path path(name);
        if (path.is_relative())
          path = std::filesystem::path(directory) / path;
        // RTLD_GLOBAL: a plugin may use another's symbols; its static
        // registration objects run here.
        if (dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL) == nullptr)
          {
            const char *why = dlerror();
            throw InputError(where + ": entry 'Additional shared libraries': cannot load '" + path.string() +
                             "': " + (why ? why : "unknown reason"));
          }
      }
  }
} // namespace anvil
