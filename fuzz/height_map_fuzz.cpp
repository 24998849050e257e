// SPDX-License-Identifier: BSD-3-Clause
// Height-map files: io::parseHeightMapText, what io::readHeightMapFile runs on a file's bytes.
#include "fuzz_support.hpp"
#include "geaware/io/height_map_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    (void)geaware::io::parseHeightMapText(geaware::fuzz::text(data, size),
                                          std::string(geaware::fuzz::kSource));
  });
  return 0;
}
