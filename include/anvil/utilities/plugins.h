/**
 * @file
 * Plugins: shared libraries named in a scene ('Additional shared
 * libraries'), loaded before the scene's entries are declared, so that the
 * material models (and whatever else) they register take part like Anvil's
 * own. doc/extending.md writes one from scratch.
 */
#pragma once

#include <string>

namespace anvil
{
  /**
   * Load each library of the comma-separated @p list (paths relative to
   * @p directory unless absolute). InputError naming @p where and the
   * library when one cannot be loaded.
   */
  void load_shared_libraries(const std::string &list, const std::string &directory, const std::string &where);
} // namespace anvil
