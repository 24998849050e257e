// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/control/land_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geaware/model/field_check.hpp"

namespace geaware::control {

std::vector<model::FieldError> LandDetectorParams::validate() const {
  std::vector<model::FieldError> errors;
  model::FieldChecker c(errors);
  constexpr auto kExclusive = model::LowerBound::kExclusive;
  constexpr auto kInclusive = model::LowerBound::kInclusive;
  c.range("height_margin_m", height_margin_m, 0.0, 1.0, kExclusive, "m");
  c.range("max_vertical_speed_mps", max_vertical_speed_mps, 0.0, 10.0, kExclusive, "m/s");
  c.range("confirm_s", confirm_s, 0.0, 10.0, kInclusive, "s");
  c.range("spool_down_s", spool_down_s, 0.0, 10.0, kInclusive, "s");
  return errors;
}

bool referenceOnTheGround(const ControllerInput& in, double gear_height_m, double margin_m) noexcept {
  if (in.reference.v_W.z() > 0.01) return false;
  if (!in.height_valid) return true;
  const double ground_z = in.estimate.p_W.z() - in.height_m;
  return in.reference.p_W.z() - ground_z <= gear_height_m + margin_m;
}

LandDetector::LandDetector(double gear_height_m, const LandDetectorParams& params, double rate_hz)
    : gear_height_m_(gear_height_m),
      params_(params),
      dt_s_(1.0 / rate_hz),
      landed_t_s_(std::numeric_limits<double>::quiet_NaN()) {}

double LandDetector::update(const ControllerInput& in) noexcept {
  if (landed_) {
    scale_ = params_.spool_down_s > 0.0 ? std::max(0.0, scale_ - dt_s_ / params_.spool_down_s) : 0.0;
    return scale_;
  }
  const double floor_m = gear_height_m_ + params_.height_margin_m;
  // The reference's height above the ground under the vehicle, from the controller's own view.
  const double ground_z = in.estimate.p_W.z() - in.height_m;
  const bool landing = in.height_valid && in.reference.p_W.z() - ground_z <= floor_m;
  const bool down = landing && in.height_m <= floor_m &&
                    std::abs(in.estimate.v_W.z()) <= params_.max_vertical_speed_mps;
  held_s_ = down ? held_s_ + dt_s_ : 0.0;
  if (down && held_s_ >= params_.confirm_s - 1e-9) {
    landed_ = true;
    landed_t_s_ = in.t_s;
  }
  return scale_;
}

}  // namespace geaware::control
