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
} // namespace anvil
