// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What every fuzz target checks besides the sanitizers (docs/reliability.md, "Fuzzing"): a
// parser given any bytes either returns or throws an exception derived from std::exception
// whose message starts with the name of the input (the CLI prints it as "geaware: error: …",
// and every error must name the file). Anything else — another exception, a message that does
// not name the input (a raw yaml-cpp or std::out_of_range text) — aborts, which libFuzzer
// reports as a crash with the input that caused it.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>
#include <typeinfo>

namespace geaware::fuzz {

/// The name every target gives its input; errors must start with it.
inline constexpr std::string_view kSource = "fuzz-input";

/// libFuzzer's bytes as text.
inline std::string_view text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Runs `parse`; aborts on an exception that is not a std::exception naming kSource first.
template <typename Parse>
void expectNamedErrors(Parse&& parse) {
  try {
    parse();
  } catch (const std::exception& e) {
    if (std::string_view(e.what()).starts_with(kSource)) return;
    std::fprintf(stderr, "fuzz: an error that does not name the input (%s): %s\n", typeid(e).name(),
                 e.what());
    std::abort();
  }
}

}  // namespace geaware::fuzz
