// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/control/controller_schema.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "geaware/model/field_check.hpp"

namespace geaware::control {
namespace {

using P = ControllerParams;
using S = model::ParamSpec<P>;
using model::ParamRange;
using enum model::LowerBound;

constexpr ParamRange kGain{0.0, 1e4, kExclusive};

S number(std::string_view key, std::string_view unit, ParamRange range, double& (*get)(P&)) {
  S s;
  s.key = key;
  s.unit = unit;
  s.range = range;
  s.number = get;
  return s;
}

/// Position and attitude gains, one key per axis.
std::vector<S> gainSpecs() {
  return {
      number("position.k_p_per_s2.x", "1/s²", kGain, [](P& p) -> double& { return p.k_p_per_s2[0]; }),
      number("position.k_p_per_s2.y", "1/s²", kGain, [](P& p) -> double& { return p.k_p_per_s2[1]; }),
      number("position.k_p_per_s2.z", "1/s²", kGain, [](P& p) -> double& { return p.k_p_per_s2[2]; }),
      number("position.k_v_per_s.x", "1/s", kGain, [](P& p) -> double& { return p.k_v_per_s[0]; }),
      number("position.k_v_per_s.y", "1/s", kGain, [](P& p) -> double& { return p.k_v_per_s[1]; }),
      number("position.k_v_per_s.z", "1/s", kGain, [](P& p) -> double& { return p.k_v_per_s[2]; }),
      number("attitude.k_xi_per_s.x", "1/s", kGain, [](P& p) -> double& { return p.k_xi_per_s[0]; }),
      number("attitude.k_xi_per_s.y", "1/s", kGain, [](P& p) -> double& { return p.k_xi_per_s[1]; }),
      number("attitude.k_xi_per_s.z", "1/s", kGain, [](P& p) -> double& { return p.k_xi_per_s[2]; }),
      number("attitude.k_w_per_s.x", "1/s", kGain, [](P& p) -> double& { return p.k_w_per_s[0]; }),
      number("attitude.k_w_per_s.y", "1/s", kGain, [](P& p) -> double& { return p.k_w_per_s[1]; }),
      number("attitude.k_w_per_s.z", "1/s", kGain, [](P& p) -> double& { return p.k_w_per_s[2]; }),
      number("attitude.max_tilt_rad", "rad", {0.0, 1.5, kExclusive},
             [](P& p) -> double& { return p.max_tilt_rad; }),
  };
}

/// Rate, filter, thrust correction and geaware's additions.
std::vector<S> loopSpecs() {
  return {
      number("loop.rate_hz", "Hz", {0.0, 1e5, kExclusive}, [](P& p) -> double& { return p.rate_hz; }),
      number("loop.filter_cutoff_hz", "Hz", {0.0, 5e4, kExclusive},
             [](P& p) -> double& { return p.filter_cutoff_hz; }),
      number("thrust_correction.k_p_s2_per_m", "s²/m", {0.0, 10.0, kInclusive},
             [](P& p) -> double& { return p.thrust_pi_kp; }),
      number("thrust_correction.k_i_s_per_m", "s/m", {0.0, 10.0, kInclusive},
             [](P& p) -> double& { return p.thrust_pi_ki; }),
      number("thrust_correction.limit_throttle", "", {0.0, 0.5, kInclusive},
             [](P& p) -> double& { return p.thrust_pi_limit; }),
      number("disturbance_feedforward.time_constant_s", "s", {0.0, 10.0, kInclusive},
             [](P& p) -> double& { return p.dob_time_constant_s; }),
      number("disturbance_feedforward.limit_mps2", "m/s²", {0.0, 20.0, kExclusive},
             [](P& p) -> double& { return p.dob_limit_mps2; }),
      number("integral.k_i_per_s3.x", "1/s³", {0.0, 1e4, kInclusive},
             [](P& p) -> double& { return p.k_i_per_s3[0]; }),
      number("integral.k_i_per_s3.y", "1/s³", {0.0, 1e4, kInclusive},
             [](P& p) -> double& { return p.k_i_per_s3[1]; }),
      number("integral.k_i_per_s3.z", "1/s³", {0.0, 1e4, kInclusive},
             [](P& p) -> double& { return p.k_i_per_s3[2]; }),
      number("integral.limit_mps2", "m/s²", {0.0, 20.0, kExclusive},
             [](P& p) -> double& { return p.integral_limit_mps2; }),
      number("clearance_guard.margin_m", "m", {0.0, 1.0, kInclusive},
             [](P& p) -> double& { return p.guard_margin_m; }),
      number("clearance_guard.brake_mps2", "m/s²", {0.0, 50.0, kExclusive},
             [](P& p) -> double& { return p.guard_brake_mps2; }),
      number("clearance_guard.reaction_time_s", "s", {0.0, 1.0, kInclusive},
             [](P& p) -> double& { return p.guard_reaction_time_s; }),
      number("clearance_guard.rate_per_s", "1/s", {0.0, 100.0, kExclusive},
             [](P& p) -> double& { return p.guard_rate_per_s; }),
      number("rotor_speed_loop.k_i_per_s", "1/s", {0.0, 100.0, kInclusive},
             [](P& p) -> double& { return p.rotor_speed_ki_per_s; }),
      number("rotor_speed_loop.limit_throttle", "", {0.0, 1.0, kInclusive},
             [](P& p) -> double& { return p.rotor_speed_limit_throttle; }),
      number("rotor_speed_loop.motor_lag_s", "s", {0.0, 1.0, kInclusive},
             [](P& p) -> double& { return p.rotor_speed_lag_s; }),
  };
}

/// The low-pass cut-off below the Nyquist frequency of the loop rate.
void checkCutoff(const P& p, model::FieldChecker& c) {
  if (!(p.filter_cutoff_hz < 0.5 * p.rate_hz)) {
    c.fail("loop.filter_cutoff_hz", model::formatValue(p.filter_cutoff_hz),
           "a cut-off in (0, loop.rate_hz/2 = " + model::formatValue(0.5 * p.rate_hz) + ") Hz");
  }
}

/// K^I below K^P·K^V per axis (Routh–Hurwitz for s³ + K^V·s² + K^P·s + K^I).
void checkIntegral(const P& p, model::FieldChecker& c) {
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i) {
    const double bound = p.k_p_per_s2[i] * p.k_v_per_s[i];
    const double k_i = p.k_i_per_s3[i];
    if (!(k_i == 0.0 || k_i < bound)) {
      c.fail(std::string("integral.k_i_per_s3.") + axes[i], model::formatValue(k_i),
             "a gain in [0, K^P·K^V = " + model::formatValue(bound) +
                 ") 1/s³ (Routh–Hurwitz for s³ + K^V·s² + K^P·s + K^I)");
    }
  }
}

model::ParamSchema<P> build() {
  std::vector<S> specs = gainSpecs();
  for (auto& s : loopSpecs()) specs.push_back(s);
  std::vector<model::ParamRule<P>> rules;
  rules.push_back({"loop.filter_cutoff_hz", {"loop.rate_hz", "loop.filter_cutoff_hz"}, checkCutoff});
  rules.push_back({"integral.k_i_per_s3.z",
                   {"position.k_p_per_s2.x", "position.k_p_per_s2.y", "position.k_p_per_s2.z",
                    "position.k_v_per_s.x", "position.k_v_per_s.y", "position.k_v_per_s.z",
                    "integral.k_i_per_s3.x", "integral.k_i_per_s3.y", "integral.k_i_per_s3.z"},
                   checkIntegral});
  return model::ParamSchema<P>(std::move(specs), std::move(rules));
}

}  // namespace

const model::ParamSchema<ControllerParams>& controllerSchema() {
  static const model::ParamSchema<ControllerParams> schema = build();
  return schema;
}

ControllerParams defaultParameterValues() {
  ControllerParams v;
  const ControllerParams r = recommendedControllerParams();
  v.dob_time_constant_s = r.dob_time_constant_s;
  v.dob_limit_mps2 = r.dob_limit_mps2;
  v.k_i_per_s3 = r.k_i_per_s3;
  v.integral_limit_mps2 = r.integral_limit_mps2;
  v.guard_margin_m = r.guard_margin_m;
  v.guard_brake_mps2 = r.guard_brake_mps2;
  v.guard_reaction_time_s = r.guard_reaction_time_s;
  v.guard_rate_per_s = r.guard_rate_per_s;
  v.rotor_speed_ki_per_s = r.rotor_speed_ki_per_s;
  v.rotor_speed_limit_throttle = r.rotor_speed_limit_throttle;
  v.rotor_speed_lag_s = r.rotor_speed_lag_s;
  return v;
}

ControllerParams applyParameters(const ControllerParams& configuration,
                                 const ControllerParams& values) {
  ControllerParams p = configuration;
  p.k_p_per_s2 = values.k_p_per_s2;
  p.k_v_per_s = values.k_v_per_s;
  p.k_xi_per_s = values.k_xi_per_s;
  p.k_w_per_s = values.k_w_per_s;
  p.max_tilt_rad = values.max_tilt_rad;
  p.rate_hz = values.rate_hz;
  p.filter_cutoff_hz = values.filter_cutoff_hz;
  p.thrust_pi_kp = values.thrust_pi_kp;
  p.thrust_pi_ki = values.thrust_pi_ki;
  p.thrust_pi_limit = values.thrust_pi_limit;
  if (configuration.dob_time_constant_s > 0.0) {
    p.dob_time_constant_s = values.dob_time_constant_s;
    p.dob_limit_mps2 = values.dob_limit_mps2;
  }
  if (configuration.k_i_per_s3.any()) {
    p.k_i_per_s3 = values.k_i_per_s3;
    p.integral_limit_mps2 = values.integral_limit_mps2;
  }
  if (configuration.clearance_guard) {
    p.guard_margin_m = values.guard_margin_m;
    p.guard_brake_mps2 = values.guard_brake_mps2;
    p.guard_reaction_time_s = values.guard_reaction_time_s;
    p.guard_rate_per_s = values.guard_rate_per_s;
  }
  // The rotor-speed loop is an addition like the three above: its values apply where the
  // configuration switches it on (`recommended`), and k_i_per_s = 0 switches it off there.
  if (configuration.rotor_speed_ki_per_s > 0.0) {
    p.rotor_speed_ki_per_s = values.rotor_speed_ki_per_s;
    p.rotor_speed_limit_throttle = values.rotor_speed_limit_throttle;
    p.rotor_speed_lag_s = values.rotor_speed_lag_s;
  }
  return p;
}

bool sameParameterValues(const ControllerParams& a, const ControllerParams& b) {
  for (const auto& s : controllerSchema().specs()) {
    if (std::bit_cast<std::uint64_t>(s.numberOf(a)) != std::bit_cast<std::uint64_t>(s.numberOf(b))) {
      return false;
    }
  }
  return true;
}

}  // namespace geaware::control
