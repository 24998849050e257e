// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/bridge/ranger_zones.hpp"

#include <cmath>
#include <cstring>

namespace geaware::bridge {

void encodeRangerZone(const model::RangerFrame& frame, int zone, double max_range_m,
                      Px4DistanceSensor& m) noexcept {
  std::memset(&m, 0, sizeof m);
  const int i = zone / frame.side;
  const int j = zone % frame.side;
  const auto z = static_cast<std::size_t>(zone);
  m.timestamp = toMicroseconds(frame.t_s);
  m.device_id = kLatticeDeviceId | static_cast<std::uint32_t>(frame.side) << 8 |
                static_cast<std::uint32_t>(zone);
  m.min_distance = 0.0f;
  m.max_distance = static_cast<float>(max_range_m);
  m.current_distance = static_cast<float>(frame.range_m[z]);
  m.variance = 0.0f;
  m.signal_quality = static_cast<std::int8_t>(frame.valid[z] ? 100 : 0);
  m.type = 0;  // MAV_DISTANCE_SENSOR_LASER
  m.h_fov = static_cast<float>(frame.fov_rad);
  m.v_fov = static_cast<float>(frame.fov_rad);
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(
      Eigen::Vector3d::UnitX(), fluToFrd(frame.zoneDirection_B(i, j)));
  m.q[0] = static_cast<float>(q.w());
  m.q[1] = static_cast<float>(q.x());
  m.q[2] = static_cast<float>(q.y());
  m.q[3] = static_cast<float>(q.z());
  m.orientation = 100;  // ROTATION_CUSTOM
  m.mode = 1;           // MODE_ENABLED
}

RangerAssembler::RangerAssembler(const Eigen::Vector3d& mount_B) noexcept {
  frame_.mount_B = mount_B;
}

void RangerAssembler::start(std::uint64_t t_us, int side, double fov_rad) noexcept {
  if (open_ && received_ > 0) ++dropped_;
  t_us_ = t_us;
  frame_.t_s = toSeconds(t_us);
  frame_.side = side;
  frame_.fov_rad = fov_rad;
  frame_.valid.fill(false);
  received_ = 0;
  open_ = true;
}

bool RangerAssembler::add(const Px4DistanceSensor& m) noexcept {
  const bool lattice = (m.device_id & 0xffff0000u) == kLatticeDeviceId;
  int side = 1;
  int zone = 0;
  double fov = 0.0;
  if (lattice) {
    side = static_cast<int>((m.device_id >> 8) & 0xffu);
    zone = static_cast<int>(m.device_id & 0xffu);
    fov = static_cast<double>(m.h_fov);
    if (side < 1 || side > model::RangerFrame::kMaxSide || zone >= side * side) return false;
    if (!std::isfinite(fov) || fov < 0.0) return false;
  }
  if (!open_ || m.timestamp != t_us_ || side != frame_.side) start(m.timestamp, side, fov);
  const auto z = static_cast<std::size_t>(zone);
  const double r = static_cast<double>(m.current_distance);
  frame_.range_m[z] = r;
  frame_.valid[z] = m.signal_quality != 0 && std::isfinite(r) && r > 0.0;
  ++received_;
  if (received_ < side * side) return false;
  open_ = false;
  return true;
}

}  // namespace geaware::bridge
