// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Disturbances of the truth plant: near-ground recirculation turbulence and wind.
// Both are seeded and deterministic; both are unknown to the controller.
//
// Ground turbulence (a Contribution for Plant::addContribution): near the ground the rotor
// wakes spread, hit the surface and part of the flow recirculates through the discs, buffeting
// the vehicle. We model the buffeting as a random body-frame force and torque
//   F = s̄(h)·σ_F ⊙ x_F(t),   τ = s̄(h)·σ_τ ⊙ x_τ(t),
// x_F, x_τ independent unit first-order Gauss–Markov processes with correlation time τ_c
// (band-limited noise, corner frequency 1/(2π·τ_c)), drawn once per plant step and held over
// its RK4 stages. The intensity s̄ is the mean over the four rotors of
//   s(h) = max(0, (f(h) − f(h_max)) / (1 − f(h_max))),   f(h) = h_s² / (h² + h_s²),
// h each rotor's distance to the surface below it. f has the shape of the additional-thrust
// ratio F_G(h) = g2/(h² + g1) (the recirculating flow is what the ground deflects back up):
// s = 1 at the surface, about ½ at h = h_s, and exactly 0 from h_max up. Averaging over the
// rotors makes a table edge under half the vehicle give about half the buffeting.
// Defaults: σ_F = (0.3, 0.3, 0.5) N (2–3 % of the 16.6 N weight), σ_τ = (0.015, 0.015, 0.005)
// N·m (≈ 7 % of the 0.2 N·m leveling-torque peak), τ_c = 20 ms (corner frequency ≈ 8 Hz:
// eddies of a rotor diameter, 0.18 m, carried by recirculating flow at ≈ 1.5 m/s, a fraction
// of the 4 m/s induced velocity), h_s = 0.15 m (about a rotor diameter: s(0.12) ≈ 0.61,
// s(0.3) ≈ 0.20, s(1.0) ≈ 0.017), h_max = 2 m. Moderate: the paper's vehicle flies at 0.12 m.
// These magnitudes are assumed, not measured (the ideal world keeps them). With per_rotor set,
// the flight loop builds sim::RotorTurbulence instead (rotor_turbulence.hpp, docs/world.md §7):
// per-rotor thrust fluctuations mapped to the body through the mixer geometry.
//
// Unsteadiness at altitude (a Contribution; docs/world.md): what buffets a multirotor
// wherever it flies — blade imbalance and tracking error, the rotors' own unsteady wakes,
// turbulence — as a body-frame force and torque F = σ_F·x_F(t), τ = σ_τ·x_τ(t), x independent
// unit Gauss–Markov processes per body axis with correlation time τ_c, independent of the
// height. Seeded with its own salt (salt::kUnsteadiness): switching it on changes no other
// stream. Default: off (σ = 0).
//
// Wind: an air velocity, nothing else. The runner advances it once per plant step and hands
// it to Plant::setWind_W; the rotor aerodynamics then see the CoM velocity relative to the
// air (rotor drag, the forward-speed fade of the ground effect, and the airframe drag and
// translational lift when the truth has them, RotorAeroParams). wind_W = mean + σ_g ⊙ x_g(t), x_g a unit Gauss–Markov process per world
// axis with correlation time T (a first-order, Dryden-like gust spectrum). Default: off.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/field_error.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/sampling.hpp"
#include "geaware/sim/wrench.hpp"

namespace geaware::sim {

struct GroundTurbulenceParams {
  Eigen::Vector3d force_std_N = Eigen::Vector3d(0.3, 0.3, 0.5);         ///< σ_F at the surface, body axes [N]
  Eigen::Vector3d torque_std_Nm = Eigen::Vector3d(0.015, 0.015, 0.005); ///< σ_τ at the surface, body axes [N·m]
  double correlation_time_s = 0.02;   ///< τ_c of the Gauss–Markov processes [s]
  double scale_height_m = 0.15;       ///< h_s: intensity falls to about ½ here [m]
  double cutoff_height_m = 2.0;       ///< h_max: no turbulence from here up [m]
  /// The per-rotor law instead (sim::RotorTurbulence, include/geaware/sim/rotor_turbulence.hpp;
  /// docs/world.md §7): σ_F, σ_τ, h_s and h_max above are then not used. Default: off.
  bool per_rotor = false;
  /// κ of the per-rotor law: σ_T,i/T_i = κ·φ_i(h_i), φ_i the rotor's in-flight additional-thrust
  /// fraction [-].
  double fluctuation_per_increment = 0.25;
  /// ρ of the per-rotor law: correlation of the four rotors' fluctuations, 0 independent [-].
  double rotor_correlation = 0.0;

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// The intensity law s(h) ∈ [0, 1] above (h < 0, under the surface, counts as 0 m; ∞ or NaN
/// gives 0).
[[nodiscard]] double turbulenceIntensity(const GroundTurbulenceParams& params, double height_m) noexcept;

class GroundTurbulence final : public Contribution {
 public:
  /// Throws model::InvalidParameters listing every invalid field. Noise stream:
  /// (scenario_seed, salt::kGroundTurbulence).
  GroundTurbulence(const GroundTurbulenceParams& params, std::uint64_t scenario_seed);

  [[nodiscard]] const char* name() const noexcept override { return "ground_turbulence"; }
  /// Advances the unit processes by dt (a non-finite or negative dt leaves them unchanged).
  void beginStep(double t_s, double dt_s, const PlantState& state) noexcept override;
  /// The buffeting at the rotors' present distances to the ground.
  [[nodiscard]] Wrench wrench(const ContributionContext& ctx) noexcept override;

  /// The buffeting with intensity s̄ = mean of s(h_i) over the given rotor distances [m].
  [[nodiscard]] Wrench wrenchAt(const std::array<double, 4>& rotor_ground_distance_m) const noexcept;
  [[nodiscard]] const GroundTurbulenceParams& params() const noexcept { return params_; }

 private:
  GroundTurbulenceParams params_;
  GaussMarkovWrench unit_;  // unit-σ buffeting, scaled by σ_F, σ_τ and s(h)
};

struct UnsteadinessParams {
  double torque_std_Nm = 0.0;        ///< σ_τ about each body axis [N·m]
  double force_std_N = 0.0;          ///< σ_F along each body axis [N]
  double correlation_time_s = 0.05;  ///< τ_c of the Gauss–Markov processes [s]

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

class Unsteadiness final : public Contribution {
 public:
  /// Throws model::InvalidParameters listing every invalid field. Noise stream:
  /// (scenario_seed, salt::kUnsteadiness).
  Unsteadiness(const UnsteadinessParams& params, std::uint64_t scenario_seed);

  [[nodiscard]] const char* name() const noexcept override { return "altitude_unsteadiness"; }
  [[nodiscard]] bool readsSurroundings() const noexcept override { return false; }
  /// Advances the unit processes by dt (a non-finite or negative dt leaves them unchanged).
  void beginStep(double t_s, double dt_s, const PlantState& state) noexcept override;
  [[nodiscard]] Wrench wrench(const ContributionContext& ctx) noexcept override;
  [[nodiscard]] const UnsteadinessParams& params() const noexcept { return params_; }

 private:
  UnsteadinessParams params_;
  GaussMarkovWrench unit_;  // unit-σ unsteadiness, scaled by σ_F, σ_τ
};

struct WindParams {
  Eigen::Vector3d mean_W_mps = Eigen::Vector3d::Zero();    ///< steady air velocity, world frame [m/s]
  Eigen::Vector3d gust_std_mps = Eigen::Vector3d::Zero();  ///< gust 1σ per world axis [m/s]
  double gust_correlation_time_s = 1.0;                    ///< T of the gust process [s]

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

class Wind {
 public:
  /// Throws model::InvalidParameters listing every invalid field. Noise stream:
  /// (scenario_seed, salt::kWind).
  Wind(const WindParams& params, std::uint64_t scenario_seed);

  /// Advance the gusts by dt ≥ 0 [s] (otherwise nothing changes) and return the air velocity
  /// [m/s], world frame: plant.setWind_W(wind.advance(dt)) before each plant.step().
  const Eigen::Vector3d& advance(double dt_s) noexcept;
  [[nodiscard]] const Eigen::Vector3d& velocity_W() const noexcept { return wind_W_; }
  [[nodiscard]] const WindParams& params() const noexcept { return params_; }

 private:
  WindParams params_;
  NoiseSource noise_;
  GaussMarkov3 gust_;
  Eigen::Vector3d wind_W_;
};

}  // namespace geaware::sim
