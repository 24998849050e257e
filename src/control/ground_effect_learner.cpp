// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/control/ground_effect_learner.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_model.hpp"  // model::InvalidParameters

namespace geaware::control {

std::size_t knotInterval(const double* knots_m, std::size_t n, double h_m) noexcept {
  std::size_t j = 0;
  while (j + 2 < n && h_m >= knots_m[j + 1]) ++j;
  return j;
}

double knotCurve(const double* knots_m, const double* values, std::size_t n, double h_m) noexcept {
  if (std::isnan(h_m)) return h_m;
  if (h_m <= knots_m[0]) return values[0];
  if (h_m >= knots_m[n - 1]) return values[n - 1];
  const std::size_t j = knotInterval(knots_m, n, h_m);
  const double t = (h_m - knots_m[j]) / (knots_m[j + 1] - knots_m[j]);
  return (1.0 - t) * values[j] + t * values[j + 1];
}

std::vector<model::FieldError> GroundEffectLearnerParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e);
  using enum model::LowerBound;
  if (knots_m.size() < 2 || knots_m.size() > GroundEffectLearner::kMaxKnots) {
    c.fail("knots_m", std::to_string(knots_m.size()) + " knots",
           "2 to " + std::to_string(GroundEffectLearner::kMaxKnots) + " heights");
  }
  for (std::size_t k = 0; k < knots_m.size(); ++k) {
    const std::string key = "knots_m[" + std::to_string(k) + "]";
    if (c.range(key, knots_m[k], 0.0, 100.0, kExclusive, "m") && k > 0 &&
        !(knots_m[k] > knots_m[k - 1])) {
      c.fail(key, model::formatValue(knots_m[k]), "a height above knots_m[" + std::to_string(k - 1) + "]");
    }
  }
  c.range("forgetting", forgetting, 0.0, 1.0, kExclusive);
  c.range("sample_sigma", sample_sigma, 0.0, 10.0, kExclusive);
  c.range("prior_sigma", prior_sigma, 0.0, 1e3, kExclusive);
  c.range("no_model_prior_sigma", no_model_prior_sigma, 0.0, 1e3, kExclusive);
  if (c.finite("min_ratio", min_ratio) && c.finite("max_ratio", max_ratio) && !(min_ratio < max_ratio)) {
    c.fail("max_ratio", model::formatValue(max_ratio), "above min_ratio = " + model::formatValue(min_ratio));
  }
  c.range("max_abs_sample", max_abs_sample, 0.0, 100.0, kExclusive);
  c.range("max_tilt_rad", max_tilt_rad, 0.0, 1.5, kExclusive, "rad");
  c.range("max_speed_mps", max_speed_mps, 0.0, 100.0, kExclusive, "m/s");
  c.range("min_fade", min_fade, 0.0, 1.0, kExclusive);
  c.range("max_climb_mps", max_climb_mps, 0.0, 100.0, kExclusive, "m/s");
  c.range("learned_samples", learned_samples, 0.0, 1e9, kInclusive);
  if (c.range("far_height_m", far_height_m, 0.0, 1e3, kExclusive, "m") && !knots_m.empty() &&
      !(far_height_m > knots_m.back())) {
    c.fail("far_height_m", model::formatValue(far_height_m),
           "a height above the last knot (" + model::formatValue(knots_m.back()) + " m)");
  }
  c.range("offset_samples", offset_samples, 1.0, 1e9, kInclusive);
  c.range("offset_sigma", offset_sigma, 0.0, 1e3, kExclusive);
  c.range("reference_propeller_radius_m", reference_propeller_radius_m, 0.0, 5.0, kInclusive, "m");
  return e;
}

namespace {

const GroundEffectLearnerParams& checked(const GroundEffectLearnerParams& p,
                                         const std::vector<double>& prior) {
  auto e = p.validate();
  if (prior.size() != p.knots_m.size()) {
    e.push_back({"prior", std::to_string(prior.size()) + " values",
                 "one per knot (" + std::to_string(p.knots_m.size()) + ")"});
  }
  for (std::size_t k = 0; k < prior.size(); ++k) {
    if (!std::isfinite(prior[k])) {
      e.push_back({"prior[" + std::to_string(k) + "]", model::formatValue(prior[k]), "a finite ratio"});
    }
  }
  if (!e.empty()) throw model::InvalidParameters(std::move(e));
  return p;
}

}  // namespace

GroundEffectLearner::GroundEffectLearner(const GroundEffectLearnerParams& params,
                                         const std::vector<double>& prior_values)
    : n_(checked(params, prior_values).knots_m.size()),
      lambda_(params.forgetting),
      w_(1.0 / (params.sample_sigma * params.sample_sigma)),
      prior_info_(1.0 / (params.prior_sigma * params.prior_sigma)),
      min_(params.min_ratio),
      max_(params.max_ratio),
      max_abs_(params.max_abs_sample),
      max_tilt_(params.max_tilt_rad),
      max_speed_(params.max_speed_mps),
      min_fade_(params.min_fade),
      max_climb_(params.max_climb_mps),
      learned_samples_(params.learned_samples),
      far_height_m_(params.far_height_m),
      far_lambda_(1.0 - 1.0 / params.offset_samples),
      monotone_(params.monotone),
      offset_prior_info_(1.0 / (params.offset_sigma * params.offset_sigma)) {
  for (std::size_t k = 0; k < n_; ++k) {
    h_[k] = params.knots_m[k];
    prior_[k] = prior_values[k];
    theta_[k] = std::clamp(prior_values[k], min_, max_);
  }
  std::array<double, kMaxKnots> info{};
  info.fill(prior_info_);
  if (monotone_) makeNonIncreasing(info);
}

LearnerSample GroundEffectLearner::update(double h_m, double f_g, double tilt_rad, double speed_mps,
                                          double climb_mps, double fade) noexcept {
  if (!(std::isfinite(h_m) && std::isfinite(f_g) && std::isfinite(tilt_rad) &&
        std::isfinite(speed_mps) && std::isfinite(climb_mps) && std::isfinite(fade))) {
    return LearnerSample::kNonFinite;
  }
  const bool far = h_m >= far_height_m_;
  if (!far && (h_m < h_[0] || h_m > h_[n_ - 1])) return LearnerSample::kOutsideKnots;
  if (std::abs(f_g) > max_abs_) return LearnerSample::kOutlier;
  if (std::abs(tilt_rad) > max_tilt_) return LearnerSample::kTilted;
  // Without a fade model the curve is learned at low speed only; with one, down to min_fade.
  if (fade == 1.0 ? std::abs(speed_mps) > max_speed_ : !(fade >= min_fade_)) return LearnerSample::kFast;
  if (std::abs(climb_mps) > max_climb_) return LearnerSample::kClimbing;
  if (far) {
    // y = θ_N·(h_N/h)² + b: the curve's inverse-square tail (as model::HeightTable continues a
    // table) plus the offset.
    const double r = h_[n_ - 1] / h_m;
    const double r2 = fade * (r * r);
    Far& s = far_;
    s.rr = far_lambda_ * s.rr + w_ * r2 * r2;
    s.rb = far_lambda_ * s.rb + w_ * r2;
    s.bb = far_lambda_ * s.bb + w_;
    s.ry = far_lambda_ * s.ry + w_ * r2 * f_g;
    s.by = far_lambda_ * s.by + w_ * f_g;
    ++offset_n_;
    solve();
    return LearnerSample::kOffset;
  }
  // y = (1−t)·θ_j + t·θ_j+1 + b in the interval [h_j, h_j+1] holding h (the last knot belongs to
  // the last interval).
  const std::size_t j = knotInterval(h_.data(), n_, h_m);
  const double t = (h_m - h_[j]) / (h_[j + 1] - h_[j]);
  const double p0 = fade * (1.0 - t);
  const double p1 = fade * t;
  Interval& s = stats_[j];
  s.a00 = lambda_ * s.a00 + w_ * p0 * p0;
  s.a01 = lambda_ * s.a01 + w_ * p0 * p1;
  s.a11 = lambda_ * s.a11 + w_ * p1 * p1;
  s.c0 = lambda_ * s.c0 + w_ * p0;
  s.c1 = lambda_ * s.c1 + w_ * p1;
  s.cc = lambda_ * s.cc + w_;
  s.b0 = lambda_ * s.b0 + w_ * p0 * f_g;
  s.b1 = lambda_ * s.b1 + w_ * p1 * f_g;
  s.cy = lambda_ * s.cy + w_ * f_g;
  ++used_;
  solve();
  return LearnerSample::kUsed;
}

namespace {

/// Thomas algorithm for the symmetric tridiagonal T (diag, upper) against one right-hand side.
void thomas(std::size_t n, const double* diag, const double* upper, const double* rhs, double* x) noexcept {
  std::array<double, GroundEffectLearner::kMaxKnots> d{}, r{};
  d[0] = diag[0];
  r[0] = rhs[0];
  for (std::size_t k = 1; k < n; ++k) {
    const double m = upper[k - 1] / d[k - 1];
    d[k] = diag[k] - m * upper[k - 1];
    r[k] = rhs[k] - m * r[k - 1];
  }
  x[n - 1] = r[n - 1] / d[n - 1];
  for (std::size_t k = n - 1; k-- > 0;) x[k] = (r[k] - upper[k] * x[k + 1]) / d[k];
}

}  // namespace

// The normal equations in (θ, b): a tridiagonal block for θ (knot k couples only to k ± 1
// through the intervals beside it), bordered by the offset's row and column. Symmetric positive
// definite (the priors make every diagonal positive), so the bordered system is solved by two
// Thomas sweeps and the Schur complement, without pivoting.
void GroundEffectLearner::solve() noexcept {
  std::array<double, kMaxKnots> diag{}, upper{}, rhs{}, u{}, x{}, z{};
  double d_b = offset_prior_info_;
  double s_b = 0.0;
  for (std::size_t k = 0; k < n_; ++k) {
    diag[k] = prior_info_;
    rhs[k] = prior_info_ * prior_[k];
  }
  for (std::size_t j = 0; j + 1 < n_; ++j) {
    const Interval& s = stats_[j];
    diag[j] += s.a00;
    diag[j + 1] += s.a11;
    upper[j] = s.a01;
    rhs[j] += s.b0;
    rhs[j + 1] += s.b1;
    u[j] += s.c0;
    u[j + 1] += s.c1;
    d_b += s.cc;
    s_b += s.cy;
  }
  diag[n_ - 1] += far_.rr;
  u[n_ - 1] += far_.rb;
  rhs[n_ - 1] += far_.ry;
  d_b += far_.bb;
  s_b += far_.by;
  std::array<double, kMaxKnots> info{};  // each knot's information, for the monotone fit
  for (std::size_t k = 0; k < n_; ++k) info[k] = diag[k];
  thomas(n_, diag.data(), upper.data(), rhs.data(), x.data());
  if (offset_n_ == 0) {  // nothing separates an offset from the curve yet: b = 0
    offset_ = 0.0;
    for (std::size_t k = 0; k < n_; ++k) theta_[k] = std::clamp(x[k], min_, max_);
  } else {
    thomas(n_, diag.data(), upper.data(), u.data(), z.data());
    double ux = 0.0, uz = 0.0;
    for (std::size_t k = 0; k < n_; ++k) {
      ux += u[k] * x[k];
      uz += u[k] * z[k];
    }
    offset_ = (s_b - ux) / (d_b - uz);
    for (std::size_t k = 0; k < n_; ++k) theta_[k] = std::clamp(x[k] - z[k] * offset_, min_, max_);
  }
  if (monotone_) makeNonIncreasing(info);
}

// Weighted isotonic regression by pooling adjacent violators (Ayer et al. 1955): the closest
// non-increasing sequence to θ in the knots' information. A knot the vehicle never reached
// (prior information only) below one it learned is pooled with it, so an unexplored height
// near the ground gets at least the extra thrust learned above it, not the prior's none.
void GroundEffectLearner::makeNonIncreasing(const std::array<double, kMaxKnots>& weight) noexcept {
  std::array<double, kMaxKnots> value{}, total{};
  std::array<std::size_t, kMaxKnots> count{};
  std::size_t blocks = 0;
  for (std::size_t k = 0; k < n_; ++k) {
    value[blocks] = theta_[k];
    total[blocks] = weight[k];
    count[blocks] = 1;
    ++blocks;
    while (blocks > 1 && value[blocks - 2] < value[blocks - 1]) {
      const double w = total[blocks - 2] + total[blocks - 1];
      value[blocks - 2] = (total[blocks - 2] * value[blocks - 2] + total[blocks - 1] * value[blocks - 1]) / w;
      total[blocks - 2] = w;
      count[blocks - 2] += count[blocks - 1];
      --blocks;
    }
  }
  std::size_t k = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    for (std::size_t i = 0; i < count[b]; ++i) theta_[k++] = value[b];
  }
}

double GroundEffectLearner::dataSamples(std::size_t k) const noexcept {
  double info = 0.0;
  if (k > 0) info += stats_[k - 1].a11;
  if (k + 1 < n_) info += stats_[k].a00;
  return info / w_;
}

double GroundEffectLearner::ratio(double h_m) const noexcept {
  return knotCurve(h_.data(), theta_.data(), n_, h_m);
}

}  // namespace geaware::control
