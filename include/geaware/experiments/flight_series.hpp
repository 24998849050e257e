// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Time series of one flight for the reports of `fly` and the campaign (trajectory, errors, attitude error,
// rotor speeds, torques), decimated to keep the page light: one point every `stride` control
// ticks (every 4th: 50 Hz at the 200 Hz control rate). A FlightObserver that reserves its memory
// up front and never allocates inside the loop.

#include <array>
#include <cstddef>
#include <vector>

#include "geaware/experiments/flight.hpp"

namespace geaware::experiments {

struct FlightSeries {
  std::vector<double> t_s;                    ///< trajectory time [s] (negative: start hover)
  std::array<std::vector<double>, 3> ref_m;   ///< reference position x, y, z [m]
  std::array<std::vector<double>, 3> true_m;  ///< true position x, y, z [m]
  std::vector<double> err_cm;                 ///< ‖reference − truth‖ [cm]
  std::vector<double> err_z_cm;               ///< reference z − true z [cm]
  std::vector<double> h_true_m;               ///< true rotor-plane height [m]
  std::vector<double> h_meas_m;               ///< ranger height handed to the controller [m] (NaN invalid)
  std::vector<double> att_err_deg;            ///< desired vs true attitude [deg] (NaN inactive)
  std::array<std::vector<double>, 4> n_rpm;   ///< true rotor speeds, mixer order [rpm]
  std::array<std::vector<double>, 3> tau_des_Nm;  ///< torque command, body [N·m]
  std::array<std::vector<double>, 3> tau_hat_Nm;  ///< filtered τ̂_B from the rotor speeds [N·m]

  [[nodiscard]] std::size_t size() const noexcept { return t_s.size(); }
};

class SeriesCollector final : public FlightObserver {
 public:
  /// Room for a flight of `ticks` control ticks; points beyond it are dropped.
  SeriesCollector(std::size_t ticks, int stride);
  void onTick(const FlightTick& tick) noexcept override;
  [[nodiscard]] const FlightSeries& series() const noexcept { return s_; }
  [[nodiscard]] FlightSeries take() noexcept { return std::move(s_); }

 private:
  FlightSeries s_;
  int stride_;
  std::size_t ticks_ = 0;
};

/// Ticks a flight of the scenario has (start hover + trajectory + settle, at the control
/// rate), with a margin.
[[nodiscard]] std::size_t expectedTicks(const FlightScenario& scenario);

}  // namespace geaware::experiments
