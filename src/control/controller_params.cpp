#include "geaware/control/controller_params.hpp"

#include <cmath>
#include <string>

#include "geaware/model/field_check.hpp"

namespace geaware::control {

using model::formatValue;

const char* toString(AccelerationCompensation c) noexcept {
  switch (c) {
    case AccelerationCompensation::kNone: return "none";
    case AccelerationCompensation::kIndi: return "indi";
    case AccelerationCompensation::kNeural: return "neural";
    case AccelerationCompensation::kModel: return "model";
  }
  return "?";
}

const char* toString(TorqueCompensation c) noexcept {
  switch (c) {
    case TorqueCompensation::kNone: return "none";
    case TorqueCompensation::kModel: return "model";
    case TorqueCompensation::kIndi: return "indi";
    case TorqueCompensation::kModelIndi: return "model_indi";
  }
  return "?";
}

bool parse(const std::string& text, AccelerationCompensation& out) noexcept {
  for (auto c : {AccelerationCompensation::kNone, AccelerationCompensation::kIndi,
                 AccelerationCompensation::kNeural, AccelerationCompensation::kModel}) {
    if (text == toString(c)) {
      out = c;
      return true;
    }
  }
  return false;
}

bool parse(const std::string& text, TorqueCompensation& out) noexcept {
  for (auto c : {TorqueCompensation::kNone, TorqueCompensation::kModel, TorqueCompensation::kIndi,
                 TorqueCompensation::kModelIndi}) {
    if (text == toString(c)) {
      out = c;
      return true;
    }
  }
  return false;
}

std::vector<model::FieldError> ControllerParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e);
  using enum model::LowerBound;
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i) {
    const std::string a(1, axes[i]);
    c.range("k_p_per_s2." + a, k_p_per_s2[i], 0.0, 1e4, kExclusive);
    c.range("k_v_per_s." + a, k_v_per_s[i], 0.0, 1e4, kExclusive);
    c.range("k_xi_per_s." + a, k_xi_per_s[i], 0.0, 1e4, kExclusive);
    c.range("k_w_per_s." + a, k_w_per_s[i], 0.0, 1e4, kExclusive);
  }
  c.range("rate_hz", rate_hz, 0.0, 1e5, kExclusive);
  c.range("max_tilt_rad", max_tilt_rad, 0.0, 1.5, kExclusive);
  if (!(std::isfinite(filter_cutoff_hz) && filter_cutoff_hz > 0.0 && filter_cutoff_hz < 0.5 * rate_hz)) {
    c.fail("filter_cutoff_hz", formatValue(filter_cutoff_hz),
           "a cut-off in (0, rate_hz/2 = " + formatValue(0.5 * rate_hz) + ") Hz");
  }
  c.range("thrust_pi_kp", thrust_pi_kp, 0.0, 10.0, kInclusive);
  c.range("thrust_pi_ki", thrust_pi_ki, 0.0, 10.0, kInclusive);
  if (!(std::isfinite(thrust_pi_limit) && thrust_pi_limit >= 0.0 && thrust_pi_limit <= 0.5)) {
    c.fail("thrust_pi_limit", formatValue(thrust_pi_limit), "a throttle fraction in [0, 0.5]");
  }
  c.integerRange("neural_iterations", neural_iterations, 1, 10);
  return e;
}

}  // namespace geaware::control
