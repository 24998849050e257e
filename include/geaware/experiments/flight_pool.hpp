// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Many independent flights on a few threads (the campaign's --jobs). Every flight is a pure
// function of its scenario (experiments/flight.hpp: same scenario and seed → bit-identical
// result), each job has its own observer, and results are stored by job index, so the results
// are identical for any number of threads and any scheduling.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "geaware/experiments/flight.hpp"

namespace geaware::experiments {

struct FlightJob {
  FlightScenario scenario;
  /// Sees this flight's ticks only (owned by the caller, outlives the call); may be null.
  FlightObserver* observer = nullptr;
  std::string label;  ///< for progress, e.g. "exp 5 seed 3"
};

/// Called after each flight, from the thread that flew it, one call at a time.
using FlightProgress = std::function<void(std::size_t done, std::size_t total,
                                          const FlightJob& job, const FlightResult& result)>;

/// Number of threads `requested` means: itself when ≥ 1, else the hardware's (at least 1).
[[nodiscard]] int resolveThreads(int requested) noexcept;

/// Flies every job on up to `threads` threads (resolveThreads) and returns the results in job
/// order. An exception from a flight (e.g. InvalidScenario) stops the remaining jobs from
/// starting and is rethrown, with the job's label prefixed, once every thread has finished.
[[nodiscard]] std::vector<FlightResult> runFlights(const std::vector<FlightJob>& jobs, int threads,
                                                   const FlightProgress& progress = {});

}  // namespace geaware::experiments
