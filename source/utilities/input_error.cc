#include <anvil/utilities/input_error.h>

#include <unistd.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <cstdlib>
#include <csignal>

#include <sstream>

namespace anvil
{
  namespace
  {
    volatile std::sig_atomic_t stop_signal = 0;
    void on_stop_signal(int)
    {
      stop_signal = 1;
    }
  } // namespace

  void install_stop_handler()
  {
    std::signal(SIGTERM, on_stop_signal);
    std::signal(SIGINT, on_stop_signal);
  }

  void raise_stop_flag()
  {
    stop_signal = 1;
  }

  bool stop_signal_received()
  {
    return stop_signal != 0;
  }

  dealii::Tensor<1, 3> three_numbers(const std::string &text, const std::string &entry, const std::string &where)
  {
    const auto           parts = dealii::Utilities::split_string_list(text, ',');
    dealii::Tensor<1, 3> x;
    for (unsigned int d = 0; d < 3; ++d)
      {
        char *end = nullptr;
        if (parts.size() != 3 || parts[d].empty() ||
            (x[d] = std::strtod(parts[d].c_str(), &end), *end != '\0') || !std::isfinite(x[d]))
          throw InputError(where + ": entry '" + entry + "' must be three numbers 'x, y, z', not '" + text + "'");
      }
    return x;
  }


  void check_size(const std::string &where,
                  const std::string &what,
                  const std::string &items,
                  const double       count,
                  const double       bytes_each)
  {
    const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    const double limit  = std::min(2147483647., memory > 0 ? memory / bytes_each : 2147483647.);
    if (std::isfinite(count) && count <= limit)
      return;
    std::ostringstream s;
    s.precision(3);
    s << where << ": " << what << " ask for " << count << ' ' << items << "; at most " << limit
      << " fit (" << memory / double(1u << 30) << " GiB of memory, about " << bytes_each
      << " bytes each, 32-bit indices)";
    throw InputError(s.str());
  }


  std::string printable_excerpt(const std::string &message)
  {
    std::string out, word;
    auto        flush = [&]() {
      out += word.size() > 120 ? word.substr(0, 80) + "..." + word.substr(word.size() - 30) : word;
      word.clear();
    };
    for (const char c : fold_whitespace(message))
      if (c == ' ')
        {
          flush();
          out += c;
        }
      else
        word += (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) ? '?' : c;
    flush();
    // A line quoted whole (deal.II's "The line <...>", which may be a long
    // continued line of a stage's changes): its start and its end.
    for (std::size_t open = out.find('<'); open != std::string::npos; open = out.find('<', open + 1))
      {
        const std::size_t close = out.find('>', open);
        if (close == std::string::npos)
          break;
        if (close - open > 160)
          out = out.substr(0, open + 101) + " ... " + out.substr(close - 40);
      }
    // One line of at most 600 characters, however long the paths it names.
    if (out.size() > 600)
      out = out.substr(0, 420) + " ... " + out.substr(out.size() - 170);
    return out;
  }


  std::string fold_whitespace(const std::string &text)
  {
    std::string out;
    bool        in_space = false;
    for (const char c : text)
      {
        if (c == ' ' || c == '\n' || c == '\t' || c == '\r')
          in_space = true;
        else
          {
            if (in_space && !out.empty())
              out += ' ';
            in_space = false;
            out += c;
          }
      }
    return out;
  }


  std::string one_line_message(const dealii::ExceptionBase &e)
  {
    std::ostringstream s;
    e.print_info(s);
    std::string msg = fold_whitespace(s.str());
    // deal.II prefixes the additional information with this phrase.
    const std::string prefix = "Additional information:";
    if (msg.rfind(prefix, 0) == 0)
      msg = msg.substr(prefix.size() + 1);
    return msg;
  }
} // namespace anvil
