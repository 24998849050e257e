// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Error-state Kalman filter fusing the IMU (200 Hz) with delayed motion-capture poses (SPEC §4),
// after J. Solà, "Quaternion kinematics for the error-state Kalman filter", 2017 (arXiv
// 1711.02508), §5 (nominal and error-state kinematics), §6 (update) and §7 (injection, reset).
//
// Nominal state x = (p_W, v_W, q_WB, b_a, b_g); error state δx = (δp, δv, δθ, δb_a, δb_g) ∈ ℝ¹⁵
// with the attitude error local to the body (q_true = q ⊗ Exp(δθ), Solà's "local" form).
// World z up; IMU model a_m = R_WBᵀ(a + g·z_W) + b_a + n_a, ω_m = ω + b_g + n_g.
//
// Delay: a MocapSample carries its capture time t_s and arrives later. The filter keeps a
// fixed-capacity ring buffer of the last kHistory IMU samples with the nominal state and
// covariance after each; a pose is fused *at* t_s (the buffered state is propagated to t_s with
// the IMU interpolated between the two neighbouring samples), then the stored IMU samples are
// re-propagated to the present. No allocation per step. See docs/estimation.md for why this
// rather than the cheaper latency-compensated update.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geaware/model/sensor_data.hpp"
#include "geaware/model/state_estimate.hpp"
#include "geaware/model/units.hpp"
#include "geaware/model/field_error.hpp"

namespace geaware::estimation {

/// Noise model and tuning. Continuous-time densities, as on IMU data sheets; the discrete
/// process noise follows from them and the actual sample interval (Solà eq. 262).
/// Defaults: a small quadrotor's MEMS IMU (BMI088 / ICM-42688 class) with the noise floor
/// raised about tenfold for propeller vibration, and a marker-based motion-capture system.
struct EskfParams {
  double imu_rate_hz = 200.0;              ///< nominal IMU rate [Hz] (delay-buffer sizing)
  double accel_noise_density = 2.0e-2;     ///< σ_a, accelerometer white noise [m/s²/√Hz]
  double gyro_noise_density = 1.0e-3;      ///< σ_g, gyro white noise [rad/s/√Hz]
  double accel_bias_random_walk = 1.0e-3;  ///< σ_ba, accel-bias random walk [m/s³/√Hz]
  double gyro_bias_random_walk = 1.0e-4;   ///< σ_bg, gyro-bias random walk [rad/s²/√Hz]
  double mocap_position_std_m = 2.0e-3;    ///< motion-capture position noise, 1σ [m]
  double mocap_attitude_std_rad = 5.0e-3;  ///< motion-capture attitude noise, 1σ [rad]
  double init_position_std_m = 1.0;        ///< initial 1σ of δp [m]
  double init_velocity_std_mps = 1.0;      ///< initial 1σ of δv [m/s]
  double init_attitude_std_rad = 0.35;     ///< initial 1σ of δθ, per axis [rad]
  double init_accel_bias_std_mps2 = 0.5;   ///< initial 1σ of δb_a [m/s²]
  double init_gyro_bias_std_radps = 0.1;   ///< initial 1σ of δb_g [rad/s]
  /// Innovation gate: a pose whose Mahalanobis distance² exceeds this is rejected. The default
  /// is the χ² quantile with 6 degrees of freedom at p = 0.001 [-].
  double gate_chi2 = 22.458;
  /// After this many consecutive gate rejections the filter assumes it, not the mocap, is wrong:
  /// it restarts as at initialisation from the next pose (position and attitude from the pose,
  /// velocity zero; after garbage it can be 1e300 m or hundreds of m/s off, which no Kalman step
  /// corrects) with the position/velocity/attitude covariance re-inflated to its initial value,
  /// and fuses that pose without the gate [-]. 0 disables the recovery.
  int max_consecutive_rejections = 25;
  /// Oldest capture time a pose may have, relative to the newest IMU sample [s]; must fit in the
  /// history buffer (kHistory samples at imu_rate_hz).
  double max_mocap_latency_s = 0.2;
  /// No pose fused for longer than this raises kEskfPoseStale (dead reckoning on the IMU) [s].
  double pose_timeout_s = 0.1;
  /// The IMU's configured full-scale ranges: a sample at either raises kEskfImuClipped. Defaults:
  /// the ±2000 °/s and ±16 g of a flight controller's MEMS IMU (ICM-20602, BMI088 class)
  /// [rad/s], [m/s²].
  double imu_gyro_range_rad_per_s = 34.906585;
  double imu_accel_range_m_per_s2 = 156.9064;
  /// An IMU interval longer than this is still integrated, but counted as a gap [s].
  double max_imu_gap_s = 0.05;
  /// false: fuse every pose as if captured now (the naive filter; kept for comparison and tests).
  bool compensate_delay = true;
  double gravity_mps2 = model::kGravity;  ///< g [m/s²]

  /// Every offending field with its value and expectation; empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// The nominal state.
struct EskfState {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();             ///< position [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();             ///< velocity [m/s]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  ///< attitude, body → world
  Eigen::Vector3d accel_bias_B = Eigen::Vector3d::Zero();    ///< b_a [m/s²]
  Eigen::Vector3d gyro_bias_B = Eigen::Vector3d::Zero();     ///< b_g [rad/s]
};

/// What happened to one sample.
enum class EskfStatus : std::uint8_t {
  kOk,                 ///< propagated / fused
  kNotInitialised,     ///< IMU before the first pose or initialise(): time recorded only
  kInitialised,        ///< this pose initialised the filter
  kNonFinite,          ///< NaN/∞ in the sample (or a zero quaternion): rejected
  /// IMU time ≤ the previous one or more than kHistory samples after it; a pose older than the
  /// last fused or captured over max_mocap_latency_s after the newest IMU sample. After kHistory
  /// IMU rejections in a row the filter restarts its history at the rejected sample (p, v, θ
  /// covariance re-inflated): a garbage time far ahead cannot stop it for good.
  kTimeNotIncreasing,
  kTooOld,             ///< pose captured before the oldest buffered IMU sample
  kDeferred,           ///< pose captured after the newest IMU sample: fused when the IMU passes it
  kGateRejected,       ///< innovation failed the χ² gate
  kQueueFull,          ///< too many deferred poses: dropped
};

[[nodiscard]] const char* toString(EskfStatus s) noexcept;

/// Counters of every rejection and event since construction/reset.
struct EskfCounters {
  std::uint64_t imu_propagated = 0;
  std::uint64_t imu_non_finite = 0;
  std::uint64_t imu_time_rejected = 0;
  std::uint64_t imu_gaps = 0;
  std::uint64_t mocap_fused = 0;
  std::uint64_t mocap_non_finite = 0;
  std::uint64_t mocap_out_of_order = 0;
  std::uint64_t mocap_too_old = 0;
  std::uint64_t mocap_gate_rejected = 0;
  std::uint64_t mocap_dropped = 0;    ///< deferred queue overflow
  std::uint64_t gate_recoveries = 0;  ///< covariance re-inflations after repeated rejections
};

/// The filter's output at the newest IMU time.
/// Named conditions of the estimate a user can see in the flight log (EskfOutput::flags).
enum EskfFlag : std::uint32_t {
  kEskfFlagNone = 0,
  kEskfPoseStale = 1u << 0,     ///< no pose fused for longer than pose_timeout_s: IMU dead reckoning
  kEskfImuClipped = 1u << 1,    ///< the newest IMU sample is at a full-scale range
  kEskfPoseRejected = 1u << 2,  ///< the last pose(s) failed the innovation gate
};

struct EskfOutput {
  double t_s = 0.0;  ///< time of the newest IMU sample [s]
  bool initialised = false;
  model::StateEstimate estimate;                      ///< p, v, q for the controller
  Eigen::Vector3d gyro_B = Eigen::Vector3d::Zero();   ///< ω_m − b_g [rad/s]
  Eigen::Vector3d accel_B = Eigen::Vector3d::Zero();  ///< a_m − b_a, specific force [m/s²]
  Eigen::Vector3d accel_bias_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_B = Eigen::Vector3d::Zero();
  /// Variances of (δp, δv, δθ, δb_a, δb_g) [m², m²/s², rad², m²/s⁴, rad²/s²].
  Eigen::Matrix<double, 15, 1> covariance_diagonal = Eigen::Matrix<double, 15, 1>::Zero();
  double last_innovation_chi2 = 0.0;  ///< Mahalanobis² of the last pose [-]
  std::uint32_t flags = kEskfFlagNone;  ///< EskfFlag bits
};

class Eskf {
 public:
  using Cov = Eigen::Matrix<double, 15, 15>;
  /// Buffered IMU samples (320 ms at 200 Hz): bounds the compensable mocap latency.
  static constexpr int kHistory = 64;
  /// Poses whose capture time is ahead of the IMU wait here.
  static constexpr int kDeferredCapacity = 4;

  /// Validates params (throws model::InvalidParameters listing the offending fields).
  explicit Eskf(EskfParams params);

  /// Starts from a given state at time t_s with the initial covariance of the params. Without
  /// this call the first accepted pose initialises p and q (v and the biases at zero).
  void initialise(const EskfState& state, double t_s) noexcept;

  /// Forgets everything (state, history, counters).
  void reset() noexcept;

  /// Integrates one IMU sample; then fuses deferred poses that the IMU time has reached.
  /// Non-finite samples and non-increasing times are rejected and counted.
  EskfStatus addImu(const model::ImuSample& imu) noexcept;

  /// Fuses a pose captured at mocap.t_s ≤ now (see the class comment); one captured after the
  /// newest IMU sample is deferred. Poses must arrive in capture-time order.
  EskfStatus addMocap(const model::MocapSample& mocap) noexcept;

  [[nodiscard]] EskfOutput output() const noexcept;
  [[nodiscard]] const EskfState& state() const noexcept;
  [[nodiscard]] const Cov& covariance() const noexcept;
  [[nodiscard]] const EskfCounters& counters() const noexcept { return counters_; }
  [[nodiscard]] bool initialised() const noexcept { return initialised_; }
  [[nodiscard]] const EskfParams& params() const noexcept { return params_; }

 private:
  /// One buffered IMU sample and the filter state after integrating up to its time.
  struct Entry {
    double t_s = 0.0;
    Eigen::Vector3d gyro_B = Eigen::Vector3d::Zero();
    Eigen::Vector3d accel_B = Eigen::Vector3d::Zero();
    bool has_imu = false;  ///< false for a start entry made without an IMU sample
    EskfState x;
    Cov P = Cov::Zero();
  };

  /// Integrates x, P over dt with IMU values (w0, a0) at the start and (w1, a1) at the end.
  void propagate(EskfState& x, Cov& P, const Eigen::Vector3d& w0, const Eigen::Vector3d& a0,
                 const Eigen::Vector3d& w1, const Eigen::Vector3d& a1, double dt) const noexcept;
  /// Gated pose update of (x, P) in place; false (unchanged) when rejected.
  bool update(EskfState& x, Cov& P, const model::MocapSample& m, bool gated) noexcept;
  EskfStatus fuseNow(const model::MocapSample& m) noexcept;
  [[nodiscard]] Cov initialCovariance() const noexcept;
  /// Forgets what the filter believed about p, v and θ (and their correlations).
  void reinflate(Cov& P) const noexcept;
  /// The gate recovery: reinflate(P), p and q from the pose `m` (normalised), v back to zero.
  void restart(EskfState& x, Cov& P, const model::MocapSample& m) const noexcept;
  /// Restarts the history at `imu`'s time from the newest state (see kTimeNotIncreasing).
  void rebase(const model::ImuSample& imu) noexcept;
  /// After an update at entry k's capture time t_s (state x, P; IMU w_s, a_s there, dt1 after
  /// entry k): re-propagates the stored IMU samples from t_s to now, overwriting the buffer.
  void repropagate(int k, const EskfState& x, const Cov& P, const Eigen::Vector3d& w_s,
                   const Eigen::Vector3d& a_s, double dt1, double t_s) noexcept;
  [[nodiscard]] Entry& at(int age) noexcept;  ///< age 0: newest
  [[nodiscard]] const Entry& at(int age) const noexcept;
  void push(const Entry& e) noexcept;

  EskfParams params_;
  std::array<Entry, kHistory> history_{};
  int head_ = -1;  ///< index of the newest entry
  int count_ = 0;  ///< valid entries
  std::array<model::MocapSample, kDeferredCapacity> deferred_{};
  int deferred_count_ = 0;
  bool initialised_ = false;
  double last_fused_t_s_;
  int consecutive_rejections_ = 0;
  int time_rejections_ = 0;  ///< consecutive IMU time rejections
  double last_chi2_ = 0.0;
  EskfCounters counters_;
  // Before initialisation: the newest IMU sample (time and values), so the first pose can
  // start the buffer.
  bool have_imu_ = false;
  model::ImuSample last_imu_;
};

}  // namespace geaware::estimation
