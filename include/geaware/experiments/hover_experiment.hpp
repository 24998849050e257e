// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's hover experiment: a slow descending hover from high altitude into ground effect,
// flown with torque compensation none / model / INDI / model + INDI, and the angle error E
// between desired and true attitude binned by the true rotor-plane height, averaged over seeds.
// The acceleration side is the same in every flight: the recommended controller's (model
// feed-forward, disturbance-observer residual, integral action, clearance guard), which
// survives the as-built world where the paper's `model` alone strikes the ground
// (docs/results.md, "Hover experiment").

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/traj/hover_descent.hpp"

namespace geaware::experiments {

struct HoverSettings {
  double from_height_m = 1.5;      ///< start of the descent [m]
  double to_height_m = 0.1;        ///< end of the descent (held) [m]
  double descent_rate_mps = 0.1;   ///< quasi-static descent [m/s]
  double hold_start_s = 2.0;       ///< hover at from_height first [s]
  double hold_end_s = 2.0;         ///< hover at to_height last [s]
  double bin_width_m = 0.05;       ///< height bins of E(h) [m]
  double max_height_m = 1.6;       ///< bins cover [0, max_height) [m]
  /// Every flight's controller but its torque compensation, which each curve sets.
  control::ControllerParams controller = control::recommendedControllerParams();
  /// The four torque compensations, in the order they are reported.
  std::vector<control::TorqueCompensation> torques = {
      control::TorqueCompensation::kNone, control::TorqueCompensation::kModel,
      control::TorqueCompensation::kIndi, control::TorqueCompensation::kModelIndi};
};

[[nodiscard]] traj::HoverDescentParams hoverDescentFor(const HoverSettings& s);
[[nodiscard]] HeightBinning hoverBinning(const HoverSettings& s);

struct HoverBin {
  double h_low_m = 0.0;
  double h_high_m = 0.0;
  std::uint64_t samples = 0;      ///< over all seeds
  std::size_t seeds_visited = 0;  ///< seeds with at least one sample in the bin
  double angle_err_deg = 0.0;     ///< mean over seeds of each seed's mean E in the bin [deg]
  double angle_err_std_deg = 0.0; ///< standard deviation of those per-seed means [deg]
  std::vector<double> per_seed_deg;  ///< each seed's mean E (NaN where it has no sample)
  [[nodiscard]] double centre_m() const noexcept { return 0.5 * (h_low_m + h_high_m); }
};

struct HoverCurve {
  control::TorqueCompensation torque = control::TorqueCompensation::kNone;
  std::vector<std::uint64_t> seeds;
  std::vector<HoverBin> bins;  ///< only bins with samples, lowest first
  int crashes = 0;
};

/// Summarises the hover flights of one torque compensation (results in the order of `seeds`).
[[nodiscard]] HoverCurve summariseHover(control::TorqueCompensation torque,
                                        const std::vector<std::uint64_t>& seeds,
                                        const std::vector<FlightResult>& flights);

/// Sample-weighted mean of E over the bins whose centre lies in [from, to) [deg]; NaN if none.
[[nodiscard]] double bandMean(const HoverCurve& c, double from_m, double to_m);
/// The near/high ratio E(0.1–0.3 m)/E(1–1.5 m) of issue 10's check (bandMean of each) [-].
[[nodiscard]] double hoverNearHighRatio(const HoverCurve& c);
/// Largest bin E among bins whose centre lies in [from, to) [deg]; NaN if none.
[[nodiscard]] double bandMax(const HoverCurve& c, double from_m, double to_m);
/// Centre of the bin with the largest E among the bins every seed visited (a bin that one
/// seed's excursion alone reached does not make a peak) [m]; NaN for an empty curve. Reported,
/// not checked (issue 10).
[[nodiscard]] double peakHeight(const HoverCurve& c);

}  // namespace geaware::experiments
