// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A batch of stepped worlds (experiments/stepped_world.hpp), one per vehicle, each with its own
// scenario copy and seed, stepped one control period at a time with the caller's throttles on a
// pool of threads; the observation of every vehicle as one row of doubles. Vehicles are
// independent, so the result does not depend on the number of threads. Plain C++ (no Python):
// sim_bindings.cpp makes geaware.Sim and geaware.VecSim of it.

#include <array>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/stepped_world.hpp"

namespace geaware::python {

/// Runs f(i) for every i in [0, n) on `threads` threads (the caller's included), each thread
/// a fixed contiguous share. Threads are started once and reused.
class StepPool {
 public:
  explicit StepPool(int threads);
  ~StepPool();
  StepPool(const StepPool&) = delete;
  StepPool& operator=(const StepPool&) = delete;
  void run(std::size_t n, const std::function<void(std::size_t)>& f);
  [[nodiscard]] int threads() const noexcept { return static_cast<int>(workers_.size()) + 1; }

 private:
  void work(int w);
  void share(int w, std::size_t n);
  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable start_, done_;
  const std::function<void(std::size_t)>* f_ = nullptr;
  std::size_t n_ = 0;
  std::uint64_t generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
};

/// One named part of an observation row: `width` doubles from `offset`.
struct ObsField {
  std::string name;
  std::size_t offset = 0;
  std::size_t width = 1;
  std::string doc;
};

class WorldBatch {
 public:
  /// One vehicle per seed, each flying a copy of `scenario` with its seed. Throws
  /// (std::invalid_argument, experiments::InvalidScenario) what SteppedWorld refuses.
  WorldBatch(const experiments::FlightScenario& scenario, const std::vector<std::uint64_t>& seeds,
             int threads);

  [[nodiscard]] std::size_t size() const noexcept { return slots_.size(); }
  [[nodiscard]] std::size_t obsWidth() const noexcept { return width_; }
  [[nodiscard]] const std::vector<ObsField>& fields() const noexcept { return fields_; }
  [[nodiscard]] double controlPeriod_s() const noexcept { return period_s_; }
  [[nodiscard]] int threads() const noexcept { return pool_.threads(); }

  /// Restarts vehicle i with `seed` (a new stepped world at the start of the scenario).
  void reset(std::size_t i, std::uint64_t seed);
  /// One control period for every vehicle not done, vehicle i with throttles[4i … 4i+3]
  /// (finite; the motors clamp to [0, 1]). Vehicles that are done keep their last observation.
  void step(const double* throttles);
  /// The observations, size() rows of obsWidth() doubles.
  [[nodiscard]] const std::vector<double>& observations() const noexcept { return obs_; }
  [[nodiscard]] bool done(std::size_t i) const noexcept { return slots_[i].done; }
  [[nodiscard]] bool crashed(std::size_t i) const noexcept { return slots_[i].world->crashed(); }
  [[nodiscard]] std::uint64_t seed(std::size_t i) const noexcept { return slots_[i].scenario.seed; }
  /// Vehicle i's result so far (tracking against its reference, the crash).
  [[nodiscard]] experiments::FlightResult result(std::size_t i) { return slots_[i].world->finish(0.0); }

 private:
  struct Slot {
    experiments::FlightScenario scenario;
    std::unique_ptr<experiments::SteppedWorld> world;
    bool done = false;
  };
  void stepOne(std::size_t i, const std::array<double, 4>& throttle) noexcept;
  void record(std::size_t i, const sim::SensorReadings& r) noexcept;
  void recordTick(std::size_t i) noexcept;

  std::vector<Slot> slots_;
  std::vector<ObsField> fields_;
  std::size_t width_ = 0;
  int ranger_zones_ = 0;
  double period_s_ = 0.0;
  std::vector<double> obs_;
  StepPool pool_;
};

}  // namespace geaware::python
