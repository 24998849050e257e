// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/mocap.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {

using model::formatValue;

std::vector<model::FieldError> MocapParams::validate() const {
  std::vector<model::FieldError> out;
  model::FieldChecker c(out);
  using enum model::LowerBound;
  c.range("rate_Hz", rate_Hz, 0.0, 1e4, kExclusive, "Hz");
  c.range("latency_s", latency_s, 0.0, 1.0, kInclusive, "s");
  const bool jitter_ok =
      c.range("latency_jitter_std_s", latency_jitter_std_s, 0.0, 0.1, kInclusive, "s");
  if (std::isfinite(rate_Hz) && rate_Hz > 0.0 && std::isfinite(latency_s) && jitter_ok &&
      (latency_s + 4.0 * latency_jitter_std_s) * rate_Hz + 2.0 > Mocap::kQueueCapacity) {
    c.fail("latency_s", formatValue(latency_s),
           "(latency_s + 4·latency_jitter_std_s)·rate_Hz + 2 ≤ " +
               std::to_string(Mocap::kQueueCapacity) + " (poses in flight)");
  }
  if (!(reported_latency_s < 0.0))
    c.range("reported_latency_s", reported_latency_s, 0.0, 1.0, kInclusive,
            "s (negative: the true latency)");
  c.nonNegative("position_noise_std_m", position_noise_std_m, "m");
  c.range("attitude_noise_std_rad", attitude_noise_std_rad, 0.0, 0.5, kInclusive, "rad");
  c.range("dropout_probability", dropout_probability, 0.0, 1.0, kInclusive);
  c.range("burst_probability", burst_probability, 0.0, 1.0, kInclusive);
  c.integerAtLeast("burst_length_samples", burst_length_samples, 1);
  return out;
}

Mocap::Mocap(const MocapParams& params, std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      noise_(scenario_seed, salt::kMocap),
      jitter_noise_(scenario_seed, salt::kMocapJitter),
      clock_(params_.rate_Hz) {}

void Mocap::capture(const PlantState& s) noexcept {
  ++captured_;
  // Fixed draws per capture: burst, dropout, 3 position and 3 attitude normals.
  const double u_burst = noise_.uniform();
  const double u_drop = noise_.uniform();
  const Eigen::Vector3d dp = params_.position_noise_std_m * noise_.normal3();
  const Eigen::Vector3d dtheta = params_.attitude_noise_std_rad * noise_.normal3();

  bool lost = false;
  if (burst_left_ > 0) {
    --burst_left_;
    lost = true;
  } else if (u_burst < params_.burst_probability) {
    burst_left_ = params_.burst_length_samples - 1;
    lost = true;
  }
  if (u_drop < params_.dropout_probability) lost = true;
  if (lost) {
    ++dropped_;
    return;
  }

  Pending p;
  p.sample.t_s = s.t_s;
  p.sample.p_W = s.p_W + dp;
  const double angle = dtheta.norm();
  const Eigen::Quaterniond dq = angle > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, dtheta / angle))
                                            : Eigen::Quaterniond::Identity();
  p.sample.q_WB = (s.q_WB * dq).normalized();
  double latency = params_.latency_s;
  if (params_.latency_jitter_std_s > 0.0)
    latency = std::max(0.0, latency + params_.latency_jitter_std_s * jitter_noise_.normal());
  p.deliver_s = s.t_s + latency;
  if (count_ == kQueueCapacity) {  // drop the oldest
    head_ = (head_ + 1) % kQueueCapacity;
    --count_;
    ++overflowed_;
  }
  ring_[static_cast<std::size_t>((head_ + count_) % kQueueCapacity)] = p;
  ++count_;
}

std::optional<model::MocapSample> Mocap::step(const PlantState& s) noexcept {
  if (!isFinite(s)) {
    ++rejected_;
  } else if (clock_.due(s.t_s)) {
    capture(s);
  }
  if (count_ == 0 || !std::isfinite(s.t_s)) return std::nullopt;
  const Pending& oldest = ring_[static_cast<std::size_t>(head_)];
  if (s.t_s + SampleClock::kTolerance_s < oldest.deliver_s) return std::nullopt;
  model::MocapSample out = oldest.sample;
  head_ = (head_ + 1) % kQueueCapacity;
  --count_;
  // The driver's stamp: the true capture time, or the arrival less the latency it believes in.
  if (params_.reported_latency_s >= 0.0) out.t_s = s.t_s - params_.reported_latency_s;
  return out;
}

}  // namespace geaware::sim
