// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The bridge's part of the loop without DDS: PX4 messages in, the estimator (ESKF, lattice
// height, disturbance observer) and the controller, a motor command out — the same stages as the
// in-process flight runner (experiments/flight.hpp) in the same order: on a tick at time t the
// samples received up to t are applied in time order (IMU, then the pose delivered at that time,
// then rotor telemetry, then a ranger frame), then the controller runs. No allocation after
// construction (tests/bridge/bridge_alloc_test.cpp).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "geaware/bridge/frames.hpp"
#include "geaware/bridge/px4_codec.hpp"
#include "geaware/bridge/ranger_zones.hpp"
#include "geaware/control/controller.hpp"
#include "geaware/estimation/disturbance_observer.hpp"
#include "geaware/estimation/eskf.hpp"
#include "geaware/estimation/lattice_height.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::bridge {

struct BridgeSettings {
  MotorMap motors;                 ///< geaware's rotor i → PX4 motor index
  double thr_mdl_fac = 0.0;        ///< PX4's THR_MDL_FAC on the vehicle [-]
  double max_height_age_s = 0.05;  ///< an older ranger height is not handed to the controller [s]
};

/// What one tick produced.
struct TickOutput {
  bool active = false;                ///< the controller ran (else: the hover fallback)
  std::array<double, 4> throttle{};   ///< mixer order [0, 1]
  std::uint32_t controller_flags = 0;  ///< control::ControllerFlag bits
  double t_traj_s = 0.0;              ///< trajectory time of the tick [s]
};

class BridgeCore {
 public:
  /// The vehicle, the trajectory, start hover, controller, ESKF and lattice parameters, and the
  /// ranger's mount, from the scenario (the truth in it is not read). Throws on invalid values.
  BridgeCore(const experiments::FlightScenario& s, const BridgeSettings& settings);

  void onImu(const Px4SensorCombined& m) noexcept;
  void onOdometry(const Px4Odometry& m) noexcept;
  void onEsc(const Px4EscStatus& m) noexcept;
  void onDistance(const Px4DistanceSensor& m) noexcept;
  void onBattery(const Px4BatteryStatus& m) noexcept;

  /// Applies the samples stamped up to t_us in time order, then runs the controller (or the
  /// hover fallback while the estimator has no pose or there is no rotor telemetry yet). The
  /// trajectory starts start_hover_s after the first tick.
  const TickOutput& tick(std::uint64_t t_us) noexcept;
  /// tick()'s output as actuator_motors (timestamp t_us, timestamp_sample the tick).
  void command(std::uint64_t now_us, Px4ActuatorMotors& m) const noexcept;

  /// Forget the flight: estimator, controller, queues (a new simulator or a restarted vehicle).
  void reset();

  [[nodiscard]] bool started() const noexcept { return started_; }
  /// Time stamp of the newest IMU sample received (the vehicle's clock in real time) [µs].
  [[nodiscard]] std::uint64_t lastImuUs() const noexcept { return last_imu_us_; }
  [[nodiscard]] double trajectoryDuration_s() const noexcept { return duration_s_; }
  [[nodiscard]] std::uint64_t droppedSamples() const noexcept { return dropped_; }
  /// Samples that arrived after the tick they belonged to had run (stamped before it).
  [[nodiscard]] std::uint64_t lateSamples() const noexcept { return late_; }
  [[nodiscard]] std::uint64_t rangerFramesDropped() const noexcept { return ranger_.droppedFrames(); }

 private:
  template <class T, int N>
  struct Queue {
    std::array<T, N> items{};
    int head = 0;
    int size = 0;
    bool push(const T& v) noexcept;
    [[nodiscard]] const T& front() const noexcept { return items[static_cast<std::size_t>(head)]; }
    void pop() noexcept;
    void clear() noexcept { head = size = 0; }
  };
  struct PoseEvent {
    std::uint64_t delivered_us = 0;
    model::MocapSample pose;
  };
  struct RangerEvent {
    std::uint64_t t_us = 0;
    model::RangerFrame frame;
  };
  void applyUpTo(std::uint64_t t_us) noexcept;
  void applyImu(const model::ImuSample& s) noexcept;
  void applyRanger(const model::RangerFrame& f) noexcept;
  void runController(double t_s) noexcept;
  [[nodiscard]] double hoverThrottle() const noexcept;

  const experiments::FlightScenario& s_;
  BridgeSettings settings_;
  model::VehicleModel vehicle_;
  std::unique_ptr<estimation::Eskf> eskf_;
  estimation::LatticeHeightEstimator lattice_;
  std::optional<estimation::DisturbanceObserver> observer_;
  std::optional<control::Controller> controller_;
  RangerAssembler ranger_;
  double duration_s_ = 0.0;

  Queue<model::ImuSample, 64> imu_;
  Queue<PoseEvent, 16> poses_;
  Queue<model::RotorTelemetry, 16> escs_;
  std::unique_ptr<Queue<RangerEvent, 4>> frames_;  // ≈ 10 kB: on the heap
  std::uint64_t dropped_ = 0;
  std::uint64_t late_ = 0;
  void noteArrival(std::uint64_t t_us) noexcept {
    if (started_ && t_us < tick_us_) ++late_;
  }

  bool started_ = false;
  std::uint64_t t0_us_ = 0;
  Eigen::Vector4d telemetry_rpm_ = Eigen::Vector4d::Zero();
  bool have_telemetry_ = false;
  double height_m_ = 0.0;
  double height_t_s_ = -1.0;
  bool have_height_ = false;
  double battery_V_ = std::numeric_limits<double>::quiet_NaN();
  control::ControllerInput in_;
  TickOutput out_;
  std::uint64_t tick_us_ = 0;
  std::uint64_t last_imu_us_ = 0;
};

}  // namespace geaware::bridge
