/**
 * @file
 * The plotting scripts beside the executable (anvil_plot.py,
 * anvil_study_plot.py), run with Debian's Python when there is one (it sees
 * Debian's python3-matplotlib).
 */
#pragma once

#include <string>

namespace anvil
{
  /**
   * Run the script @p name that sits beside the anvil executable with the
   * (already quoted) @p arguments, its output to @p log. Returns true on
   * success; @p message is the last line the script printed (or why it could
   * not run).
   */
  /** @p s as one word of /bin/sh (single-quoted, quotes inside escaped). */
  std::string shell_quote(const std::string &s);

  bool run_python_script(const std::string &name,
                         const std::string &arguments,
                         const std::string &log,
                         std::string       &message);
} // namespace anvil
