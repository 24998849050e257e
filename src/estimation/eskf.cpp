// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/estimation/eskf.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geaware/model/field_check.hpp"
#include "geaware/model/finite.hpp"
#include "geaware/model/imu_limits.hpp"
#include "geaware/model/rotation.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::estimation {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Cov = Eskf::Cov;

// Offsets of the error-state blocks.
constexpr int kP = 0, kV = 3, kTh = 6, kBa = 9, kBg = 12;

Mat3 skew(const Vec3& w) {
  Mat3 S;
  S << 0.0, -w.z(), w.y(),  //
      w.z(), 0.0, -w.x(),   //
      -w.y(), w.x(), 0.0;
  return S;
}

bool finite(const Vec3& v) { return model::allFinite(v); }
bool finite(const EskfState& x, const Cov& P) {
  return model::allFinite(x.p_W) && model::allFinite(x.v_W) && model::allFinite(x.q_WB.coeffs()) &&
         model::allFinite(x.accel_bias_B) && model::allFinite(x.gyro_bias_B) && model::allFinite(P);
}

/// M ← F·M for the error-state transition of one IMU interval (Solà eq. 269), using its block
/// structure: F = I except F_pv = I·dt, F_vθ = A, F_vba = B, F_θθ = C, F_θbg = −I·dt.
/// About a seventh of the flops of a dense 15×15 product.
void applyTransition(Cov& M, double dt, const Mat3& A, const Mat3& B, const Mat3& C) {
  M.middleRows<3>(kP) += dt * M.middleRows<3>(kV);
  M.middleRows<3>(kV) += A * M.middleRows<3>(kTh) + B * M.middleRows<3>(kBa);
  const Eigen::Matrix<double, 3, 15> th = C * M.middleRows<3>(kTh) - dt * M.middleRows<3>(kBg);
  M.middleRows<3>(kTh) = th;
}

}  // namespace

Eskf::Eskf(EskfParams params)
    : params_(params), last_fused_t_s_(-std::numeric_limits<double>::infinity()) {
  if (auto errors = params_.validate(); !errors.empty())
    throw model::InvalidParameters(std::move(errors));
}

void Eskf::reset() noexcept {
  head_ = -1;
  count_ = 0;
  deferred_count_ = 0;
  initialised_ = false;
  last_fused_t_s_ = -std::numeric_limits<double>::infinity();
  consecutive_rejections_ = time_rejections_ = 0;
  last_chi2_ = 0.0;
  counters_ = EskfCounters{};
  have_imu_ = false;
}

Cov Eskf::initialCovariance() const noexcept {
  Eigen::Matrix<double, 15, 1> d;
  d << Vec3::Constant(params_.init_position_std_m), Vec3::Constant(params_.init_velocity_std_mps),
      Vec3::Constant(params_.init_attitude_std_rad),
      Vec3::Constant(params_.init_accel_bias_std_mps2),
      Vec3::Constant(params_.init_gyro_bias_std_radps);
  return d.cwiseAbs2().asDiagonal();
}

Eskf::Entry& Eskf::at(int age) noexcept {
  return history_[static_cast<std::size_t>((head_ - age + kHistory) % kHistory)];
}
const Eskf::Entry& Eskf::at(int age) const noexcept {
  return history_[static_cast<std::size_t>((head_ - age + kHistory) % kHistory)];
}

void Eskf::push(const Entry& e) noexcept {
  head_ = (head_ + 1) % kHistory;
  history_[static_cast<std::size_t>(head_)] = e;
  if (count_ < kHistory) ++count_;
}

void Eskf::initialise(const EskfState& state, double t_s) noexcept {
  reset();
  Entry e;
  e.t_s = t_s;
  e.x = state;
  e.x.q_WB.normalize();
  e.P = initialCovariance();
  e.has_imu = false;
  push(e);
  initialised_ = true;
}

void Eskf::propagate(EskfState& x, Cov& P, const Vec3& w0, const Vec3& a0, const Vec3& w1,
                     const Vec3& a1, double dt) const noexcept {
  // Nominal kinematics (Solà eq. 260) with the midpoint rule: IMU values averaged over the
  // interval and the rotation taken at its middle, so a smooth motion integrates to second order.
  const Vec3 w = 0.5 * (w0 + w1) - x.gyro_bias_B;
  const Vec3 a = 0.5 * (a0 + a1) - x.accel_bias_B;
  const Mat3 R_mid = (x.q_WB * model::expMap(0.5 * dt * w)).toRotationMatrix();
  const Vec3 a_W = R_mid * a - params_.gravity_mps2 * Vec3::UnitZ();
  x.p_W += x.v_W * dt + 0.5 * dt * dt * a_W;
  x.v_W += a_W * dt;
  const Eigen::Quaterniond dq = model::expMap(w * dt);
  x.q_WB = (x.q_WB * dq).normalized();

  // Error-state covariance (Solà eqs. 269–270): P ← F·P·Fᵀ + Q, with Q from the continuous
  // densities, V_i = σ_a²·dt, Θ_i = σ_g²·dt, A_i = σ_ba²·dt, Ω_i = σ_bg²·dt (eq. 262).
  const Mat3 A = -R_mid * skew(a) * dt;
  const Mat3 B = -R_mid * dt;
  const Mat3 C = dq.toRotationMatrix().transpose();
  applyTransition(P, dt, A, B, C);  // F·P
  P.transposeInPlace();             // (F·P)ᵀ = P·Fᵀ
  applyTransition(P, dt, A, B, C);  // F·P·Fᵀ
  const double qa = params_.accel_noise_density * params_.accel_noise_density * dt;
  const double qg = params_.gyro_noise_density * params_.gyro_noise_density * dt;
  const double qba = params_.accel_bias_random_walk * params_.accel_bias_random_walk * dt;
  const double qbg = params_.gyro_bias_random_walk * params_.gyro_bias_random_walk * dt;
  P.diagonal().segment<3>(kV).array() += qa;
  P.diagonal().segment<3>(kTh).array() += qg;
  P.diagonal().segment<3>(kBa).array() += qba;
  P.diagonal().segment<3>(kBg).array() += qbg;
  P = 0.5 * (P + P.transpose()).eval();
}

bool Eskf::update(EskfState& x, Cov& P, const model::MocapSample& m, bool gated) noexcept {
  // Pose measurement h(x) = (p, q); residual (Solà §6.1) with the attitude part as the local
  // rotation vector Log(q̂⁻¹ ⊗ q_m), so H selects δp and δθ (the Jacobian of Log at the small
  // residual is I to first order).
  Vec6 r;
  r.head<3>() = m.p_W - x.p_W;
  r.tail<3>() = model::logMap(x.q_WB.conjugate() * m.q_WB);
  Mat6 S;
  S.topLeftCorner<3, 3>() = P.block<3, 3>(kP, kP);
  S.topRightCorner<3, 3>() = P.block<3, 3>(kP, kTh);
  S.bottomLeftCorner<3, 3>() = P.block<3, 3>(kTh, kP);
  S.bottomRightCorner<3, 3>() = P.block<3, 3>(kTh, kTh);
  Vec6 r_diag;
  r_diag << Vec3::Constant(params_.mocap_position_std_m * params_.mocap_position_std_m),
      Vec3::Constant(params_.mocap_attitude_std_rad * params_.mocap_attitude_std_rad);
  S.diagonal() += r_diag;
  const Eigen::LDLT<Mat6> ldlt(S);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return false;
  last_chi2_ = r.dot(ldlt.solve(r));
  if (!std::isfinite(last_chi2_)) return false;
  if (gated && last_chi2_ > params_.gate_chi2) return false;

  // K = P·Hᵀ·S⁻¹; P·Hᵀ is the δp and δθ columns of P.
  Eigen::Matrix<double, 15, 6> PHt;
  PHt.leftCols<3>() = P.middleCols<3>(kP);
  PHt.rightCols<3>() = P.middleCols<3>(kTh);
  const Eigen::Matrix<double, 15, 6> K = ldlt.solve(PHt.transpose()).transpose();
  const Eigen::Matrix<double, 15, 1> dx = K * r;

  // Joseph form P ← (I − K·H)·P·(I − K·H)ᵀ + K·R·Kᵀ: stays symmetric positive definite under
  // round-off, which the short form P − K·S·Kᵀ does not guarantee. H only selects blocks, so
  // (I − K·H)·P = P − K·(H·P) and M·(I − K·H)ᵀ = M − (M·Hᵀ)·Kᵀ: the same products without
  // the multiplications by the zeros of H (about half the flops of the dense form).
  Eigen::Matrix<double, 6, 15> HP;
  HP.topRows<3>() = P.middleRows<3>(kP);
  HP.bottomRows<3>() = P.middleRows<3>(kTh);
  Cov M = P;
  M.noalias() -= K * HP;
  Eigen::Matrix<double, 15, 6> MHt;
  MHt.leftCols<3>() = M.middleCols<3>(kP);
  MHt.rightCols<3>() = M.middleCols<3>(kTh);
  P = M;
  P.noalias() -= MHt * K.transpose();
  P.noalias() += K * r_diag.asDiagonal() * K.transpose();

  // Injection (Solà eq. 283) and reset (eqs. 285–287): G = I except G_θθ = I − [½·δθ]×.
  x.p_W += dx.segment<3>(kP);
  x.v_W += dx.segment<3>(kV);
  x.q_WB = (x.q_WB * model::expMap(dx.segment<3>(kTh))).normalized();
  x.accel_bias_B += dx.segment<3>(kBa);
  x.gyro_bias_B += dx.segment<3>(kBg);
  const Mat3 G = Mat3::Identity() - skew(0.5 * dx.segment<3>(kTh));
  P.middleRows<3>(kTh) = (G * P.middleRows<3>(kTh)).eval();
  P.middleCols<3>(kTh) = (P.middleCols<3>(kTh) * G.transpose()).eval();
  P = 0.5 * (P + P.transpose()).eval();
  return true;
}

EskfStatus Eskf::addImu(const model::ImuSample& imu) noexcept {
  if (!(std::isfinite(imu.t_s) && model::plausibleImu(imu.gyro_B, imu.accel_B))) {
    ++counters_.imu_non_finite;
    return EskfStatus::kNonFinite;
  }
  if (!initialised_) {
    if (have_imu_ && !(imu.t_s > last_imu_.t_s)) {
      ++counters_.imu_time_rejected;
      return EskfStatus::kTimeNotIncreasing;
    }
    last_imu_ = imu;
    have_imu_ = true;
    return EskfStatus::kNotInitialised;
  }
  const Entry& prev = at(0);
  const double dt = imu.t_s - prev.t_s;
  if (!(dt > 0.0 && dt <= kHistory / params_.imu_rate_hz)) {
    ++counters_.imu_time_rejected;
    // A garbage time far ahead would refuse every later sample: after kHistory rejections in a
    // row the filter assumes its own time is wrong and restarts its history at this sample.
    if (++time_rejections_ < kHistory) return EskfStatus::kTimeNotIncreasing;
    rebase(imu);
    return EskfStatus::kTimeNotIncreasing;
  }
  time_rejections_ = 0;
  if (dt > params_.max_imu_gap_s) ++counters_.imu_gaps;

  // Write the new entry straight into its ring slot: no temporary copy of P.
  const int slot = (head_ + 1) % kHistory;
  Entry& e = history_[static_cast<std::size_t>(slot)];
  if (&e != &prev) {
    e.x = prev.x;
    e.P = prev.P;
  }
  const Vec3 w0 = prev.has_imu ? prev.gyro_B : imu.gyro_B;
  const Vec3 a0 = prev.has_imu ? prev.accel_B : imu.accel_B;
  e.t_s = imu.t_s;
  e.gyro_B = imu.gyro_B;
  e.accel_B = imu.accel_B;
  e.has_imu = true;
  propagate(e.x, e.P, w0, a0, imu.gyro_B, imu.accel_B, dt);
  if (!finite(e.x, e.P)) {  // finite inputs that overflowed: not committed (slot now unused)
    if (count_ == kHistory) --count_;
    ++counters_.imu_non_finite;
    return EskfStatus::kNonFinite;
  }
  head_ = slot;
  if (count_ < kHistory) ++count_;
  ++counters_.imu_propagated;

  // Poses that were captured ahead of the IMU can be fused now.
  while (deferred_count_ > 0 && deferred_[0].t_s <= imu.t_s) {
    const model::MocapSample m = deferred_[0];
    for (int i = 1; i < deferred_count_; ++i)
      deferred_[static_cast<std::size_t>(i - 1)] = deferred_[static_cast<std::size_t>(i)];
    --deferred_count_;
    (void)fuseNow(m);
  }
  return EskfStatus::kOk;
}

EskfStatus Eskf::addMocap(const model::MocapSample& mocap) noexcept {
  const double qn = mocap.q_WB.norm();
  if (!(std::isfinite(mocap.t_s) && finite(mocap.p_W) && model::allFinite(mocap.q_WB.coeffs()) &&
        qn > 0.5 && qn < 2.0)) {
    ++counters_.mocap_non_finite;
    return EskfStatus::kNonFinite;
  }
  model::MocapSample m = mocap;
  m.q_WB.normalize();

  if (!initialised_) {
    // Start at the pose, at the newest IMU time if there is one (the IMU samples before are
    // gone; the small latency error is corrected by the following poses).
    Entry e;
    e.t_s = have_imu_ ? std::max(last_imu_.t_s, m.t_s) : m.t_s;
    e.x.p_W = m.p_W;
    e.x.q_WB = m.q_WB;
    e.P = initialCovariance();
    e.has_imu = have_imu_;
    if (have_imu_) {
      e.gyro_B = last_imu_.gyro_B;
      e.accel_B = last_imu_.accel_B;
    }
    head_ = -1;
    count_ = 0;
    deferred_count_ = 0;
    consecutive_rejections_ = 0;
    push(e);
    initialised_ = true;
    last_fused_t_s_ = m.t_s;
    ++counters_.mocap_fused;
    return EskfStatus::kInitialised;
  }

  const double last = deferred_count_ > 0
                          ? deferred_[static_cast<std::size_t>(deferred_count_ - 1)].t_s
                          : last_fused_t_s_;
  if (!(m.t_s > last)) {
    ++counters_.mocap_out_of_order;
    return EskfStatus::kTimeNotIncreasing;
  }
  if (m.t_s > at(0).t_s) {
    if (m.t_s - at(0).t_s > params_.max_mocap_latency_s) {  // far ahead: would block the queue
      ++counters_.mocap_out_of_order;
      return EskfStatus::kTimeNotIncreasing;
    }
    if (deferred_count_ == kDeferredCapacity) {
      ++counters_.mocap_dropped;
      return EskfStatus::kQueueFull;
    }
    deferred_[static_cast<std::size_t>(deferred_count_++)] = m;
    return EskfStatus::kDeferred;
  }
  return fuseNow(m);
}

void Eskf::rebase(const model::ImuSample& imu) noexcept {
  Entry e = at(0);
  e.t_s = imu.t_s;
  e.gyro_B = imu.gyro_B;
  e.accel_B = imu.accel_B;
  e.has_imu = true;
  reinflate(e.P);
  head_ = -1;
  count_ = deferred_count_ = time_rejections_ = 0;
  last_fused_t_s_ = -std::numeric_limits<double>::infinity();
  push(e);
}

void Eskf::restart(EskfState& x, Cov& P, const model::MocapSample& m) const noexcept {
  // As at initialisation: p and q from the pose, at rest. A Kalman step from a state 1e300 m off
  // lost the pose to cancellation and never came back.
  reinflate(P);
  x.p_W = m.p_W;
  x.q_WB = m.q_WB;
  x.v_W.setZero();
}

void Eskf::reinflate(Cov& P) const noexcept {
  const Cov P0 = initialCovariance();
  for (int blk : {kP, kV, kTh}) {
    P.middleRows<3>(blk).setZero();
    P.middleCols<3>(blk).setZero();
    P.block<3, 3>(blk, blk) = P0.block<3, 3>(blk, blk);
  }
}

void Eskf::repropagate(int k, const EskfState& x, const Cov& P, const Vec3& w_s, const Vec3& a_s,
                       double dt1, double t_s) noexcept {
  int j = k;
  if (dt1 > 0.0 && k > 0) {
    Entry& next = at(k - 1);
    next.x = x;
    next.P = P;
    propagate(next.x, next.P, w_s, a_s, next.gyro_B, next.accel_B, next.t_s - t_s);
    j = k - 1;
  } else {
    Entry& e = at(k);
    e.x = x;
    e.P = P;
  }
  for (; j > 0; --j) {
    const Entry& from = at(j);
    Entry& to = at(j - 1);
    to.x = from.x;
    to.P = from.P;
    propagate(to.x, to.P, from.has_imu ? from.gyro_B : to.gyro_B,
              from.has_imu ? from.accel_B : to.accel_B, to.gyro_B, to.accel_B, to.t_s - from.t_s);
  }
}

EskfStatus Eskf::fuseNow(const model::MocapSample& m) noexcept {
  last_fused_t_s_ = m.t_s;
  const bool recover = params_.max_consecutive_rejections > 0 &&
                       consecutive_rejections_ >= params_.max_consecutive_rejections;
  const auto rejected = [this]() {
    ++counters_.mocap_gate_rejected;
    ++consecutive_rejections_;
    return EskfStatus::kGateRejected;
  };
  const auto accepted = [this, recover]() {
    ++counters_.mocap_fused;
    if (recover) ++counters_.gate_recoveries;
    consecutive_rejections_ = 0;
    return EskfStatus::kOk;
  };

  if (!params_.compensate_delay) {
    // The naive filter: the pose is treated as a measurement of the newest state.
    Entry& e = at(0);
    EskfState x = e.x;
    Cov P = e.P;
    if (recover) restart(x, P, m);
    if (!update(x, P, m, !recover) || !finite(x, P)) return rejected();
    e.x = x;
    e.P = P;
    return accepted();
  }

  // 1. Newest buffered entry k at or before the capture time.
  int k = 0;
  while (k < count_ && at(k).t_s > m.t_s) ++k;
  if (k == count_ || at(0).t_s - m.t_s > params_.max_mocap_latency_s) {
    ++counters_.mocap_too_old;
    return EskfStatus::kTooOld;
  }

  // 2. State at t_s: entry k, propagated over [t_k, t_s] with the IMU interpolated linearly
  //    between samples k and k−1.
  const Entry& ek = at(k);
  EskfState x = ek.x;
  Cov P = ek.P;
  const double dt1 = m.t_s - ek.t_s;
  Vec3 w_s = ek.gyro_B, a_s = ek.accel_B;
  if (k > 0 && dt1 > 0.0) {
    const Entry& next = at(k - 1);
    const double alpha = dt1 / (next.t_s - ek.t_s);
    const Vec3 w_k = ek.has_imu ? ek.gyro_B : next.gyro_B;
    const Vec3 a_k = ek.has_imu ? ek.accel_B : next.accel_B;
    w_s = w_k + alpha * (next.gyro_B - w_k);
    a_s = a_k + alpha * (next.accel_B - a_k);
    propagate(x, P, w_k, a_k, w_s, a_s, dt1);
  }

  // 3. Gated update at t_s.
  if (recover) restart(x, P, m);
  if (!update(x, P, m, !recover) || !finite(x, P)) return rejected();

  // 4. Re-propagate the stored IMU samples from t_s to now.
  repropagate(k, x, P, w_s, a_s, dt1, m.t_s);
  return accepted();
}

const EskfState& Eskf::state() const noexcept {
  static const EskfState kEmpty{};
  return count_ > 0 ? at(0).x : kEmpty;
}

const Eskf::Cov& Eskf::covariance() const noexcept {
  static const Cov kZero = Cov::Zero();
  return count_ > 0 ? at(0).P : kZero;
}

EskfOutput Eskf::output() const noexcept {
  EskfOutput out;
  out.initialised = initialised_;
  out.last_innovation_chi2 = last_chi2_;
  if (count_ == 0) return out;
  const Entry& e = at(0);
  out.t_s = e.t_s;
  out.estimate.p_W = e.x.p_W;
  out.estimate.v_W = e.x.v_W;
  out.estimate.q_WB = e.x.q_WB;
  out.accel_bias_B = e.x.accel_bias_B;
  out.gyro_bias_B = e.x.gyro_bias_B;
  if (e.has_imu) {
    out.gyro_B = e.gyro_B - e.x.gyro_bias_B;
    out.accel_B = e.accel_B - e.x.accel_bias_B;
  }
  out.covariance_diagonal = e.P.diagonal();
  if (initialised_ && e.t_s - last_fused_t_s_ > params_.pose_timeout_s) out.flags |= kEskfPoseStale;
  if (e.has_imu && (e.gyro_B.cwiseAbs().maxCoeff() >= params_.imu_gyro_range_rad_per_s ||
                    e.accel_B.cwiseAbs().maxCoeff() >= params_.imu_accel_range_m_per_s2)) {
    out.flags |= kEskfImuClipped;
  }
  if (consecutive_rejections_ > 0) out.flags |= kEskfPoseRejected;
  return out;
}

}  // namespace geaware::estimation
