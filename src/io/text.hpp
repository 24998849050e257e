#pragma once
// Private to io/: small text helpers the line-based readers share.

#include <string_view>

namespace geaware::io::detail {

/// `s` without leading and trailing spaces, tabs and carriage returns.
inline std::string_view trimBlanks(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

}  // namespace geaware::io::detail
