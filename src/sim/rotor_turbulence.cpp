// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/rotor_turbulence.hpp"

#include <cmath>

#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {

Wrench rotorFluctuationWrench(const RotorGeometry& g, const std::array<double, 4>& dT) noexcept {
  Wrench w;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d f = dT[i] * g.thrust_axis_B[i];
    const double k_T = g.k_T_N_per_rpm2[i];
    const double torque_per_thrust_m = k_T > 0.0 ? g.k_I_Nm_per_rpm2[i] / k_T : 0.0;
    w.force_B += f;
    w.torque_B += g.position_B[i].cross(f) + g.spin[i] * torque_per_thrust_m * f;
  }
  return w;
}

RotorTurbulence::RotorTurbulence(const GroundTurbulenceParams& params, const TruthParams& truth,
                                 std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      geometry_(truth.rotorGeometry()),
      aero_(geometry_, truth.aero),
      unit_(params_.correlation_time_s, scenario_seed, salt::kGroundTurbulence) {}

void RotorTurbulence::beginStep(double /*t_s*/, double dt_s, const PlantState& /*state*/) noexcept {
  unit_.advance(dt_s);
  intensities_held_ = false;
}

std::array<double, 4> RotorTurbulence::relativeStd(const std::array<double, 4>& d) const noexcept {
  const RotorGroundFactors f = aero_.flightFactors(d);
  std::array<double, 4> s{};
  for (std::size_t i = 0; i < 4; ++i) {
    s[i] = std::isfinite(f.phi[i]) && f.phi[i] > 0.0 ? params_.fluctuation_per_increment * f.phi[i]
                                                       : 0.0;
  }
  return s;
}

std::array<double, 4> RotorTurbulence::unitFluctuations() const noexcept {
  const Eigen::Vector3d& a = unit_.force();
  const Eigen::Vector3d& b = unit_.torque();
  const double rho = params_.rotor_correlation;
  const double common = std::sqrt(rho) * b.y();
  const double own = std::sqrt(1.0 - rho);
  return {common + own * a.x(), common + own * a.y(), common + own * a.z(), common + own * b.x()};
}

std::array<double, 4> RotorTurbulence::thrustFluctuation(const std::array<double, 4>& n_rpm,
                                                         const std::array<double, 4>& rel) const noexcept {
  const std::array<double, 4> x = unitFluctuations();
  std::array<double, 4> dT{};
  for (std::size_t i = 0; i < 4; ++i) {
    dT[i] = rel[i] * geometry_.k_T_N_per_rpm2[i] * n_rpm[i] * n_rpm[i] * x[i];
  }
  return dT;
}

Wrench RotorTurbulence::wrench(const ContributionContext& ctx) noexcept {
  if (!intensities_held_) {
    relative_std_ = relativeStd(ctx.surroundings.ground_distance_m);
    intensities_held_ = true;
  }
  return rotorFluctuationWrench(geometry_, thrustFluctuation(ctx.n_rpm, relative_std_));
}

}  // namespace geaware::sim
