// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Private to io/: small text helpers the line-based readers share.

#include <string>
#include <string_view>

namespace geaware::io::detail {

/// `s` without leading and trailing spaces, tabs and carriage returns.
inline std::string_view trimBlanks(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

/// `s` as echoed in a message: at most `max_chars` bytes, "…" when cut (a cell or value of a
/// hostile file may be up to a line's 1 MiB long).
inline std::string excerpt(std::string_view s, std::size_t max_chars = 80) {
  if (s.size() <= max_chars) return std::string(s);
  return std::string(s.substr(0, max_chars)) + "…";
}

/// A plain decimal [-]digits[.digits] of at most 15 digits, parsed to the same double
/// std::from_chars gives (decimal_text.cpp); false for anything else, which from_chars then
/// parses or refuses.
bool parsePlainDecimal(const char* first, const char* last, double& out);

}  // namespace geaware::io::detail
