// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's virtual test rigs (its section on methods), driven by the truth
// aerodynamics (sim/rotor_aerodynamics.hpp):
//  - the quadrotor force/torque platform: vehicle fixed and level at height h above a ground
//    board tilted by δ about the vehicle's y axis, rotors at commanded speeds, a six-axis sensor
//    with seeded Gaussian noise; sweeps over heights × tilts × speeds (× speed differences);
//  - the single-rotor stand: thrust and torque against throttle and rotor speed, with the
//    motor's first-order response and J_R·ṅ for throttle steps.
// Rows go to a callback, so a sweep of 10⁶ rows never sits in memory. Same seed → bit-identical
// rows (mt19937_64 and the Gaussian transform here are exactly specified).
//
// Board geometry: the board passes through the point h below the rotor-plane centre and rises
// toward +x_B for δ > 0, so rotor i (at x_i) is at the vertical distance z_i = h − x_i·tan δ;
// the front rotors are nearer and the leveling torque about y_B is negative.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/sampling.hpp"

namespace geaware::sim {


/// The truth rotor geometry of a nominal vehicle (X layout of model::Mixer, nominal k_T, k_I,
/// radius), as the rigs mount it: positions relative to the geometric centre.
[[nodiscard]] RotorGeometry rigGeometry(const model::VehicleParams& vehicle);

// ----------------------------------------------------------------------------------------------
// Quadrotor force/torque platform
// ----------------------------------------------------------------------------------------------

struct PlatformParams {
  double force_noise_N = 0.05;     ///< six-axis sensor noise, std per force axis [N]
  double torque_noise_Nm = 0.004;  ///< six-axis sensor noise, std per torque axis [N·m]
  int samples_per_setpoint = 5;    ///< samples logged per setpoint (steady state), ≥ 1
  double sample_period_s = 0.01;   ///< time between samples [s]
  double settle_time_s = 0.5;      ///< time between setpoints (not logged) [s]

  /// Offending fields (key paths "platform.<field>"); empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// Which torque axis a rotor-speed difference excites (rows 2–4 of the mixer pattern A).
enum class DiffAxis { kRoll = 1, kPitch = 2, kYaw = 3 };

struct PlatformSweep {
  std::vector<double> heights_m;  ///< rotor-plane centre above the board (at the centre) [m]
  std::vector<double> tilts_deg;  ///< board tilt about y_B [deg], |δ| < 45°
  std::vector<double> rpm;        ///< mean rotor speed [rpm]
  /// Speed differences Δ [rpm]: n_i = n + Δ·A(axis, i) for each axis in `diff_axes`. Empty:
  /// equal speeds only. A zero in the list gives the equal-speed row once.
  std::vector<double> rpm_diffs;
  std::vector<DiffAxis> diff_axes{DiffAxis::kRoll, DiffAxis::kPitch, DiffAxis::kYaw};

  /// Number of setpoints the sweep visits.
  [[nodiscard]] std::size_t setpointCount() const noexcept;
};

struct PlatformRow {
  double t_s = 0.0;
  double h_m = 0.0;
  double tilt_deg = 0.0;
  std::array<double, 4> n_rpm{};
  Eigen::Vector3d force_B = Eigen::Vector3d::Zero();   ///< measured force, body frame [N]
  Eigen::Vector3d torque_B = Eigen::Vector3d::Zero();  ///< measured torque about the centre [N·m]
};

class ForceTorquePlatform {
 public:
  /// Throws std::invalid_argument naming the fields when the parameters are not usable.
  ForceTorquePlatform(const RotorGeometry& geometry, const RotorAeroParams& aero,
                      const PlatformParams& params);

  /// Each rotor's vertical distance to the board [m] (h − x_i·tan δ).
  [[nodiscard]] RotorSurroundings surroundings(double h_m, double tilt_deg) const noexcept;

  /// Noise-free steady wrench on the sensor at one setpoint (body frame, about the geometric
  /// centre of the rotors as given in the geometry).
  [[nodiscard]] RotorAeroOutput wrench(double h_m, double tilt_deg,
                                       const std::array<double, 4>& n_rpm) const noexcept;

  /// Runs the sweep: for each height, tilt, speed (and difference), `samples_per_setpoint`
  /// rows with sensor noise drawn from `seed`. `progress(done, total)` (optional) is called
  /// after each setpoint. Throws std::invalid_argument for an invalid sweep (empty lists,
  /// non-finite values, heights ≤ 0, |tilt| ≥ 45°, negative speeds). Returns the row count.
  std::size_t sweep(const PlatformSweep& sweep, std::uint64_t seed,
                    const std::function<void(const PlatformRow&)>& sink,
                    const std::function<void(std::size_t, std::size_t)>& progress = {}) const;

  [[nodiscard]] const RotorAerodynamics& aerodynamics() const noexcept { return aero_; }

 private:
  RotorAerodynamics aero_;
  PlatformParams params_;
};

// ----------------------------------------------------------------------------------------------
// Single-rotor stand
// ----------------------------------------------------------------------------------------------

struct RotorStandParams {
  double thrust_noise_N = 0.01;         ///< load-cell noise, std [N]
  double torque_noise_Nm = 2e-4;        ///< torque-cell noise, std [N·m]
  double rpm_noise = 10.0;              ///< rotor-speed measurement noise, std [rpm]
  double motor_time_constant_s = 0.03;  ///< first-order speed response τ [s]
  double sample_period_s = 0.005;       ///< time between samples [s]
  double hold_s = 1.0;                  ///< time each throttle is held [s]

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

struct RotorStandRow {
  double t_s = 0.0;
  double throttle = 0.0;   ///< commanded throttle [0, 1]
  double rpm = 0.0;        ///< measured rotor speed [rpm]
  double thrust_N = 0.0;   ///< measured thrust [N]
  double torque_Nm = 0.0;  ///< measured reaction torque magnitude, k_I·n² + J_R·ṅ [N·m]
};

class RotorStand {
 public:
  /// The stand holds rotor 1 of `vehicle` in free air (k_T, k_I, J_R, the throttle curve).
  /// Throws std::invalid_argument naming the fields when the parameters are not usable.
  RotorStand(const model::VehicleParams& vehicle, const RotorStandParams& params);

  /// Steps through `throttles` in order (each held hold_s, starting from rest at throttle 0),
  /// logging every sample_period_s. Throws std::invalid_argument for an empty list or a
  /// throttle outside [0, 1]. Returns the row count.
  std::size_t sweep(const std::vector<double>& throttles, std::uint64_t seed,
                    const std::function<void(const RotorStandRow&)>& sink) const;

 private:
  model::VehicleParams vehicle_;
  RotorStandParams params_;
};

// ----------------------------------------------------------------------------------------------
// Calibration against the paper (docs/paper-facts.md)
// ----------------------------------------------------------------------------------------------

/// One calibration target: what the paper measured, what our truth gives, the tolerance.
struct CalibrationCheck {
  std::string name;       ///< e.g. "tau(15°, 0.18 m)"
  std::string unit;       ///< e.g. "N·m"
  double paper = 0.0;     ///< the paper's measurement (or target)
  double ours = 0.0;      ///< the truth's value
  std::string tolerance;  ///< e.g. "±25 %", "|x| < 0.02"
  bool pass = false;
};

/// Curves of the calibration, for plots.
struct CalibrationCurves {
  std::vector<double> h_m;                 ///< heights of the level-board and 15° sweeps [m]
  std::vector<double> thrust_ratio;        ///< ours: ΣT/ΣT_free − 1 on the level board
  std::vector<double> thrust_ratio_paper;  ///< g2/(h² + g1), the paper's fit
  std::vector<double> torque_15deg_Nm;     ///< ours at 15°, 15,000 rpm
  std::vector<double> tilt_deg;            ///< tilts of the 0.11 m sweep [deg]
  std::vector<double> torque_011_Nm;       ///< ours at 0.11 m, 15,000 rpm
};

struct CalibrationResult {
  std::vector<CalibrationCheck> checks;
  CalibrationCurves curves;
  [[nodiscard]] bool allPass() const noexcept;
};

/// Runs the calibration sweeps (docs/paper-facts.md) on the noise-free platform and the drag/mixing
/// experiments on `vehicle` with the truth aerodynamics `aero`.
[[nodiscard]] CalibrationResult calibrate(const model::VehicleParams& vehicle,
                                          const RotorAeroParams& aero);

}  // namespace geaware::sim
