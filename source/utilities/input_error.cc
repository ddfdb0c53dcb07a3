#include <anvil/utilities/input_error.h>

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
