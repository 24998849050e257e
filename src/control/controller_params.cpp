#include "geaware/control/controller_params.hpp"

#include <cmath>
#include <cstdio>

namespace geaware::control {
namespace {

std::string show(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

void positive(std::vector<model::FieldError>& out, const std::string& field, double v, double hi) {
  if (!(std::isfinite(v) && v > 0.0 && v <= hi)) {
    out.push_back({field, show(v), "a finite number in (0, " + show(hi) + "]"});
  }
}

}  // namespace

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
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i) {
    const std::string a(1, axes[i]);
    positive(e, "k_p_per_s2." + a, k_p_per_s2[i], 1e4);
    positive(e, "k_v_per_s." + a, k_v_per_s[i], 1e4);
    positive(e, "k_xi_per_s." + a, k_xi_per_s[i], 1e4);
    positive(e, "k_w_per_s." + a, k_w_per_s[i], 1e4);
  }
  positive(e, "rate_hz", rate_hz, 1e5);
  positive(e, "max_tilt_rad", max_tilt_rad, 1.5);
  if (!(std::isfinite(filter_cutoff_hz) && filter_cutoff_hz > 0.0 && filter_cutoff_hz < 0.5 * rate_hz)) {
    e.push_back({"filter_cutoff_hz", show(filter_cutoff_hz),
                 "a cut-off in (0, rate_hz/2 = " + show(0.5 * rate_hz) + ") Hz"});
  }
  for (auto [field, v] : {std::pair{"thrust_pi_kp", thrust_pi_kp}, std::pair{"thrust_pi_ki", thrust_pi_ki}}) {
    if (!(std::isfinite(v) && v >= 0.0 && v <= 10.0)) e.push_back({field, show(v), "a finite number in [0, 10]"});
  }
  if (!(std::isfinite(thrust_pi_limit) && thrust_pi_limit >= 0.0 && thrust_pi_limit <= 0.5)) {
    e.push_back({"thrust_pi_limit", show(thrust_pi_limit), "a throttle fraction in [0, 0.5]"});
  }
  if (neural_iterations < 1 || neural_iterations > 10) {
    e.push_back({"neural_iterations", std::to_string(neural_iterations), "an integer in [1, 10]"});
  }
  return e;
}

}  // namespace geaware::control
