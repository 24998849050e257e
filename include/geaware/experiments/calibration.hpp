#pragma once
// Step 1 of the campaign (issue 6): the controller's parameters identified from the virtual
// rigs run on the TRUTH (sim/rigs.hpp), through the identification fits (ident/), exactly as a
// real vehicle would be calibrated on the paper's rigs. The controller never gets the truth's
// parameters: it gets the vehicle file with the identified values merged in.
//
// Rigs (coarse grids, well under a second):
//   1. quadrotor platform, level board, 0.07–1.0 m, equal speeds      → k_T, g1, g2 (eq. 8–9)
//   2. quadrotor platform, tilted board 2–10°, 0.08–0.40 m            → M_G shape and scale (eq. 14–15)
//   3. quadrotor platform, rpm-difference sweeps at 1–2 m              → k_TX, k_TY, k_I (eq. 2)
//   4. single-rotor stand, throttle 0…1                                → k_T, k_I, J_R, throttle curve
// The order of the merge follows docs/identification.md: the stand first, then the platform,
// so the platform's k_T (the one g1, g2 and the leveling scale were fitted with) and its k_I
// are what the controller gets; J_R and the throttle curve come from the stand. The drag table
// and the mass and inertia stay those of the vehicle file (the rigs cannot measure them).
// The identification is `geaware identify`'s own (ident/identify.hpp, default options), run
// on the rigs' rows in memory. Details and the reasons for the sweeps: docs/results.md,
// "Calibration".

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/rigs.hpp"
#include "geaware/sim/truth_params.hpp"

namespace geaware::experiments {

/// What the rigs are swept over.
struct CalibrationSweeps {
  sim::PlatformSweep level;      ///< level board, equal speeds
  sim::PlatformSweep tilted;     ///< tilted board, equal speeds
  sim::PlatformSweep mixing;     ///< rpm differences out of ground effect
  std::vector<double> stand_throttles;  ///< single-rotor stand throttle steps [0, 1]
  sim::PlatformParams platform;  ///< sensor noise, samples per setpoint
  sim::RotorStandParams stand;
  /// Tilts above this are left out of the leveling fit (the torque saturates above ≈ 10°,
  /// docs/paper-facts.md) [deg].
  double tilt_limit_deg = 10.0;
  std::uint64_t seed = 1;  ///< rig noise; each rig draws from its own derived seed
  /// Identify F_G and M_G as tables at the swept heights (ident/table_fit.hpp) instead of the
  /// paper's closed forms; F_G's knots go up to 0.5 m, the level heights above fix k_T.
  bool tables = false;

  /// The campaign's sweeps (see the file comment).
  [[nodiscard]] static CalibrationSweeps defaults();
};

/// One identified parameter beside the vehicle file's value.
struct IdentifiedParameter {
  std::string key;         ///< vehicle-file key path, e.g. "rotor.k_T_N_per_rpm2"
  std::string unit;
  std::string source;      ///< which rig and fit
  double file_value = 0.0;
  double identified = 0.0;
  double std_error = 0.0;
};

/// A curve at one height: the truth (noise-free rig), the identified model, the vehicle file.
struct CurvePoint {
  double h_m = 0.0;
  double truth = 0.0;
  double identified = 0.0;
  double file = 0.0;
};

struct ControllerCalibration {
  /// The controller's parameters: the vehicle file with every identified value merged in.
  model::VehicleParams vehicle;
  std::vector<IdentifiedParameter> parameters;
  /// F_G(h) on the level board [-]: truth ΣF_z/ΣT_free − 1, identified and file g2/(h² + g1).
  std::vector<CurvePoint> thrust_ratio;
  /// Leveling torque about y at `torque_tilt_deg` and `torque_rpm` [N·m] (negative:
  /// leveling): truth, and −M_G(h)·T·sin δ with T = 4·k_T·n² of the identified and file models.
  std::vector<CurvePoint> leveling_torque;
  double torque_tilt_deg = 5.0;
  double torque_rpm = 15000.0;
  std::vector<std::string> warnings;  ///< from the fits
  std::size_t platform_rows = 0;
  std::size_t stand_rows = 0;
};

/// Runs the rigs on `truth` (its rotor geometry, aerodynamics and motors) and identifies the
/// controller's parameters, starting from `file_vehicle` (the nominal vehicle file). Throws
/// ident::IdentError when a fit fails, std::invalid_argument when the identified parameters
/// are not a valid vehicle.
[[nodiscard]] ControllerCalibration calibrateController(
    const model::VehicleParams& file_vehicle, const sim::TruthParams& truth,
    const CalibrationSweeps& sweeps = CalibrationSweeps::defaults());

}  // namespace geaware::experiments
