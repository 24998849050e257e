// SPDX-License-Identifier: BSD-3-Clause
// Vehicle files: io::parseVehicleYaml, what io::loadVehicleFile runs on a file's bytes.
#include "fuzz_support.hpp"
#include "geaware/io/vehicle_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    (void)geaware::io::parseVehicleYaml(geaware::fuzz::text(data, size),
                                        std::string(geaware::fuzz::kSource));
  });
  return 0;
}
