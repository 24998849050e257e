#pragma once
// Minimal JSON text helpers for the commands' `--json` outputs (flat objects of numbers and
// strings; no JSON library needed for writing them).

#include <cstdio>
#include <string>
#include <string_view>

namespace geaware::io {

/// `s` as a JSON string literal: quotes and backslashes escaped, control characters as \uXXXX.
[[nodiscard]] inline std::string jsonString(std::string_view s) {
  std::string out = "\"";
  out.reserve(s.size() + 2);
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + '"';
}

}  // namespace geaware::io
