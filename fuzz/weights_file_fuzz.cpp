// SPDX-License-Identifier: BSD-3-Clause
// Weight files of the residual network: neural::parseWeightsYaml, what neural::loadWeights
// (fly --neural-weights, the bench cache) runs on a file's bytes: io::parseWeightsFile and the
// network's own checks.
#include "fuzz_support.hpp"
#include "geaware/neural/weights_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    (void)geaware::neural::parseWeightsYaml(geaware::fuzz::text(data, size),
                                            std::string(geaware::fuzz::kSource));
  });
  return 0;
}
