// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Faults injected into a flight on purpose (issue 16 item 4; docs/reliability.md, "Fault
// campaign"), the way PX4's and ArduPilot's simulators break a vehicle (PX4 `failure` command:
// motor, GPS/mocap, distance sensor, gyro/accel; ArduPilot SIM_ENGINE_MUL, SIM_GYR_FAIL_MSK).
// They act between the truth and the controller, never inside it: on the sensor readings the
// estimator gets, on the throttles the motors get, and as extra wrench or wind on the plant.
// The controller learns of them only through its inputs.
//
// Times are trajectory times (t_traj = t − start_hover_s). Every random draw (ranger outliers)
// comes from the scenario's seed with its own salt, so a faulted flight is reproducible.

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/field_error.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/sampling.hpp"
#include "geaware/sim/sensors.hpp"

namespace geaware::experiments {

enum class FaultKind {
  /// Motor `motor` delivers `value` ∈ [0, 1) of its thrust: its ESC reaches √value of the rotor
  /// speed the throttle asks for (thrust ∝ n²), as a worn motor or a throttle-limited ESC does;
  /// the rotor-speed telemetry shows it.
  kMotorEffectiveness,
  /// Motor `motor` stops (its ESC cuts: the rotor spins down to 0 with its own time constant).
  kMotorStop,
  /// No motion-capture pose reaches the estimator for `duration_s`.
  kMocapDropout,
  /// Each ranger zone returns a uniform random range in [0.02, 4] m with probability `value`.
  kRangerOutliers,
  /// The ranger delivers nothing from `start_s` on.
  kRangerDead,
  /// A body torque kick of `value` N·m about x for 0.1 s, while the IMU clips at ±250 °/s and
  /// ±4 g for `duration_s` (a consumer IMU in its low ranges).
  kImuClipKick,
  /// The gyro's bias steps by `value` rad/s on every axis.
  kGyroBiasStep,
  /// The battery's terminal voltage drops to `value` of its level (all ESCs reach that fraction
  /// of the rotor speed a throttle asks for: ESC speed ∝ supply voltage).
  kBatterySag,
  /// A gust of `value` m/s along world x, 1 − cos shaped over `duration_s`.
  kGust,
};

[[nodiscard]] const char* toString(FaultKind k) noexcept;

struct Fault {
  FaultKind kind = FaultKind::kMotorStop;
  double start_s = 4.0;  ///< trajectory time the fault begins [s]
  double duration_s = std::numeric_limits<double>::infinity();  ///< how long it lasts [s]
  int motor = 0;         ///< mixer order, 0-based (motor faults)
  double value = 0.0;    ///< kind-specific, see FaultKind (unit per kind)
};

/// Every problem of `faults` (prefix "faults[i]."): times finite and ≥ 0, durations > 0,
/// motor in [0, 4), values in their kind's range.
[[nodiscard]] std::vector<model::FieldError> validate(const std::vector<Fault>& faults);

/// Fault bits for the flight log (column fault_active): bit i set while fault i is active.
class FaultInjector {
 public:
  /// `seed`: the scenario's; start_hover_s: to turn plant time into trajectory time.
  FaultInjector(std::vector<Fault> faults, std::uint64_t seed, double start_hover_s);

  [[nodiscard]] bool empty() const noexcept { return faults_.empty(); }
  /// Bit i: fault i active at plant time t_s.
  [[nodiscard]] std::uint32_t activeBits(double t_s) const noexcept;

  /// The readings the estimator gets at plant time t_s (dropouts, outliers, clipping, bias).
  void onSensors(double t_s, sim::SensorReadings& r) noexcept;
  /// The motors' speed scales at plant time t_s (stops, effectiveness, battery sag; product of
  /// the active faults, 1 when none), set on the plant before its step. No allocation.
  void applyToMotors(double t_s, sim::Plant& plant) const noexcept;
  /// Extra wind at plant time t_s [m/s] (gusts).
  [[nodiscard]] Eigen::Vector3d windAt(double t_s) const noexcept;
  /// The torque kicks as a plant contribution (null when there are none).
  [[nodiscard]] std::unique_ptr<sim::Contribution> kickContribution() const;

 private:
  [[nodiscard]] bool active(const Fault& f, double t_s) const noexcept;

  std::vector<Fault> faults_;
  double start_hover_s_;
  sim::NoiseSource outliers_;
};

}  // namespace geaware::experiments
