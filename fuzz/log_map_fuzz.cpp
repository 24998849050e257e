// SPDX-License-Identifier: BSD-3-Clause
// Log-map files (`identify flight --map FILE`): io::parseLogMap, what io::loadLogMap runs on a
// file's bytes.
#include "fuzz_support.hpp"
#include "geaware/io/log_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    (void)geaware::io::parseLogMap(std::string(geaware::fuzz::text(data, size)),
                                   std::string(geaware::fuzz::kSource), "fuzz");
  });
  return 0;
}
