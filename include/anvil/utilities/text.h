/**
 * @file
 * Small text helpers for the run's summaries.
 */
#pragma once

#include <string>

namespace anvil
{
  /** The strings of @p items one after the other, with @p separator
      between two of them. */
  template <typename Container>
  std::string join(const Container &items, const std::string &separator = "; ")
  {
    std::string s;
    for (const auto &item : items)
      s += (s.empty() ? "" : separator) + item;
    return s;
  }

  /** @p s without the blanks, tabs and line ends around it. */
  inline std::string trim(const std::string &s)
  {
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
      return "";
    return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
  }
} // namespace anvil
