// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Quadrotor-platform identification with a level board (paper, sections "additional thrust"
// and "mixing matrix under ground effect"):
//
//  - additional thrust: the measured thrust f̃_z against T̃ = k_T·Σn² (eq. 6). The paper forms
//    F̃_G(h) = z_Wᵀf̃/T̃ − 1 per sample (eq. 9) with k_T from heights out of ground effect, and
//    fits F_G(h) = g2/(h² + g1) (eq. 8). We fit k_T, g1 and g2 together, with Ceres and a
//    robust loss, on f̃_z = k_T·Σn²·(1 + g2/(h² + g1)): k_T from the highest heights alone
//    would carry their small but non-zero F_G into every F̃_G sample (F_G(1 m) ≈ 0.7 %).
//    The paper's k_T from the top height band is reported beside it (MixingFit::k_T_top).
//  - mixing (rotor-speed differences, eq. 2): roll torque = (√2·b/4)·k_TX·(−n1²+n2²+n3²−n4²),
//    pitch the same with k_TY and (−n1²+n2²−n3²+n4²), yaw = k_I·(−n1²−n2²+n3²+n4²); linear
//    least squares over all level samples, and per height band to show how each coefficient
//    changes with height (eq. 18, k̄(h) = k(h)/k(top band) − 1).
//
// Only level-board samples (|tilt| ≤ level_tilt_deg) are used here; the tilted ones are for
// the leveling torque (ident/leveling_fit.hpp).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/ident/table_fit.hpp"

namespace geaware::ident {

struct PlatformFitOptions {
  RobustOptions robust;
  double level_tilt_deg = 0.5;   ///< samples with |tilt| ≤ this count as a level board [deg]
  int height_bands = 6;          ///< equal-count height bands for the per-height coefficients
  std::size_t min_band_samples = 20;  ///< bands with fewer samples are not fitted
  /// Knots of F_G as a table (fitAdditionalThrustTable). Samples above the top knot follow the
  /// 1/h² tail and are what separates k_T from F_G, so the default leaves heights above 0.5 m
  /// to the tail.
  TableOptions thrust_table = {{}, 0.5, 120};
};

/// f̃_z = k_T·Σn²·(1 + F_G(h)), F_G(h) = g2/(h² + g1).
struct AdditionalThrustFit {
  Estimate k_T_N_per_rpm2;
  Estimate g1_m2;
  Estimate g2_m2;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< of (k_T, g1, g2)
  FitStats stats;                                        ///< residuals in N
  double h_min_m = kNaN;                                 ///< height range of the samples [m]
  double h_max_m = kNaN;
  std::vector<std::string> warnings;
  /// Problems that block `--out` unless accepted: a parameter that ended at its bound.
  std::vector<std::string> blocking;
};

/// f̃_z = k_T·Σn²·(1 + F_G(h)) with F_G a table (table_fit.hpp): k_T and the knot values.
struct AdditionalThrustTableFit {
  Estimate k_T_N_per_rpm2;
  TableCurve F_G;          ///< dimensionless values; covariance by the delta method
  FitStats stats;          ///< residuals in N
  double h_min_m = kNaN;   ///< height range of the level samples [m]
  double h_max_m = kNaN;
  std::size_t tail_samples = 0;  ///< samples above the top knot (they fix k_T)
  std::vector<std::string> warnings;
};

/// The coefficients of one height band (k_T here is the effective k_T·(1 + F_G(h))).
struct HeightBand {
  double h_min_m = kNaN;
  double h_max_m = kNaN;
  double h_mean_m = kNaN;
  std::size_t count = 0;  ///< samples (a row that is a mean counts as its samples)
  std::optional<Estimate> k_T_N_per_rpm2;
  std::optional<Estimate> k_TX_N_per_rpm2;
  std::optional<Estimate> k_TY_N_per_rpm2;
  std::optional<Estimate> k_I_Nm_per_rpm2;
};

struct MixingFit {
  std::optional<Estimate> k_TX_N_per_rpm2;  ///< absent when the log has no roll excitation
  std::optional<Estimate> k_TY_N_per_rpm2;  ///< … no pitch excitation
  std::optional<Estimate> k_I_Nm_per_rpm2;  ///< … no yaw excitation
  FitStats roll, pitch, yaw;                ///< residuals in N·m
  Estimate k_T_top_N_per_rpm2;              ///< k_T from the top height band (the paper's way)
  std::vector<HeightBand> bands;            ///< lowest first; the last is the top band
  std::vector<std::string> warnings;
};

/// The joint fit of k_T, g1, g2 on the level samples. Throws IdentError.
[[nodiscard]] AdditionalThrustFit fitAdditionalThrust(const PlatformLog& log,
                                                      const PlatformFitOptions& options = {});

/// The joint fit of k_T and F_G at the knots of options.thrust_table, linear in (k_T,
/// k_T·F_G(h_j)). Throws IdentError, e.g. when no level sample lies above the top knot.
[[nodiscard]] AdditionalThrustTableFit fitAdditionalThrustTable(
    const PlatformLog& log, const PlatformFitOptions& options = {});

/// k_T alone: f̃_z = k_T·Σn² on every level sample, F_G taken as 0 (one height band).
struct ThrustAloneFit {
  Estimate k_T_N_per_rpm2;
  FitStats stats;          ///< residuals in N
  double h_min_m = kNaN;   ///< height range of the level samples [m]
  double h_max_m = kNaN;
  std::vector<std::string> warnings;
};

/// For a stand at one height or out of ground effect, where g1 and g2 cannot be fitted and the
/// user asks for k_T alone (`identify platform --k-T-only`). Throws IdentError.
[[nodiscard]] ThrustAloneFit fitThrustAlone(const PlatformLog& log, const PlatformFitOptions& options = {});

/// k_TX, k_TY, k_I overall and per height band; b is the diagonal rotor distance [m].
/// Throws IdentError when the log has too few level samples.
[[nodiscard]] MixingFit fitMixing(const PlatformLog& log, double diagonal_rotor_distance_m,
                                  const PlatformFitOptions& options = {});

/// The paper's per-sample F̃_G = f̃_z/(k_T·Σn²) − 1 (eq. 9), for plots; NaN where Σn² = 0.
[[nodiscard]] std::vector<double> measuredAdditionalThrust(const PlatformLog& log,
                                                           double k_T_N_per_rpm2);

/// The F_G curve's standard error at height h from the fit's covariance (delta method) [-].
[[nodiscard]] double additionalThrustStdError(const AdditionalThrustFit& fit, double h_m);

}  // namespace geaware::ident
