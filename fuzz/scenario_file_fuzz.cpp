// SPDX-License-Identifier: BSD-3-Clause
// Scenario files: experiments::parseScenarioYaml, what experiments::loadScenarioFile (fly
// --scenario) runs on a file's bytes. Relative paths in the scenario (vehicle, truth, height
// map) resolve against fuzz/data/, which holds one valid file of each kind, so the fuzzer
// reaches the readers a scenario calls.
//
// Flights are bounded to 120 s here (fly --max-sim-s 120): validation samples the trajectory at
// every control tick to check the motors can fly it, a cost that grows with the flight's length
// by design (0.7 s in Release for a 50-minute descent, 25 s under the sanitizers, which the 10 s
// timeout reported). Longer flights are refused by the duration check, which the fuzzer reaches.
#include "fuzz_support.hpp"
#include "geaware/experiments/scenario_file.hpp"

namespace {
constexpr double kMaxSimS = 120.0;  // [s]
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    (void)geaware::experiments::parseScenarioYaml(geaware::fuzz::text(data, size),
                                                  std::string(geaware::fuzz::kSource),
                                                  GEAWARE_FUZZ_DATA_DIR, nullptr, kMaxSimS);
  });
  return 0;
}
