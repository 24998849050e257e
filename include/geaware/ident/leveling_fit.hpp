// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Leveling torque from the quadrotor platform with a tilted board (paper, section "leveling
// torque", eq. 14–15): the vehicle stays level, the board below it is tilted by δ about the
// body y axis, and the ground pushes the vehicle towards the board's attitude. With the
// platform's sign convention (docs/paper-facts.md: a positive tilt gives a negative torque,
// "leveling")
//
//   y_Wᵀτ_G = −M_G(h)·T·sin δ,   M_G(h) = scale·h/(h² + g3·h + g4)²,   T = k_T·Σn²,
//
// where τ_G is the measured torque minus the rotors' own τ_B = M·N² (eq. 2, with k_TY). The
// shape (g3, g4) and the scale are fitted together with Ceres and a robust loss. Above about
// 10° of tilt the measured torque stops growing (docs/paper-facts.md), so by default only tilts
// up to max_tilt_deg are used.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/ident/table_fit.hpp"

namespace geaware::ident {

struct LevelingFitOptions {
  RobustOptions robust;
  double level_tilt_deg = 0.5;   ///< |tilt| ≤ this is a level board, not used here [deg]
  double max_tilt_deg = 10.0;    ///< larger tilts are left out (the torque saturates) [deg]
  /// Sign s in y_Wᵀτ_G = s·M_G(h)·T·sin δ: −1 for the platform convention above. A fit whose
  /// data have the other sign fails with a message saying so.
  double torque_sign = -1.0;
  /// Knots of M_G as a table (fitLevelingTable); by default every logged tilted height.
  TableOptions table;
};

/// The vehicle constants the leveling fit needs (from the level-board fits or a vehicle file).
struct LevelingInputs {
  double k_T_N_per_rpm2 = kNaN;            ///< for T = k_T·Σn²
  double k_TY_N_per_rpm2 = kNaN;           ///< for the rotors' own pitch torque
  double diagonal_rotor_distance_m = kNaN; ///< b
};

struct LevelingFit {
  Estimate g3_m;
  Estimate g4_m2;
  Estimate scale_m4;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< of (g3, g4, scale)
  FitStats stats;                                        ///< residuals in N·m
  double peak_height_m = kNaN;      ///< (−g3 + √(g3² + 12·g4))/6
  double h_min_m = kNaN;            ///< height range of the samples used [m]
  double h_max_m = kNaN;
  double tilt_min_deg = kNaN;       ///< |tilt| range of the samples used [deg]
  double tilt_max_deg = kNaN;
  std::vector<std::string> warnings;
  /// Problems that block `--out` unless accepted: a parameter that ended at its bound.
  std::vector<std::string> blocking;
};

/// y_Wᵀτ_G = s·M_G(h)·T·sin δ with M_G a table (table_fit.hpp), linear in the knot values.
struct LevelingTableFit {
  TableCurve M_G;                   ///< values in m (N·m per N of thrust per unit sin δ)
  FitStats stats;                   ///< residuals in N·m
  double peak_height_m = kNaN;      ///< the knot with the largest M_G
  double h_min_m = kNaN;            ///< height range of the samples used [m]
  double h_max_m = kNaN;
  double tilt_min_deg = kNaN;       ///< |tilt| range of the samples used [deg]
  double tilt_max_deg = kNaN;
  std::vector<std::string> warnings;
};

/// Throws IdentError when the log has too few tilted samples or the fit fails.
[[nodiscard]] LevelingTableFit fitLevelingTable(const PlatformLog& log,
                                                const LevelingInputs& inputs,
                                                const LevelingFitOptions& options = {});

/// Throws IdentError when the log has too few tilted samples or the fit fails.
[[nodiscard]] LevelingFit fitLeveling(const PlatformLog& log, const LevelingInputs& inputs,
                                      const LevelingFitOptions& options = {});

/// The per-sample M̃_G = y_Wᵀτ_G/(s·T·sin δ) [m] of the samples the fits use (level_tilt_deg <
/// |tilt| ≤ max_tilt_deg), NaN elsewhere; for plots.
[[nodiscard]] std::vector<double> measuredLevelingCoefficient(
    const PlatformLog& log, const LevelingInputs& inputs, const LevelingFitOptions& options = {});

/// M_G(h) [m] for given shape and scale.
[[nodiscard]] double levelingCoefficient(double g3_m, double g4_m2, double scale_m4, double h_m);

/// The M_G curve's standard error at height h from the fit's covariance (delta method) [m].
[[nodiscard]] double levelingCoefficientStdError(const LevelingFit& fit, double h_m);

}  // namespace geaware::ident
