// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/bridge/px4_codec.hpp"

#include <cmath>
#include <cstring>
#include <limits>

namespace geaware::bridge {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

void put(const Eigen::Vector3d& v, float (&out)[3]) noexcept {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<float>(v[i]);
}
Eigen::Vector3d get(const float (&in)[3]) noexcept {
  return {static_cast<double>(in[0]), static_cast<double>(in[1]), static_cast<double>(in[2])};
}
std::uint32_t periodUs(double period_s) noexcept {
  return static_cast<std::uint32_t>(toMicroseconds(period_s));
}

}  // namespace

MotorMap motorMapOf(const model::RotorLayoutParams& layout) noexcept {
  MotorMap m;
  for (std::size_t i = 0; i < 4; ++i) m.px4_index[i] = static_cast<int>(layout.rotors[i].px4_motor) - 1;
  return m;
}

void encodeImu(const model::ImuSample& s, double sample_period_s, Px4SensorCombined& m) noexcept {
  std::memset(&m, 0, sizeof m);
  m.timestamp = toMicroseconds(s.t_s);
  put(fluToFrd(s.gyro_B), m.gyro_rad);
  m.gyro_integral_dt = periodUs(sample_period_s);
  m.accelerometer_timestamp_relative = 0;
  put(fluToFrd(s.accel_B), m.accelerometer_m_s2);
  m.accelerometer_integral_dt = periodUs(sample_period_s);
}

model::ImuSample decodeImu(const Px4SensorCombined& m) noexcept {
  model::ImuSample s;
  s.t_s = toSeconds(m.timestamp);
  s.gyro_B = frdToFlu(get(m.gyro_rad));
  s.accel_B = frdToFlu(get(m.accelerometer_m_s2));
  return s;
}

void encodePose(const model::MocapSample& s, double delivered_t_s, Px4Odometry& m) noexcept {
  std::memset(&m, 0, sizeof m);
  m.timestamp = toMicroseconds(delivered_t_s);
  m.timestamp_sample = toMicroseconds(s.t_s);
  m.pose_frame = 1;  // POSE_FRAME_NED
  put(enuToNed(s.p_W), m.position);
  const Eigen::Quaterniond q = enuFluToNedFrd(s.q_WB);
  m.q[0] = static_cast<float>(q.w());
  m.q[1] = static_cast<float>(q.x());
  m.q[2] = static_cast<float>(q.y());
  m.q[3] = static_cast<float>(q.z());
  m.velocity_frame = 1;  // VELOCITY_FRAME_NED
  for (int i = 0; i < 3; ++i) {
    m.velocity[i] = kNaN;
    m.angular_velocity[i] = kNaN;
    m.position_variance[i] = kNaN;
    m.orientation_variance[i] = kNaN;
    m.velocity_variance[i] = kNaN;
  }
}

DecodedPose decodePose(const Px4Odometry& m) noexcept {
  DecodedPose d;
  d.delivered_t_s = toSeconds(m.timestamp);
  d.pose.t_s = toSeconds(m.timestamp_sample);
  d.pose.p_W = nedToEnu(get(m.position));
  const Eigen::Quaterniond q(m.q[0], m.q[1], m.q[2], m.q[3]);
  const bool finite = d.pose.p_W.allFinite() && q.coeffs().allFinite();
  d.valid = m.pose_frame == 1 && finite && std::abs(q.norm() - 1.0) < 1e-3;
  d.pose.q_WB = d.valid ? nedFrdToEnuFlu(q) : Eigen::Quaterniond::Identity();
  return d;
}

void encodeEsc(const model::RotorTelemetry& r, const MotorMap& map, Px4EscStatus& m) noexcept {
  std::memset(&m, 0, sizeof m);
  m.timestamp = toMicroseconds(r.t_s);
  m.esc_count = 4;
  m.esc_connectiontype = 5;  // DShot
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<std::size_t>(map.px4_index[static_cast<std::size_t>(i)]);
    auto& e = m.esc[k];
    e.timestamp = m.timestamp;
    e.esc_rpm = static_cast<std::int32_t>(std::lround(r.n_rpm[i]));
    e.esc_address = static_cast<std::uint8_t>(k + 1);
    e.actuator_function = static_cast<std::uint8_t>(101 + k);  // ACTUATOR_FUNCTION_MOTOR1 + k
    m.esc_online_flags = static_cast<std::uint8_t>(m.esc_online_flags | (1u << k));
    m.esc_armed_flags = static_cast<std::uint8_t>(m.esc_armed_flags | (1u << k));
  }
}

model::RotorTelemetry decodeEsc(const Px4EscStatus& m, const MotorMap& map) noexcept {
  model::RotorTelemetry r;
  r.t_s = toSeconds(m.timestamp);
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<std::size_t>(map.px4_index[static_cast<std::size_t>(i)]);
    r.n_rpm[i] = k < 8 ? static_cast<double>(m.esc[k].esc_rpm) : std::nan("");
  }
  return r;
}

void encodeBattery(double t_s, double voltage_V, Px4BatteryStatus& m) noexcept {
  std::memset(&m, 0, sizeof m);
  m.timestamp = toMicroseconds(t_s);
  m.id = 1;
  m.connected = true;
  m.voltage_v = static_cast<float>(voltage_V);
  m.current_a = -1.0f;
  m.current_average_a = -1.0f;
  m.discharged_mah = -1.0f;
  m.remaining = -1.0f;
  m.scale = -1.0f;
  m.time_remaining_s = kNaN;
  m.temperature = kNaN;
}

void encodeMotors(double t_s, double tick_t_s, const std::array<double, 4>& throttle,
                  double thr_mdl_fac, const MotorMap& map, Px4ActuatorMotors& m) noexcept {
  std::memset(&m, 0, sizeof m);
  m.timestamp = toMicroseconds(t_s);
  m.timestamp_sample = toMicroseconds(tick_t_s);
  for (float& c : m.control) c = kNaN;
  for (std::size_t i = 0; i < 4; ++i) {
    m.control[map.px4_index[i]] =
        static_cast<float>(normalisedThrustFromThrottle(throttle[i], thr_mdl_fac));
  }
}

std::array<double, 4> decodeMotors(const Px4ActuatorMotors& m, double thr_mdl_fac,
                                   const MotorMap& map) noexcept {
  std::array<double, 4> u{};
  for (std::size_t i = 0; i < 4; ++i) {
    const double c = static_cast<double>(m.control[map.px4_index[i]]);
    u[i] = std::isnan(c) ? 0.0 : throttleFromNormalisedThrust(c, thr_mdl_fac);
  }
  return u;
}

void encodeOffboardMode(double t_s, Px4OffboardControlMode& m) noexcept {
  std::memset(&m, 0, sizeof m);
  m.timestamp = toMicroseconds(t_s);
  m.direct_actuator = true;
}

void encodeClock(double t_s, RosClock& m) noexcept {
  const std::uint64_t us = toMicroseconds(t_s);
  m.clock.sec = static_cast<std::int32_t>(us / 1000000u);
  m.clock.nanosec = static_cast<std::uint32_t>((us % 1000000u) * 1000u);
}

std::uint64_t decodeClockUs(const RosClock& m) noexcept {
  if (m.clock.sec < 0) return 0;
  return static_cast<std::uint64_t>(m.clock.sec) * 1000000u + m.clock.nanosec / 1000u;
}

}  // namespace geaware::bridge
