// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/control/controller_params.hpp"

#include <cmath>
#include <string>

#include "controller_internal.hpp"
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

namespace {

/// The ranges of geaware's additions (docs/controller.md, "Parameters").
void validateAdditions(const ControllerParams& p, model::FieldChecker& c) {
  using enum model::LowerBound;
  c.range("dob_time_constant_s", p.dob_time_constant_s, 0.0, 10.0, kInclusive, "s");
  if (p.dob_time_constant_s > 0.0 && p.acceleration != AccelerationCompensation::kModel &&
      p.acceleration != AccelerationCompensation::kNone) {
    c.fail("dob_time_constant_s", formatValue(p.dob_time_constant_s),
           std::string("0 with acceleration '") + toString(p.acceleration) +
               "' (it measures or learns the force itself): the disturbance feed-forward needs "
               "'model' or 'none'");
  }
  c.range("dob_limit_mps2", p.dob_limit_mps2, 0.0, 20.0, kExclusive, "m/s²");
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i) {
    const std::string field = std::string("k_i_per_s3.") + axes[i];
    const double bound = p.k_p_per_s2[i] * p.k_v_per_s[i];
    const double k_i = p.k_i_per_s3[i];
    if (!(std::isfinite(k_i) && k_i >= 0.0 && (k_i == 0.0 || k_i < bound))) {
      c.fail(field, formatValue(k_i),
             "a gain in [0, K^P·K^V = " + formatValue(bound) +
                 ") 1/s³ (Routh–Hurwitz for s³ + K^V·s² + K^P·s + K^I)");
    }
  }
  c.range("integral_limit_mps2", p.integral_limit_mps2, 0.0, 20.0, kExclusive, "m/s²");
  c.range("guard_margin_m", p.guard_margin_m, 0.0, 1.0, kInclusive, "m");
  c.range("guard_brake_mps2", p.guard_brake_mps2, 0.0, 50.0, kExclusive, "m/s²");
  c.range("guard_reaction_time_s", p.guard_reaction_time_s, 0.0, 1.0, kInclusive, "s");
  c.range("guard_rate_per_s", p.guard_rate_per_s, 0.0, 100.0, kExclusive, "1/s");
  c.range("rotor_speed_ki_per_s", p.rotor_speed_ki_per_s, 0.0, 100.0, kInclusive, "1/s");
  c.range("rotor_speed_limit_throttle", p.rotor_speed_limit_throttle, 0.0, 1.0, kInclusive, "throttle");
  c.range("rotor_speed_lag_s", p.rotor_speed_lag_s, 0.0, 1.0, kInclusive, "s");
  if (p.learn_ground_effect != GroundEffectLearning::kOff) {
    if (p.acceleration != AccelerationCompensation::kModel) {
      c.fail("learn_ground_effect", "on",
             std::string("off with acceleration '") + toString(p.acceleration) +
                 "': the learned F_G is fed forward by 'model' only");
    }
    for (auto& e : p.learner.validate()) c.fail("learner." + e.field, e.value, e.expected);
    for (auto& e : p.leveling_learner.validate()) c.fail("leveling_learner." + e.field, e.value, e.expected);
  }
  if (p.per_rotor_ground_effect && p.acceleration != AccelerationCompensation::kModel &&
      !detail::usesJPrime(p.torque)) {
    c.fail("per_rotor_ground_effect", "on",
           std::string("off with '") + toString(p.acceleration) + ":" + toString(p.torque) +
               "': the per-rotor terms feed the model's force (acceleration 'model') and torque "
               "(torque 'model' or 'model_indi')");
  }
}

}  // namespace

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
  validateAdditions(*this, c);
  return e;
}

bool ControllerParams::hasAdditions() const noexcept {
  return dob_time_constant_s > 0.0 || k_i_per_s3.any() || clearance_guard || rotor_speed_ki_per_s > 0.0 ||
         learn_ground_effect != GroundEffectLearning::kOff || per_rotor_ground_effect ||
         proximity_compensation;
}

ControllerParams recommendedControllerParams() {
  ControllerParams p;
  p.acceleration = AccelerationCompensation::kModel;
  p.torque = TorqueCompensation::kModelIndi;
  // docs/controller.md, "Why it is stable": τ_d six times faster than the position loop
  // (ω_n = √K^P ≈ 1.7 rad/s) and four times slower than a 25 ms sensor/actuator timing mismatch.
  p.dob_time_constant_s = 0.1;
  p.dob_limit_mps2 = 3.0;
  // s³ + K^V·s² + K^P·s + K^I = (s + 0.5)·(s² + 2s + 2) with K^P = 3, K^V = 2.5, K^I = 1.
  p.k_i_per_s3 = Eigen::Vector3d::Constant(1.0);
  p.integral_limit_mps2 = 1.0;
  p.clearance_guard = true;
  p.guard_margin_m = 0.01;
  p.guard_brake_mps2 = 2.0;
  p.guard_reaction_time_s = 0.05;
  p.guard_rate_per_s = 4.0;
  // docs/controller.md §4: K_n = 15 /s crosses over below the motor pole (33 rad/s) with ≈ 57° of
  // phase margin; ±0.3 throttle covers a 25 % voltage sag at hover.
  p.rotor_speed_ki_per_s = 15.0;
  p.rotor_speed_limit_throttle = 0.3;
  p.rotor_speed_lag_s = 0.04;
  // Issue 13 item 4: the ceiling and wall feed-forward; nothing without a surface in a beam.
  p.proximity_compensation = true;
  return p;
}

namespace {

/// Whether `p`'s switches and additions are those of `q` (gains and rates aside).
bool sameConfiguration(const ControllerParams& p, const ControllerParams& q) {
  return p.acceleration == q.acceleration && p.torque == q.torque &&
         p.dob_time_constant_s == q.dob_time_constant_s && p.dob_limit_mps2 == q.dob_limit_mps2 &&
         p.k_i_per_s3 == q.k_i_per_s3 && p.integral_limit_mps2 == q.integral_limit_mps2 &&
         p.clearance_guard == q.clearance_guard && p.guard_margin_m == q.guard_margin_m &&
         p.guard_brake_mps2 == q.guard_brake_mps2 &&
         p.guard_reaction_time_s == q.guard_reaction_time_s && p.guard_rate_per_s == q.guard_rate_per_s &&
         p.rotor_speed_ki_per_s == q.rotor_speed_ki_per_s &&
         p.rotor_speed_limit_throttle == q.rotor_speed_limit_throttle && p.rotor_speed_lag_s == q.rotor_speed_lag_s &&
         p.learn_ground_effect == q.learn_ground_effect &&
         p.per_rotor_ground_effect == q.per_rotor_ground_effect &&
         p.proximity_compensation == q.proximity_compensation;
}

/// Copies `q`'s switches and additions into `p`.
void setConfiguration(ControllerParams& p, const ControllerParams& q) {
  p.acceleration = q.acceleration;
  p.torque = q.torque;
  p.dob_time_constant_s = q.dob_time_constant_s;
  p.dob_limit_mps2 = q.dob_limit_mps2;
  p.k_i_per_s3 = q.k_i_per_s3;
  p.integral_limit_mps2 = q.integral_limit_mps2;
  p.clearance_guard = q.clearance_guard;
  p.guard_margin_m = q.guard_margin_m;
  p.guard_brake_mps2 = q.guard_brake_mps2;
  p.guard_reaction_time_s = q.guard_reaction_time_s;
  p.guard_rate_per_s = q.guard_rate_per_s;
  p.rotor_speed_ki_per_s = q.rotor_speed_ki_per_s;
  p.rotor_speed_limit_throttle = q.rotor_speed_limit_throttle;
  p.rotor_speed_lag_s = q.rotor_speed_lag_s;
  p.learn_ground_effect = q.learn_ground_effect;
  p.per_rotor_ground_effect = q.per_rotor_ground_effect;
  p.proximity_compensation = q.proximity_compensation;
}

}  // namespace

std::string configurationName(const ControllerParams& p) {
  // Suffixes for the switches that extend any configuration: "+rotors", then "+learn(0)".
  const char* learn = p.learn_ground_effect == GroundEffectLearning::kFromVehicle   ? "+learn"
                      : p.learn_ground_effect == GroundEffectLearning::kFromNothing ? "+learn0"
                                                                                     : "";
  const std::string suffix = std::string(p.per_rotor_ground_effect ? "+rotors" : "") + learn;
  ControllerParams plain = p;
  plain.learn_ground_effect = GroundEffectLearning::kOff;
  plain.per_rotor_ground_effect = false;
  if (sameConfiguration(plain, recommendedControllerParams())) return "recommended" + suffix;
  std::string name = std::string(toString(p.acceleration)) + ":" + toString(p.torque);
  if (p.dob_time_constant_s > 0.0) name += "+dob";
  if (p.k_i_per_s3.any()) name += "+integral";
  if (p.clearance_guard) name += "+guard";
  if (p.rotor_speed_ki_per_s > 0.0) name += "+speedloop";
  if (p.proximity_compensation) name += "+proximity";
  return name + suffix;
}

bool parseConfiguration(const std::string& text_with_switches, ControllerParams& p) {
  // Trailing switches, in this order: "+rotors" (per-rotor ground effect), then "+learn" /
  // "+learn0" (F_G learned in flight, from the vehicle file's or from none).
  std::string text = text_with_switches;
  GroundEffectLearning learn = GroundEffectLearning::kOff;
  const auto strip = [&](const std::string& suffix) {
    const bool ends = text.size() > suffix.size() &&
                      text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
    if (ends) text.resize(text.size() - suffix.size());
    return ends;
  };
  if (strip("+learn0")) {
    learn = GroundEffectLearning::kFromNothing;
  } else if (strip("+learn")) {
    learn = GroundEffectLearning::kFromVehicle;
  }
  const bool rotors = strip("+rotors");
  const bool proximity = strip("+proximity");
  ControllerParams q;  // the paper's row: no additions
  if (text == "recommended") {
    if (proximity) return false;  // recommended has it
    q = recommendedControllerParams();
  } else {
    q.proximity_compensation = proximity;
    const auto colon = text.find(':');
    if (colon == std::string::npos || !parse(text.substr(0, colon), q.acceleration) ||
        !parse(text.substr(colon + 1), q.torque)) {
      return false;
    }
  }
  q.learn_ground_effect = learn;
  q.per_rotor_ground_effect = rotors;
  setConfiguration(p, q);
  return true;
}

}  // namespace geaware::control
