// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The land detector (issue 13 item 5), in the spirit of PX4's multicopter land detector: from
// what the controller sees only (the ranger's rotor-plane height, the estimate, the reference),
// it decides that the vehicle stands on its gear and takes the motors down.
//
// Armed only while landing: the reference's height above the ground, ref_z − (p̂_z − h), is at
// or below the gear's height + height_margin_m (the reference has reached the surface). Then
// "landed" when, for confirm_s without a break,
//   h ≤ gear height + height_margin_m   (the ranger sees the rotor plane at the gear's height)
//   |v̂_z| ≤ max_vertical_speed_mps      (the estimate has stopped sinking)
// From "landed" on, the throttle scale falls linearly from 1 to 0 over spool_down_s and stays
// there (the flight controller disarms; the ESC idles). It never re-arms within one flight.
//
// No allocation, no I/O; one update per control tick.

#include <vector>

#include "geaware/control/controller.hpp"
#include "geaware/model/field_check.hpp"

namespace geaware::control {

struct LandDetectorParams {
  double height_margin_m = 0.01;         ///< above the gear's height that still counts as down [m]
  double max_vertical_speed_mps = 0.05;  ///< estimated |v_z| below which the vehicle stands [m/s]
  double confirm_s = 0.2;                ///< both conditions held this long [s]
  double spool_down_s = 0.3;             ///< throttle ramp to zero after the verdict [s]

  /// Every invalid field (finite, ≥ 0; margin and speed > 0); empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// Before a take-off (a flight that starts standing on the gear): whether the reference still
/// stands on the ground, from the controller's view — not rising (v_z ≤ 1 cm/s) and, with a
/// valid ranger height, at most `margin_m` above the gear's height over the ground under the
/// vehicle. The flight controller keeps the motors at idle until it does not (armed, not yet
/// flying), as autopilots do: a position loop asked to hover at the gear's exact height would
/// hop on the cushion.
[[nodiscard]] bool referenceOnTheGround(const ControllerInput& in, double gear_height_m,
                                        double margin_m) noexcept;

class LandDetector {
 public:
  /// `gear_height_m`: the rotor-plane height standing on the gear (the vehicle file's
  /// min_rotor_plane_height_m); `rate_hz`: the control rate.
  LandDetector(double gear_height_m, const LandDetectorParams& params, double rate_hz);

  /// One control tick: the controller's input of this tick. Returns the throttle scale in [0, 1].
  [[nodiscard]] double update(const ControllerInput& in) noexcept;

  [[nodiscard]] bool landed() const noexcept { return landed_; }
  /// Controller time of the verdict [s] (NaN before).
  [[nodiscard]] double landedAt() const noexcept { return landed_t_s_; }

 private:
  double gear_height_m_;
  LandDetectorParams params_;
  double dt_s_;
  double held_s_ = 0.0;
  bool landed_ = false;
  double landed_t_s_;
  double scale_ = 1.0;
};

}  // namespace geaware::control
