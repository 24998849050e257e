// SPDX-License-Identifier: BSD-3-Clause
// Sweep files: experiments::parseSweepYaml, what experiments::loadSweepFile (`geaware sweep`,
// geaware.sweep) runs on a file's bytes, before any flight. Relative paths in the sweep
// (vehicle, world, scenario and controller-parameter files) resolve against fuzz/data/, which
// holds one valid file of each kind, so the fuzzer reaches the readers a sweep calls; the keys
// and their file names are built too, as every run builds them.
//
// Flights are bounded to 120 s here (the sweep key max_sim_s), as in fuzz_scenario_file: the
// scenarios' validation samples every control tick, a cost that grows with the flight's length
// by design; longer flights reach the duration check's refusal instead.
#include "fuzz_support.hpp"
#include "geaware/experiments/sweep.hpp"

namespace {
constexpr double kMaxSimS = 120.0;  // [s]
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    const auto spec = geaware::experiments::parseSweepYaml(geaware::fuzz::text(data, size),
                                                           std::string(geaware::fuzz::kSource),
                                                           GEAWARE_FUZZ_DATA_DIR, kMaxSimS);
    // The keys of a small sweep (a large one is only counted: 10^6 keys is seconds per input).
    if (spec.flights() <= 4096) {
      for (const auto& key : geaware::experiments::sweepKeys(spec)) {
        (void)geaware::experiments::sweepKeyFileName(key);
        (void)geaware::experiments::parseSweepKey(spec, key);
      }
    }
  });
  return 0;
}
