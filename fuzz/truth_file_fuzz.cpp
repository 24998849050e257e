// SPDX-License-Identifier: BSD-3-Clause
// Truth files: io::parseTruthYaml, what io::loadTruthFile runs on a file's bytes.
#include "fuzz_support.hpp"
#include "geaware/io/truth_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    (void)geaware::io::parseTruthYaml(geaware::fuzz::text(data, size),
                                      std::string(geaware::fuzz::kSource));
  });
  return 0;
}
