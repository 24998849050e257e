// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Progress of a long run (a flight of many laps, the campaign, the Neural-Lander training),
// reported through one small interface so that the library says what it is doing and the
// command line decides how (and whether) to show it. The library never prints.

#include <cstddef>
#include <string_view>

#include "geaware/experiments/flight.hpp"

namespace geaware::experiments {

/// Receives what a long run is doing. Implementations must be cheap and must not throw from
/// update() (it is called inside flight loops); calls may come from several threads, but never
/// at the same time (the callers serialise them).
class Progress {
 public:
  virtual ~Progress() = default;
  /// A new stage or an event worth its own line, e.g. "calibration: 412 platform rows".
  virtual void message(std::string_view text) = 0;
  /// `done` of `total` units of the current stage (flights, epochs, simulated seconds); `what`
  /// names the last unit finished.
  virtual void update(double done, double total, std::string_view what) noexcept = 0;
};

/// Reports the simulated time of one flight to a Progress, every `every_ticks` control ticks.
class FlightProgressObserver final : public FlightObserver {
 public:
  FlightProgressObserver(Progress& progress, double duration_s, std::size_t every_ticks = 200)
      : progress_(progress), duration_s_(duration_s), every_(every_ticks == 0 ? 1 : every_ticks) {}
  void onTick(const FlightTick& tick) noexcept override {
    if (ticks_++ % every_ == 0) progress_.update(tick.t_s, duration_s_, "simulated s");
  }
  void finish(const FlightResult& result) override {
    progress_.update(result.simulated_s, duration_s_, "simulated s");
  }

 private:
  Progress& progress_;
  double duration_s_;
  std::size_t every_;
  std::size_t ticks_ = 0;
};

}  // namespace geaware::experiments
