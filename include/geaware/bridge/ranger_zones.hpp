// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The lattice ranger over PX4's distance_sensor: one message per zone (PX4 has no multi-zone
// message). A zone's message carries the frame's time stamp, its range, signal_quality 100 (a
// return) or 0 (none), h_fov = v_fov = the lattice's full field of view, orientation
// ROTATION_CUSTOM with q the zone's ray in the FRD body frame (the sensor looks along its +x), and
// device_id = kLatticeDeviceId | side << 8 | zone. A single-beam rangefinder (any other
// device_id, e.g. PX4's own downward lidar) is a 1×1 lattice looking straight down.
// Docs: docs/bridge.md, "Topics".

#include <cstdint>

#include "geaware/bridge/px4_codec.hpp"
#include "geaware/model/sensor_data.hpp"

namespace geaware::bridge {

inline constexpr std::uint32_t kLatticeDeviceId = 0x47410000u;  ///< "GA" in the upper half

/// Zone `zone` (row-major, model::RangerFrame::index) of `frame` as a distance_sensor message.
void encodeRangerZone(const model::RangerFrame& frame, int zone, double max_range_m,
                      Px4DistanceSensor& m) noexcept;

/// Collects zone messages into frames. No allocation.
class RangerAssembler {
 public:
  /// `mount_B`: the sensor's origin in the body frame (FLU) [m]; not in the messages.
  explicit RangerAssembler(const Eigen::Vector3d& mount_B) noexcept;
  /// Adds one message; true when it completed a frame (then frame() holds it until the next
  /// add). A message of a new time stamp drops an incomplete frame (counted).
  bool add(const Px4DistanceSensor& m) noexcept;
  [[nodiscard]] const model::RangerFrame& frame() const noexcept { return frame_; }
  [[nodiscard]] std::uint64_t droppedFrames() const noexcept { return dropped_; }

 private:
  void start(std::uint64_t t_us, int side, double fov_rad) noexcept;
  model::RangerFrame frame_;
  std::uint64_t t_us_ = 0;
  int received_ = 0;
  bool open_ = false;
  std::uint64_t dropped_ = 0;
};

}  // namespace geaware::bridge
