#include <anvil/utilities/python_script.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace anvil
{
  std::string shell_quote(const std::string &s)
  {
    std::string q = "'";
    for (const char c : s)
      q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  }


  bool run_python_script(const std::string &name,
                         const std::string &arguments,
                         const std::string &log,
                         std::string       &message)
  {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path  script = fs::read_symlink("/proc/self/exe", ec).parent_path() / name;
    if (ec || !fs::exists(script))
      {
        message = name + " is not beside the executable";
        return false;
      }
    const std::string python  = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const std::string command =
      python + " " + shell_quote(script.string()) + " " + arguments + " > " + shell_quote(log) + " 2>&1";
    const int         status  = std::system(command.c_str());
    std::ifstream     in(log);
    std::string       line;
    message.clear();
    while (std::getline(in, line))
      if (!line.empty())
        message = line;
    if (message.empty())
      message = "the plotting script failed";
    return status == 0;
  }
} // namespace anvil
