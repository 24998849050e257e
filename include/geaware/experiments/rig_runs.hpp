// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The virtual rigs run as the paper's rigs (`geaware rig platform|rotor|calibrate`): what a run
// collects beside its rows, the pages that show it, and the text table of the truth's
// calibration against the paper. The rows themselves go to the caller's sink (a CSV file on the
// command line); nothing here opens a file or prints.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "geaware/model/vehicle_params.hpp"
#include "geaware/report/page.hpp"
#include "geaware/sim/rigs.hpp"
#include "geaware/sim/truth_params.hpp"

namespace geaware::experiments {

/// A platform sweep to run on a truth's rotor geometry and aerodynamics.
struct PlatformRigRun {
  sim::PlatformSweep sweep;
  sim::PlatformParams params;
  std::uint64_t seed = 1;
  /// Collect the per-setpoint means for platformRigPage (at most 200,000 setpoints; more is
  /// refused with std::invalid_argument before the sweep starts).
  bool collect_means = false;
};

/// Per equal-speed setpoint (tilt, n, h) means of a platform sweep, for its page.
struct PlatformSetpointMean {
  double fz_N = 0.0;      ///< sum of f_z until divided [N]
  double ty_Nm = 0.0;     ///< sum of τ_y [N·m]
  double t_free_N = 0.0;  ///< the rotors' free-air thrust Σk_T·n² [N]
  int count = 0;
};
using PlatformMeans = std::map<std::tuple<double, double, double>, PlatformSetpointMean>;

struct PlatformRigResult {
  std::size_t rows = 0;
  PlatformMeans means;  ///< empty unless collect_means
};

/// Throws std::invalid_argument when `run` collects means of more setpoints than a page can plot
/// (runPlatformRig checks this first too; call it before creating the rows' file).
void checkPlatformRigRun(const PlatformRigRun& run);

/// Runs the sweep, handing every row to `sink`; `progress(done, total)` after each setpoint.
[[nodiscard]] PlatformRigResult runPlatformRig(
    const sim::TruthParams& truth, const PlatformRigRun& run,
    const std::function<void(const sim::PlatformRow&)>& sink,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The sweep's page: F_G on the level board and the leveling torque, per speed (and tilt).
/// `produced_by` is the first paragraph (the command that made it).
[[nodiscard]] report::Page platformRigPage(const PlatformMeans& means, const std::string& produced_by);

/// The rotors as the force/torque platform holds them: the truth's rotors (their spread and
/// thrust axes) about the platform's sensor at the vehicle's geometric centre, where the
/// vehicle is mounted and its weight tared, not about its centre of mass.
[[nodiscard]] sim::RotorGeometry platformGeometry(const sim::TruthParams& truth);

/// The vehicle the single-rotor stand mounts: rotor 1 of the truth — its k_T and k_I (with their
/// spreads), J_R and ESC curve — on `file_vehicle`'s other parameters.
[[nodiscard]] model::VehicleParams rotorStandVehicle(const model::VehicleParams& file_vehicle,
                                                     const sim::TruthParams& truth);

/// A stand run on `vehicle` (rotorStandVehicle): the rows to `sink`; with `collect` the first
/// 500,000 rows are kept for the page.
struct RotorRigResult {
  std::size_t rows = 0;
  std::vector<sim::RotorStandRow> kept;
};
[[nodiscard]] RotorRigResult runRotorRig(const model::VehicleParams& vehicle,
                                         const sim::RotorStandParams& params,
                                         const std::vector<double>& throttles, std::uint64_t seed,
                                         const std::function<void(const sim::RotorStandRow&)>& sink,
                                         bool collect);

/// The stand's page: speed over time, thrust and torque against speed.
[[nodiscard]] report::Page rotorRigPage(const std::vector<sim::RotorStandRow>& rows,
                                        const std::string& produced_by);

/// The truth's calibration against the paper as a text table (one line per target, a summary).
/// `world`: where the aerodynamics came from. `differs`: empty when the world's rotors are the
/// paper vehicle's (its targets apply); otherwise how they differ, said in the text, whose
/// results are then information ("info"), not a test.
[[nodiscard]] std::string calibrationText(const sim::CalibrationResult& result,
                                          const std::string& vehicle_name, const std::string& world,
                                          const std::string& differs);

/// Empty when `vehicle`'s rotors are the paper vehicle's (mass, propeller radius, rotor diagonal
/// and k_T: the calibration targets are measurements of them); otherwise what differs.
[[nodiscard]] std::string differsFromThePapersRotors(const model::VehicleParams& vehicle);

/// The calibration page: the targets' table and the truth's curves beside the paper's points.
[[nodiscard]] report::Page calibrationPage(const sim::CalibrationResult& result,
                                           const std::string& produced_by);

/// Writes `page` as DIR/STEM.html (DIR created; an existing non-directory is an error) and,
/// with `png`, DIR/STEM.png at 1200 × png_height_px through headless Chromium. Returns the
/// files written.
std::vector<std::filesystem::path> writeRigPage(const report::Page& page, const std::filesystem::path& dir,
                                                const std::string& stem, bool png, int png_height_px);

}  // namespace geaware::experiments
