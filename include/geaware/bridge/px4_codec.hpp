// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// geaware's sensor samples and commands ↔ PX4's messages (the C structs idlc generates from
// idl/, idl/README.md), with the frame and unit conversions of frames.hpp. Plain functions: no
// DDS call, no allocation. Which field carries what: docs/bridge.md, "Topics".

#include <array>
#include <cstdint>

#include "geaware/bridge/frames.hpp"
#include "geaware/model/sensor_data.hpp"
#include "geaware/model/vehicle_params.hpp"
#include "px4_msgs/msg/ActuatorMotors.h"
#include "px4_msgs/msg/BatteryStatus.h"
#include "px4_msgs/msg/DistanceSensor.h"
#include "px4_msgs/msg/EscStatus.h"
#include "px4_msgs/msg/OffboardControlMode.h"
#include "px4_msgs/msg/SensorCombined.h"
#include "px4_msgs/msg/VehicleOdometry.h"
#include "rosgraph_msgs/msg/Clock.h"

namespace geaware::bridge {

using Px4Odometry = px4_msgs_msg_dds__VehicleOdometry_;
using Px4SensorCombined = px4_msgs_msg_dds__SensorCombined_;
using Px4EscStatus = px4_msgs_msg_dds__EscStatus_;
using Px4DistanceSensor = px4_msgs_msg_dds__DistanceSensor_;
using Px4BatteryStatus = px4_msgs_msg_dds__BatteryStatus_;
using Px4OffboardControlMode = px4_msgs_msg_dds__OffboardControlMode_;
using Px4ActuatorMotors = px4_msgs_msg_dds__ActuatorMotors_;
using RosClock = rosgraph_msgs_msg_dds__Clock_;

/// The vehicle file's motor numbers (rotor_layout.rotorN.px4_motor, 1-based) as a motor map.
[[nodiscard]] MotorMap motorMapOf(const model::RotorLayoutParams& layout) noexcept;

/// IMU sample → sensor_combined (FRD body, float32; both sensors at the sample's time).
void encodeImu(const model::ImuSample& s, double sample_period_s, Px4SensorCombined& m) noexcept;
[[nodiscard]] model::ImuSample decodeImu(const Px4SensorCombined& m) noexcept;

/// A pose captured at s.t_s and delivered at delivered_t_s → vehicle_odometry (NED, FRD body;
/// timestamp = delivery, timestamp_sample = capture; velocity and rates unknown: NaN).
void encodePose(const model::MocapSample& s, double delivered_t_s, Px4Odometry& m) noexcept;
struct DecodedPose {
  model::MocapSample pose;
  double delivered_t_s = 0.0;  ///< the message's timestamp [s]
  bool valid = false;          ///< NED pose frame, finite position, unit quaternion
};
[[nodiscard]] DecodedPose decodePose(const Px4Odometry& m) noexcept;

/// Rotor telemetry → esc_status (4 ESCs online, rpm rounded to integers, motor order `map`).
void encodeEsc(const model::RotorTelemetry& r, const MotorMap& map, Px4EscStatus& m) noexcept;
[[nodiscard]] model::RotorTelemetry decodeEsc(const Px4EscStatus& m, const MotorMap& map) noexcept;

/// Battery terminal voltage → battery_status (connected, voltage only; the rest unknown).
void encodeBattery(double t_s, double voltage_V, Px4BatteryStatus& m) noexcept;

/// Throttles (mixer order, [0, 1]) → actuator_motors (normalised thrust through THR_MDL_FAC,
/// PX4's motor order; unused motors NaN = stopped). timestamp_sample: the tick the command
/// answers.
void encodeMotors(double t_s, double tick_t_s, const std::array<double, 4>& throttle,
                  double thr_mdl_fac, const MotorMap& map, Px4ActuatorMotors& m) noexcept;
/// actuator_motors → throttles as PX4 would send them to the ESCs (NaN → 0: stopped).
[[nodiscard]] std::array<double, 4> decodeMotors(const Px4ActuatorMotors& m, double thr_mdl_fac,
                                                 const MotorMap& map) noexcept;

/// offboard_control_mode for direct actuator control.
void encodeOffboardMode(double t_s, Px4OffboardControlMode& m) noexcept;

void encodeClock(double t_s, RosClock& m) noexcept;
/// The clock's time in microseconds.
[[nodiscard]] std::uint64_t decodeClockUs(const RosClock& m) noexcept;

}  // namespace geaware::bridge
