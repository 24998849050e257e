// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Near-ground turbulence from per-rotor thrust fluctuations (docs/world.md §7): the as-built
// world's law in place of GroundTurbulence's body-axis law (GroundTurbulenceParams::per_rotor).
//
// Each rotor's thrust fluctuates about its mean by
//   δT_i(t) = κ·φ_i(h_i)·k_T,i·n_i²·x_i(t),   x_i = √ρ·c(t) + √(1 − ρ)·e_i(t),
// φ_i the truth's own in-flight additional-thrust fraction of rotor i at its distance h_i to the
// surface below it (RotorAerodynamics::flightFactors: the rig-calibrated per-rotor law times
// the in-flight cushion scale), κ the fluctuation per unit of that mean increment, c and e_i
// unit first-order Gauss–Markov processes with correlation time τ_c, ρ the correlation between
// rotors. σ_T,i/T_i = κ·φ_i(h_i) grows as the rotor nears the ground and vanishes with φ_i far
// from it. The body wrench follows from the mixer geometry of the truth (no free torque):
//   F = Σ δT_i·a_i,   τ = Σ r_i × δT_i·a_i + spin_i·(k_I,i/k_T,i)·δT_i·a_i,
// r_i the rotor-disc centre relative to the CoM, a_i its thrust axis (TruthParams::rotorGeometry).
// For level rotors about a centred CoM and independent rotors (ρ = 0),
// Var τ_x = Σ y_i²·σ_T,i², Var τ_y = Σ x_i²·σ_T,i², Var F_z = Σ σ_T,i²; fully correlated equal
// fluctuations (ρ = 1, equal σ_T,i) give a vertical force and no torque.
//
// Noise: the stream (scenario_seed, salt::kGroundTurbulence) of sim::GaussMarkovWrench, whose
// six unit processes are, in their draw order, e_1, e_2, e_3, e_4, c and one unused. The
// intensities κ·φ_i are evaluated at the first stage of each step and held over its RK4 stages,
// like the plant's own ground factors.

#include <array>
#include <cstdint>

#include "geaware/sim/disturbances.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/sampling.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware/sim/wrench.hpp"

namespace geaware::sim {

/// The body-frame wrench about the CoM of thrust fluctuations δT_i [N] along the rotors' axes
/// (with the reaction torque spin_i·(k_I,i/k_T,i)·δT_i each carries).
[[nodiscard]] Wrench rotorFluctuationWrench(const RotorGeometry& geometry,
                                            const std::array<double, 4>& thrust_fluctuation_N) noexcept;

class RotorTurbulence final : public Contribution {
 public:
  /// `params` must have per_rotor set or not, it is not read; its fluctuation_per_increment,
  /// rotor_correlation and correlation_time_s are. Throws model::InvalidParameters listing every
  /// invalid field (the truth's aerodynamics included).
  RotorTurbulence(const GroundTurbulenceParams& params, const TruthParams& truth,
                  std::uint64_t scenario_seed);

  [[nodiscard]] const char* name() const noexcept override { return "rotor_turbulence"; }
  /// Advances the unit processes by dt (a non-finite or negative dt leaves them unchanged); the
  /// next wrench() re-evaluates the intensities.
  void beginStep(double t_s, double dt_s, const PlantState& state) noexcept override;
  [[nodiscard]] Wrench wrench(const ContributionContext& ctx) noexcept override;

  /// σ_T,i/T_i = κ·φ_i(h_i) at the given distances of the rotors to the surface [m] [-].
  [[nodiscard]] std::array<double, 4> relativeStd(
      const std::array<double, 4>& rotor_ground_distance_m) const noexcept;
  /// The unit processes x_i of this step [-].
  [[nodiscard]] std::array<double, 4> unitFluctuations() const noexcept;
  /// δT_i [N] at rotor speeds n [rpm] with relative intensities σ_T,i/T_i.
  [[nodiscard]] std::array<double, 4> thrustFluctuation(
      const std::array<double, 4>& n_rpm, const std::array<double, 4>& relative_std) const noexcept;
  [[nodiscard]] const RotorGeometry& geometry() const noexcept { return geometry_; }

 private:
  GroundTurbulenceParams params_;
  RotorGeometry geometry_;
  RotorAerodynamics aero_;
  GaussMarkovWrench unit_;
  std::array<double, 4> relative_std_{};
  bool intensities_held_ = false;
};

}  // namespace geaware::sim
