/**
 * @file
 * Errors in user input: one clear line, a non-zero exit.
 */
#pragma once

#include <deal.II/base/exceptions.h>

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
   * The message a deal.II exception carries, without the source location
   * decoration, folded onto one line.
   */
  std::string one_line_message(const dealii::ExceptionBase &e);

  /** Fold whitespace runs (including newlines) of @p text to single spaces. */
  std::string fold_whitespace(const std::string &text);
} // namespace anvil
