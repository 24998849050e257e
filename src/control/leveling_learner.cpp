// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/control/leveling_learner.hpp"

#include <algorithm>
#include <cmath>

#include "geaware/model/field_check.hpp"
#include "geaware/model/finite.hpp"
#include "geaware/model/vehicle_model.hpp"  // model::InvalidParameters

namespace geaware::control {

std::vector<model::FieldError> LevelingLearnerParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e);
  using enum model::LowerBound;
  c.range("scale_walk_sigma", scale_walk_sigma, 0.0, 1.0, kInclusive);
  c.range("bias_walk_sigma_Nm", bias_walk_sigma_Nm, 0.0, 1.0, kInclusive, "N·m");
  c.range("sample_sigma_Nm", sample_sigma_Nm, 0.0, 100.0, kExclusive, "N·m");
  c.range("prior_sigma", prior_sigma, 0.0, 1e3, kExclusive);
  c.range("no_model_prior_sigma", no_model_prior_sigma, 0.0, 1e3, kExclusive);
  c.range("bias_sigma_Nm", bias_sigma_Nm, 0.0, 1e3, kExclusive, "N·m");
  if (c.finite("min_scale", min_scale) && c.finite("max_scale", max_scale) && !(min_scale < max_scale)) {
    c.fail("max_scale", model::formatValue(max_scale), "above min_scale = " + model::formatValue(min_scale));
  }
  c.range("min_regressor_Nm", min_regressor_Nm, 0.0, 100.0, kExclusive, "N·m");
  c.range("learned_sigma", learned_sigma, 0.0, 1e3, kExclusive);
  c.range("max_abs_sample_Nm", max_abs_sample_Nm, 0.0, 1e3, kExclusive, "N·m");
  c.range("max_tilt_rad", max_tilt_rad, 0.0, 1.5, kExclusive, "rad");
  c.range("max_speed_mps", max_speed_mps, 0.0, 100.0, kExclusive, "m/s");
  c.range("max_climb_mps", max_climb_mps, 0.0, 100.0, kExclusive, "m/s");
  if (c.range("reference_mass_kg", reference_mass_kg, 0.0, 1000.0, kInclusive, "kg") && reference_mass_kg > 0.0) {
    c.range("reference_diagonal_m", reference_diagonal_m, 0.0, 10.0, kExclusive, "m");
  }
  return e;
}

namespace {

const LevelingLearnerParams& checked(const LevelingLearnerParams& p, double prior_scale) {
  auto e = p.validate();
  if (!std::isfinite(prior_scale)) e.push_back({"prior_scale", model::formatValue(prior_scale), "a finite scale"});
  if (!e.empty()) throw model::InvalidParameters(std::move(e));
  return p;
}

}  // namespace

LevelingLearner::LevelingLearner(const LevelingLearnerParams& params, double prior_scale)
    : p_(checked(params, prior_scale)),
      r_(params.sample_sigma_Nm * params.sample_sigma_Nm),
      published_(std::clamp(prior_scale, params.min_scale, params.max_scale)) {
  const double sigma_s = prior_scale == 0.0 ? params.no_model_prior_sigma : params.prior_sigma;
  const double var_b = params.bias_sigma_Nm * params.bias_sigma_Nm;
  P_.diagonal() << sigma_s * sigma_s, var_b, var_b;
  theta_ << prior_scale, 0.0, 0.0;
}

double LevelingLearner::scaleSigma() const noexcept { return std::sqrt(P_(0, 0)); }

LearnerSample LevelingLearner::update(const Eigen::Vector2d& x_B_Nm, const Eigen::Vector2d& y_B_Nm,
                                      double tilt_rad, double speed_mps, double climb_mps) noexcept {
  if (!(model::allFinite(x_B_Nm) && model::allFinite(y_B_Nm) && std::isfinite(tilt_rad) &&
        std::isfinite(speed_mps) && std::isfinite(climb_mps))) {
    return LearnerSample::kNonFinite;
  }
  if (y_B_Nm.cwiseAbs().maxCoeff() > p_.max_abs_sample_Nm) return LearnerSample::kOutlier;
  if (std::abs(tilt_rad) > p_.max_tilt_rad) return LearnerSample::kTilted;
  if (std::abs(speed_mps) > p_.max_speed_mps) return LearnerSample::kFast;
  if (std::abs(climb_mps) > p_.max_climb_mps) return LearnerSample::kClimbing;
  if (!(x_B_Nm.norm() >= p_.min_regressor_Nm)) return LearnerSample::kUnexcited;
  // The random walk, then y_a = s·x_a + b_a on each axis: φ_x = (x_x, 1, 0), φ_y = (x_y, 0, 1).
  P_(0, 0) += p_.scale_walk_sigma * p_.scale_walk_sigma;
  P_(1, 1) += p_.bias_walk_sigma_Nm * p_.bias_walk_sigma_Nm;
  P_(2, 2) += p_.bias_walk_sigma_Nm * p_.bias_walk_sigma_Nm;
  addRow(Eigen::Vector3d(x_B_Nm.x(), 1.0, 0.0), y_B_Nm.x());
  addRow(Eigen::Vector3d(x_B_Nm.y(), 0.0, 1.0), y_B_Nm.y());
  ++used_;
  if (scaleSigma() <= p_.learned_sigma) {
    published_ = std::clamp(theta_(0), p_.min_scale, p_.max_scale);
    learned_ = true;
  }
  return LearnerSample::kUsed;
}

void LevelingLearner::addRow(const Eigen::Vector3d& phi, double y) noexcept {
  // The Kalman update in Joseph form, P ← (I − Kφᵀ)·P·(I − Kφᵀ)ᵀ + K·σ²·Kᵀ, which keeps P
  // symmetric and positive definite however small σ² is against φᵀPφ.
  const Eigen::Vector3d Pphi = P_ * phi;
  const Eigen::Vector3d K = Pphi / (phi.dot(Pphi) + r_);
  theta_ += K * (y - phi.dot(theta_));
  const Eigen::Matrix3d I_KH = Eigen::Matrix3d::Identity() - K * phi.transpose();
  P_ = I_KH * P_ * I_KH.transpose() + r_ * (K * K.transpose());
}

}  // namespace geaware::control
