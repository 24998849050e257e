// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/flight_pool.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace geaware::experiments {

int resolveThreads(int requested) noexcept {
  if (requested >= 1) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

std::vector<FlightResult> runFlights(const std::vector<FlightJob>& jobs, int threads,
                                     const FlightProgress& progress) {
  std::vector<FlightResult> results(jobs.size());
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;  // guards `done`, `error` and the progress callback
  std::size_t done = 0;
  std::exception_ptr error;
  std::string error_label;

  auto worker = [&]() {
    for (;;) {
      if (failed.load()) return;
      const std::size_t k = next.fetch_add(1);
      if (k >= jobs.size()) return;
      try {
        results[k] = runFlight(jobs[k].scenario, jobs[k].observer);
        const std::lock_guard<std::mutex> lock(mutex);
        ++done;
        if (progress) progress(done, jobs.size(), jobs[k], results[k]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) {
          error = std::current_exception();
          error_label = jobs[k].label;
        }
        failed.store(true);
        return;
      }
    }
  };

  const auto n = static_cast<std::size_t>(
      std::min<std::size_t>(static_cast<std::size_t>(resolveThreads(threads)), jobs.size()));
  if (n <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(n);
    for (std::size_t i = 0; i < n; ++i) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      throw std::runtime_error(error_label + ": " + e.what());
    }
  }
  return results;
}

}  // namespace geaware::experiments
