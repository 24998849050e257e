// SPDX-License-Identifier: BSD-3-Clause
// The CSV reader's fast path for plain decimals (src/io/text.hpp).
#include "text.hpp"

#include <cstdint>

namespace geaware::io::detail {
namespace {

// The exactly representable powers of ten 10^0 … 10^22.
constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                   1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

}  // namespace

// A plain decimal [-]digits[.digits] of at most 15 digits (what loggers write), parsed to the
// same double std::from_chars gives: the digits as an integer m < 10^15 < 2^53 and the decimal
// places e ≤ 15 are both exact doubles, so m / 10^e is one correctly rounded division (Clinger's
// fast path, which from_chars takes for these too). False for anything else (exponents, more
// digits, inf, nan, malformed text), which from_chars then parses or refuses.
bool parsePlainDecimal(const char* first, const char* last, double& out) {
  const char* p = first;
  const bool negative = p != last && *p == '-';
  if (negative) ++p;
  std::uint64_t m = 0;
  int digits = 0;
  int places = 0;
  const char* const int_start = p;
  while (p != last && static_cast<unsigned>(*p - '0') < 10U) m = 10 * m + static_cast<unsigned>(*p++ - '0');
  digits = static_cast<int>(p - int_start);
  if (digits == 0) return false;
  if (p != last && *p == '.') {
    const char* const frac_start = ++p;
    while (p != last && static_cast<unsigned>(*p - '0') < 10U) m = 10 * m + static_cast<unsigned>(*p++ - '0');
    places = static_cast<int>(p - frac_start);
    if (places == 0) return false;
    digits += places;
  }
  if (p != last || digits > 15) return false;  // (a longer m may have overflowed: not used)
  const double v = static_cast<double>(m) / kPowersOfTen[places];
  out = negative ? -v : v;
  return true;
}

}  // namespace geaware::io::detail
