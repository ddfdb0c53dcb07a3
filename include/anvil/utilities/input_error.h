/**
 * @file
 * Errors in user input: one clear line, a non-zero exit.
 */
#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/base/tensor.h>

#include <stdexcept>
#include <string>

namespace anvil
{
  /**
   * An error the user can act on: which file, which entry, what is wrong,
   * what is allowed. main() prints it as one line and exits with status 2.
   */
  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * A numerical failure during the run (inverted element, NaN, energy
   * growth). main() prints it as one line and exits with status 3.
   */
  class NumericalFailure : public std::runtime_error
  {
  public:
    explicit NumericalFailure(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * The run was asked to stop (SIGTERM, SIGINT) and wrote a checkpoint.
   * main() prints it as one line and exits with status 5.
   */
  class Interrupted : public std::runtime_error
  {
  public:
    explicit Interrupted(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /** Catch SIGTERM and SIGINT: the run checkpoints and stops at the next
      step instead of dying mid-write. */
  void install_stop_handler();
  /** Whether SIGTERM or SIGINT arrived. */
  bool stop_signal_received();
  /** What the handler does (async-signal-safe). */
  void raise_stop_flag();

  /**
   * The message a deal.II exception carries, without the source location
   * decoration, folded onto one line.
   */
  std::string one_line_message(const dealii::ExceptionBase &e);

  /**
   * The three numbers of a comma-separated entry 'x, y, z' (@p text, read
   * from entry @p entry of @p where): an InputError naming them if there
   * are not three finite numbers.
   */
  dealii::Tensor<1, 3> three_numbers(const std::string &text, const std::string &entry,
                                     const std::string &where);

  /**
   * Before a scene allocates @p count @p items of about @p bytes_each
   * bytes: an InputError naming @p where and the entries (@p what) if they
   * would not fit in this machine's memory, or if @p count exceeds the
   * 32-bit indices deal.II and Anvil use (or is not finite).
   */
  void check_size(const std::string &where, const std::string &what, const std::string &items,
                  double count, double bytes_each);

  /**
   * A message fit to print on one line: bytes that are not printable
   * become '?', and a run of more than 120 characters without a space (a
   * value pasted whole into the message) keeps its first 80 and last 30
   * characters around "...", a line quoted whole between '<' and '>'
   * keeps its first 100 and last 40, and the whole message is at most 600
   * characters (its first 420 and last 170 around " ... ").
   */
  std::string printable_excerpt(const std::string &message);

  /** Fold whitespace runs (including newlines) of @p text to single spaces. */
  std::string fold_whitespace(const std::string &text);
} // namespace anvil
