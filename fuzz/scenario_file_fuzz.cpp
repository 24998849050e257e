// SPDX-License-Identifier: BSD-3-Clause
// Scenario files: experiments::parseScenarioYaml, what experiments::loadScenarioFile (fly
// --scenario) runs on a file's bytes. Relative paths in the scenario (vehicle, truth, height
// map) resolve against fuzz/data/, which holds one valid file of each kind, so the fuzzer
// reaches the readers a scenario calls.
#include "fuzz_support.hpp"
#include "geaware/experiments/scenario_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    (void)geaware::experiments::parseScenarioYaml(geaware::fuzz::text(data, size),
                                                  std::string(geaware::fuzz::kSource),
                                                  GEAWARE_FUZZ_DATA_DIR);
  });
  return 0;
}
