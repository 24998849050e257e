// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The ground effect learned in flight (issue 13 item 3): F_G(h), the extra thrust ratio, as
// values at fixed knot heights, estimated from the disturbance observer's flight estimate
// F̃_G = m·z_Wᵀ·ã_ext/T (the paper's eq. for its flight data) by exponentially weighted least
// squares with a prior.
//
// The curve between knots is linear in the knot values θ (hat functions), so a sample at
// height h in [h_j, h_j+1] is y = (1−t)·θ_j + t·θ_j+1 + noise, t = (h − h_j)/(h_j+1 − h_j).
// Each interval keeps its own sufficient statistics (a 2×2 information matrix and a 2-vector)
// and forgets (factor λ per sample) only when a sample falls in it: information about heights
// the vehicle no longer visits is kept, so with poor excitation nothing drifts (directional
// forgetting, Kulhavý 1987). The estimate solves the tridiagonal normal equations
//     (Λ₀ + Σ_j A_j) θ = Λ₀·θ₀ + Σ_j b_j   (bordered by the offset's row and column)
// with the prior θ₀ (the vehicle file's curve at the knots, or 0: no model at all) of
// information Λ₀ = 1/σ₀² per knot, then bounds θ to [min, max] and makes it non-increasing in h
// (weighted isotonic regression). Knots no sample reached keep their prior, raised where needed
// to the value learned above them. No allocation after construction; every update is O(knots).
//
// The flight estimate holds everything the rotors' nominal thrust does not explain: a mass or
// thrust-coefficient error shows as an offset b at every height. b is estimated with θ: a sample
// among the knots is y = (1−t)·θ_j + t·θ_j+1 + b, a sample at or above far_height_m (out of
// ground effect) is y = θ_N·(h_N/h)² + b, the curve's inverse-square tail beyond the last knot
// (as model::HeightTable continues a table) plus the offset. The far samples are what separates
// b from the curve (with a weak prior, 0), so the curve learned is the ground's
// share alone whenever the vehicle has been out of ground effect. Before the first far sample
// b is 0: nothing tells it from the curve.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geaware/model/field_error.hpp"

namespace geaware::control {

struct GroundEffectLearnerParams {
  /// Knot heights of the learned curve, strictly increasing, 2 to kMaxKnots, rotor plane above
  /// the ground [m]. Samples outside [first, last] are not used.
  std::vector<double> knots_m = {0.08, 0.10, 0.12, 0.14, 0.17, 0.20, 0.24, 0.28, 0.33, 0.40, 0.50};
  double forgetting = 0.999;       ///< λ per sample in an interval, (0, 1] [-]
  double sample_sigma = 0.05;      ///< σ of one F̃_G sample [-]
  double prior_sigma = 0.02;       ///< σ₀ of a prior from a vehicle file, at each knot [-]
  /// σ₀ when there is no model to start from (prior 0): a regulariser only [-].
  double no_model_prior_sigma = 1.0;
  double min_ratio = 0.0;          ///< lower bound on F_G [-]
  double max_ratio = 1.5;          ///< upper bound on F_G [-]
  double max_abs_sample = 2.0;     ///< |F̃_G| above this is an outlier, not used [-]
  double max_tilt_rad = 0.35;      ///< samples at a larger tilt are not used [rad]
  /// nor at a larger horizontal speed (the forward-flight fade), unless the fade is modelled [m/s]
  double max_speed_mps = 1.5;
  /// With the fade modelled (update()'s `fade` below 1), samples are used down to this fade
  /// instead, V ≤ v_i at 0.5 [-].
  double min_fade = 0.5;
  double max_climb_mps = 0.5;      ///< nor at a larger vertical speed [m/s]
  /// A knot counts as learned once its data information reaches this many samples' worth [-].
  double learned_samples = 200.0;
  /// Samples at or above this height estimate the offset (must be above the last knot) [m].
  double far_height_m = 0.8;
  /// Memory of the far samples (forgetting 1 − 1/offset_samples per far sample) [-].
  double offset_samples = 400.0;
  /// σ of the offset's prior (0) once far samples have come; before any, the offset is 0 [-].
  double offset_sigma = 0.1;
  /// The propeller radius the heights above (knots_m, far_height_m) are for: the paper's
  /// vehicle's. The controller multiplies them by R/this for its own vehicle, so that a vehicle
  /// of another size learns at the same heights over radius (sim/similarity.hpp's rule for
  /// lengths); 0: the heights as given [m].
  double reference_propeller_radius_m = 0.089;
  /// F_G never decreases as the ground comes closer: the estimate is the closest non-increasing
  /// curve (weighted isotonic regression). The paper's curve and every law of
  /// docs/sim-aerodynamics.md are monotone; off only to see the raw fit.
  bool monotone = true;

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// Why a sample was or was not used.
/// The index j of the interval [h_j, h_j+1] of `knots_m` (n ≥ 2, increasing) that holds h; the
/// last knot belongs to the last interval, heights outside to the end intervals.
[[nodiscard]] std::size_t knotInterval(const double* knots_m, std::size_t n, double h_m) noexcept;
/// The curve through (knots_m[k], values[k]), linear between knots, the end values held
/// outside; NaN for a NaN h.
[[nodiscard]] double knotCurve(const double* knots_m, const double* values, std::size_t n, double h_m) noexcept;

enum class LearnerSample : std::uint8_t {
  kUsed, kOffset, kNonFinite, kOutsideKnots, kOutlier, kTilted, kFast, kClimbing,
  kUnexcited  ///< the leveling learner's regressor is below its excitation gate
};

class GroundEffectLearner {
 public:
  static constexpr std::size_t kMaxKnots = 16;

  /// prior_values: θ₀ at each knot (same count as params.knots_m). Throws
  /// model::InvalidParameters for invalid params or a prior of the wrong size / non-finite.
  GroundEffectLearner(const GroundEffectLearnerParams& params, const std::vector<double>& prior_values);

  /// One flight estimate: F̃_G at height h_m, with the tilt, horizontal and vertical speeds that
  /// gate it. `fade`: the model's forward-flight fade at this speed (model::GroundEffectModel::
  /// forwardFade; exactly 1 without one): the sample is then fade·F_G(h) + offset, and the
  /// speed gate becomes fade ≥ min_fade. No allocation.
  LearnerSample update(double h_m, double f_g, double tilt_rad, double speed_mps, double climb_mps,
                       double fade = 1.0) noexcept;

  [[nodiscard]] std::size_t knots() const noexcept { return n_; }
  [[nodiscard]] double knot_m(std::size_t k) const noexcept { return h_[k]; }
  /// Current estimate θ_k [-].
  [[nodiscard]] double value(std::size_t k) const noexcept { return theta_[k]; }
  [[nodiscard]] const double* values() const noexcept { return theta_.data(); }
  /// Information from data at knot k, in samples' worth [-].
  [[nodiscard]] double dataSamples(std::size_t k) const noexcept;
  [[nodiscard]] bool learned(std::size_t k) const noexcept { return dataSamples(k) >= learned_samples_; }
  /// The learned curve at h (linear between knots, the first / last value held outside) [-].
  [[nodiscard]] double ratio(double h_m) const noexcept;
  /// Samples used for the curve so far.
  [[nodiscard]] std::uint64_t used() const noexcept { return used_; }
  /// The offset subtracted from samples among the knots (0 until a far sample came) [-].
  [[nodiscard]] double offset() const noexcept { return offset_; }
  [[nodiscard]] std::uint64_t offsetSamples() const noexcept { return offset_n_; }

 private:
  struct Interval {
    double a00 = 0.0, a01 = 0.0, a11 = 0.0;  // information of the two knots [1/σ²]
    double c0 = 0.0, c1 = 0.0, cc = 0.0;     // with the offset, and the offset's own
    double b0 = 0.0, b1 = 0.0, cy = 0.0;     // right-hand sides
  };
  struct Far {
    double rr = 0.0, rb = 0.0, bb = 0.0, ry = 0.0, by = 0.0;
  };
  void solve() noexcept;
  void makeNonIncreasing(const std::array<double, kMaxKnots>& weight) noexcept;

  std::size_t n_ = 0;
  std::array<double, kMaxKnots> h_{};
  std::array<double, kMaxKnots> prior_{};
  std::array<double, kMaxKnots> theta_{};
  std::array<Interval, kMaxKnots> stats_{};  // interval j between knots j and j+1
  double lambda_, w_, prior_info_, min_, max_, max_abs_, max_tilt_, max_speed_, min_fade_, max_climb_;
  double learned_samples_, far_height_m_, far_lambda_;
  bool monotone_;
  double offset_prior_info_;
  Far far_;
  double offset_ = 0.0;
  std::uint64_t offset_n_ = 0;
  std::uint64_t used_ = 0;
};

}  // namespace geaware::control
