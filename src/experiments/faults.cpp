// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/faults.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "geaware/model/units.hpp"

namespace geaware::experiments {
namespace {

constexpr double kGyroClipRadps = 250.0 * std::numbers::pi / 180.0;  // ±250 °/s
constexpr double kAccelClipMps2 = 4.0 * model::kGravity;             // ±4 g
constexpr double kKickDuration_s = 0.1;

std::string formatNumber(double v) {
  std::string s = std::to_string(v);
  return s;
}

/// A body torque about x of `torque_Nm` during [t0, t0 + kKickDuration_s) of plant time.
class KickContribution final : public sim::Contribution {
 public:
  explicit KickContribution(std::vector<std::pair<double, double>> kicks) : kicks_(std::move(kicks)) {}
  [[nodiscard]] const char* name() const noexcept override { return "fault_kick"; }
  [[nodiscard]] bool readsSurroundings() const noexcept override { return false; }
  [[nodiscard]] sim::Wrench wrench(const sim::ContributionContext& ctx) noexcept override {
    sim::Wrench w;
    for (const auto& [t0, torque] : kicks_) {
      if (ctx.t_s >= t0 && ctx.t_s < t0 + kKickDuration_s) w.torque_B.x() += torque;
    }
    return w;
  }

 private:
  std::vector<std::pair<double, double>> kicks_;  // (plant time [s], torque [N·m])
};

}  // namespace

const char* toString(FaultKind k) noexcept {
  switch (k) {
    case FaultKind::kMotorEffectiveness: return "motor_effectiveness";
    case FaultKind::kMotorStop: return "motor_stop";
    case FaultKind::kMocapDropout: return "mocap_dropout";
    case FaultKind::kRangerOutliers: return "ranger_outliers";
    case FaultKind::kRangerDead: return "ranger_dead";
    case FaultKind::kImuClipKick: return "imu_clip_kick";
    case FaultKind::kGyroBiasStep: return "gyro_bias_step";
    case FaultKind::kBatterySag: return "battery_sag";
    case FaultKind::kGust: return "gust";
  }
  return "?";
}

std::vector<model::FieldError> validate(const std::vector<Fault>& faults) {
  std::vector<model::FieldError> out;
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const Fault& f = faults[i];
    const std::string p = "faults[" + std::to_string(i) + "].";
    if (!(std::isfinite(f.start_s) && f.start_s >= 0.0)) out.push_back({p + "start_s", formatNumber(f.start_s), "finite, ≥ 0 s"});
    if (!(f.duration_s > 0.0)) out.push_back({p + "duration_s", formatNumber(f.duration_s), "> 0 s (∞: to the end)"});
    const bool motor = f.kind == FaultKind::kMotorEffectiveness || f.kind == FaultKind::kMotorStop;
    if (motor && (f.motor < 0 || f.motor > 3)) out.push_back({p + "motor", std::to_string(f.motor), "0, 1, 2 or 3"});
    const auto range = [&](double lo, double hi, const char* what) {
      if (!(f.value >= lo && f.value <= hi)) out.push_back({p + "value", formatNumber(f.value), what});
    };
    switch (f.kind) {
      case FaultKind::kMotorEffectiveness: range(0.0, 1.0, "thrust fraction in [0, 1]"); break;
      case FaultKind::kRangerOutliers: range(0.0, 1.0, "probability per zone in [0, 1]"); break;
      case FaultKind::kImuClipKick: range(-10.0, 10.0, "kick torque in [−10, 10] N·m"); break;
      case FaultKind::kGyroBiasStep: range(-1.0, 1.0, "bias step in [−1, 1] rad/s"); break;
      case FaultKind::kBatterySag: range(0.3, 1.0, "voltage fraction in [0.3, 1]"); break;
      case FaultKind::kGust: range(-30.0, 30.0, "gust speed in [−30, 30] m/s"); break;
      default: break;
    }
    if (f.kind == FaultKind::kGust && !std::isfinite(f.duration_s)) {
      out.push_back({p + "duration_s", formatNumber(f.duration_s), "finite for a gust (its 1 − cos length)"});
    }
  }
  return out;
}

FaultInjector::FaultInjector(std::vector<Fault> faults, std::uint64_t seed, double start_hover_s)
    : faults_(std::move(faults)), start_hover_s_(start_hover_s), outliers_(seed, sim::salt::kFaultOutliers) {}

bool FaultInjector::active(const Fault& f, double t_s) const noexcept {
  const double t = t_s - start_hover_s_;
  return t >= f.start_s && t < f.start_s + f.duration_s;
}

std::uint32_t FaultInjector::activeBits(double t_s) const noexcept {
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < faults_.size() && i < 32; ++i) {
    if (active(faults_[i], t_s)) bits |= 1u << i;
  }
  return bits;
}

void FaultInjector::onSensors(double t_s, sim::SensorReadings& r) noexcept {
  for (const Fault& f : faults_) {
    if (!active(f, t_s)) continue;
    switch (f.kind) {
      case FaultKind::kMocapDropout: r.mocap.reset(); break;
      case FaultKind::kRangerDead: r.ranger.reset(); break;
      case FaultKind::kRangerOutliers:
        if (r.ranger) {
          const int n = r.ranger->side * r.ranger->side;
          for (int z = 0; z < n; ++z) {
            if (outliers_.uniformHalfOpen() < f.value) {
              r.ranger->range_m[static_cast<std::size_t>(z)] = 0.02 + 3.98 * outliers_.uniformHalfOpen();
              r.ranger->valid[static_cast<std::size_t>(z)] = true;
            }
          }
        }
        break;
      case FaultKind::kImuClipKick:
        if (r.imu) {
          r.imu->gyro_B = r.imu->gyro_B.cwiseMax(-kGyroClipRadps).cwiseMin(kGyroClipRadps);
          r.imu->accel_B = r.imu->accel_B.cwiseMax(-kAccelClipMps2).cwiseMin(kAccelClipMps2);
        }
        break;
      case FaultKind::kGyroBiasStep:
        if (r.imu) r.imu->gyro_B.array() += f.value;
        break;
      default: break;
    }
  }
}

void FaultInjector::applyToMotors(double t_s, sim::Plant& plant) const noexcept {
  std::array<double, 4> scale{1.0, 1.0, 1.0, 1.0};
  for (const Fault& f : faults_) {
    if (!active(f, t_s)) continue;
    const auto m = static_cast<std::size_t>(f.motor);
    switch (f.kind) {
      case FaultKind::kMotorStop: scale[m] = 0.0; break;
      // Thrust ∝ n²: a thrust fraction e is a speed fraction √e.
      case FaultKind::kMotorEffectiveness: scale[m] *= std::sqrt(f.value); break;
      case FaultKind::kBatterySag:
        for (double& x : scale) x *= f.value;
        break;
      default: break;
    }
  }
  for (std::size_t i = 0; i < 4; ++i) plant.setMotorSpeedScale(i, scale[i]);
}

Eigen::Vector3d FaultInjector::windAt(double t_s) const noexcept {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  for (const Fault& f : faults_) {
    if (f.kind != FaultKind::kGust || !active(f, t_s)) continue;
    const double x = (t_s - start_hover_s_ - f.start_s) / f.duration_s;  // ∈ [0, 1)
    w.x() += 0.5 * f.value * (1.0 - std::cos(2.0 * std::numbers::pi * x));
  }
  return w;
}

std::unique_ptr<sim::Contribution> FaultInjector::kickContribution() const {
  std::vector<std::pair<double, double>> kicks;
  for (const Fault& f : faults_) {
    if (f.kind == FaultKind::kImuClipKick) kicks.emplace_back(start_hover_s_ + f.start_s, f.value);
  }
  if (kicks.empty()) return nullptr;
  return std::make_unique<KickContribution>(std::move(kicks));
}

}  // namespace geaware::experiments
