// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// All the simulated sensors of one vehicle, each at its own rate with its own
// seeded noise stream: IMU, motion capture, rotor-speed telemetry and the lattice ranger. The
// runner calls step() once per plant step with the true state; the samples that fall due come
// back as the types of model/sensor_data.hpp, the only things that cross the wall to the
// estimator. The single sensors (imu.hpp, mocap.hpp, rotor_telemetry.hpp, ranger.hpp) can be
// used alone.

#include <cstdint>
#include <optional>
#include <vector>

#include "geaware/model/sensor_data.hpp"
#include "geaware/model/field_error.hpp"
#include "geaware/sim/imu.hpp"
#include "geaware/sim/mocap.hpp"
#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/ranger.hpp"
#include "geaware/sim/rotor_telemetry.hpp"
#include "geaware/sim/terrain.hpp"

namespace geaware::sim {

struct SensorSuiteParams {
  ImuParams imu;
  MocapParams mocap;
  RotorTelemetryParams rotor_telemetry;
  RangerParams ranger;

  /// Every offending field, key paths prefixed by the sensor ("imu.rate_Hz", "ranger.side" …).
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// What fell due at one step.
struct SensorReadings {
  std::optional<model::ImuSample> imu;
  std::optional<model::MocapSample> mocap;       ///< delivered now; captured at mocap->t_s
  std::optional<model::RotorTelemetry> rotors;
  std::optional<model::RangerFrame> ranger;
};

class SensorSuite {
 public:
  /// Throws model::InvalidParameters listing every invalid field (prefixed key paths). Each
  /// sensor draws from its own stream (scenario_seed, its salt).
  SensorSuite(const SensorSuiteParams& params, std::uint64_t scenario_seed);

  /// Sample every sensor at the true state (call every plant step). No allocation.
  [[nodiscard]] SensorReadings step(const PlantState& state, const Terrain* terrain) noexcept;

  [[nodiscard]] const Imu& imu() const noexcept { return imu_; }
  [[nodiscard]] const Mocap& mocap() const noexcept { return mocap_; }
  [[nodiscard]] const RotorTelemetrySensor& rotorTelemetry() const noexcept { return rotors_; }
  [[nodiscard]] const LatticeRanger& ranger() const noexcept { return ranger_; }

 private:
  Imu imu_;
  Mocap mocap_;
  RotorTelemetrySensor rotors_;
  LatticeRanger ranger_;
};

}  // namespace geaware::sim
