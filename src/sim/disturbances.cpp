// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/disturbances.hpp"

#include <cmath>
#include <utility>

#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {

std::vector<model::FieldError> GroundTurbulenceParams::validate() const {
  std::vector<model::FieldError> out;
  model::FieldChecker c(out);
  using enum model::LowerBound;
  c.nonNegative("force_std_N", force_std_N, "N");
  c.nonNegative("torque_std_Nm", torque_std_Nm, "N·m");
  c.range("correlation_time_s", correlation_time_s, 0.0, 1e3, kExclusive, "s");
  c.range("scale_height_m", scale_height_m, 0.0, 1e2, kExclusive, "m");
  c.range("cutoff_height_m", cutoff_height_m, 0.0, 1e3, kExclusive, "m");
  c.range("fluctuation_per_increment", fluctuation_per_increment, 0.0, 10.0, kInclusive, "[-]");
  c.range("rotor_correlation", rotor_correlation, 0.0, 1.0, kInclusive, "[-]");
  return out;
}

double turbulenceIntensity(const GroundTurbulenceParams& p, double height_m) noexcept {
  if (!(height_m < p.cutoff_height_m)) return 0.0;  // also ∞ and NaN
  const double h = height_m > 0.0 ? height_m : 0.0;
  const double hs2 = p.scale_height_m * p.scale_height_m;
  const double f = hs2 / (h * h + hs2);
  const double f_max = hs2 / (p.cutoff_height_m * p.cutoff_height_m + hs2);
  return (f - f_max) / (1.0 - f_max);
}

GroundTurbulence::GroundTurbulence(const GroundTurbulenceParams& params,
                                   std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      unit_(params_.correlation_time_s, scenario_seed, salt::kGroundTurbulence) {}

void GroundTurbulence::beginStep(double /*t_s*/, double dt_s, const PlantState& /*state*/) noexcept {
  unit_.advance(dt_s);
}

Wrench GroundTurbulence::wrenchAt(const std::array<double, 4>& d) const noexcept {
  double s = 0.0;
  for (double h : d) s += turbulenceIntensity(params_, h);
  s *= 0.25;
  Wrench w;
  if (s > 0.0) {
    w.force_B = s * params_.force_std_N.cwiseProduct(unit_.force());
    w.torque_B = s * params_.torque_std_Nm.cwiseProduct(unit_.torque());
  }
  return w;
}

Wrench GroundTurbulence::wrench(const ContributionContext& ctx) noexcept {
  return wrenchAt(ctx.surroundings.ground_distance_m);
}

std::vector<model::FieldError> UnsteadinessParams::validate() const {
  std::vector<model::FieldError> out;
  model::FieldChecker c(out);
  using enum model::LowerBound;
  c.range("torque_std_Nm", torque_std_Nm, 0.0, 10.0, kInclusive, "N·m");
  c.range("force_std_N", force_std_N, 0.0, 100.0, kInclusive, "N");
  c.range("correlation_time_s", correlation_time_s, 0.0, 1e3, kExclusive, "s");
  return out;
}

Unsteadiness::Unsteadiness(const UnsteadinessParams& params, std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      unit_(params_.correlation_time_s, scenario_seed, salt::kUnsteadiness) {}

void Unsteadiness::beginStep(double /*t_s*/, double dt_s, const PlantState& /*state*/) noexcept {
  unit_.advance(dt_s);
}

Wrench Unsteadiness::wrench(const ContributionContext& /*ctx*/) noexcept {
  Wrench w;
  w.force_B = params_.force_std_N * unit_.force();
  w.torque_B = params_.torque_std_Nm * unit_.torque();
  return w;
}

std::vector<model::FieldError> WindParams::validate() const {
  std::vector<model::FieldError> out;
  model::FieldChecker c(out);
  using enum model::LowerBound;
  c.finite("mean_W_mps", mean_W_mps, "m/s");
  c.nonNegative("gust_std_mps", gust_std_mps, "m/s");
  c.range("gust_correlation_time_s", gust_correlation_time_s, 0.0, 1e4, kExclusive, "s");
  return out;
}

Wind::Wind(const WindParams& params, std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      noise_(scenario_seed, salt::kWind),
      gust_(params_.gust_correlation_time_s, noise_),
      wind_W_(params_.mean_W_mps + params_.gust_std_mps.cwiseProduct(gust_.value())) {}

const Eigen::Vector3d& Wind::advance(double dt_s) noexcept {
  if (std::isfinite(dt_s) && dt_s >= 0.0) {
    gust_.advance(dt_s, noise_);
    wind_W_ = params_.mean_W_mps + params_.gust_std_mps.cwiseProduct(gust_.value());
  }
  return wind_W_;
}

}  // namespace geaware::sim
