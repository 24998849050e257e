// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Spearman rank correlation (paper eq. 4) and the correlation table of the paper's
// supplementary material, computed from a quadrotor-platform log.
//
// r_s(x, y) = cov[R(x), R(y)] / (σ[R(x)]·σ[R(y)]), with R the ranks; tied values get the
// average of the ranks they span, so the formula stays the Pearson correlation of the ranks
// (the shortcut 1 − 6Σd²/(n(n²−1)) is only exact without ties and is not used).
//
// How the platform's measurements are separated (the vehicle is level on the platform, so the
// world and body axes coincide):
//  - τ_B, the rotors' torque: the measured roll and yaw torques x_Wᵀτ, z_Wᵀτ. The board tilts
//    about y only, so these hold τ_B (plus noise); computing them from the rotor speeds
//    through the mixer instead would make their correlation with N_base(2), N_base(4) exactly 1.
//  - τ_G, the leveling torque: y_Wᵀτ_G = measured y torque − the mixer's pitch torque
//    (√2·b/4)·k_TY·(−n1²+n2²−n3²+n4²) (eq. 2).
//  - f_G, the additional thrust: measured z force − T̃, T̃ = k_T·Σn² (eq. 6).
//  - N_base = diag(k_T, k_TX, k_TY, k_I)⁻¹·M·N² (eq. 5), h, and the tilt δ.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/ident/rig_logs.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::ident {

/// 1-based ranks of v; tied values share the average of their ranks.
[[nodiscard]] std::vector<double> averageRanks(std::span<const double> v);

/// Pearson correlation; NaN when a variable is constant or there are fewer than 2 samples.
[[nodiscard]] double pearson(std::span<const double> x, std::span<const double> y);

/// Spearman rank correlation with ties handled by average ranks (eq. 4).
[[nodiscard]] double spearman(std::span<const double> x, std::span<const double> y);

/// Weighted forms, for rows that stand for `w[i]` samples each (a stand table's mean rows and
/// their count): the ranks and the correlation the table expanded to its counts gives (each row
/// repeated w[i] times). w[i] > 0.
[[nodiscard]] std::vector<double> averageRanks(std::span<const double> v, std::span<const double> w);
[[nodiscard]] double pearson(std::span<const double> x, std::span<const double> y,
                             std::span<const double> w);

struct CorrelationTable {
  /// "N_base(1)" … "N_base(4)", "h", "delta".
  std::vector<std::string> row_names;
  /// "x_W'tau_B", "z_W'tau_B", "y_W'tau_G", "y_W'tau_G/sin(delta)", "f_G".
  std::vector<std::string> column_names;
  Eigen::MatrixXd r;                 ///< rows × columns; NaN where a variable is constant
  std::vector<std::size_t> samples;  ///< samples behind each column (rows weighted by their count)
};

struct CorrelationOptions {
  /// y_Wᵀτ_G/sin δ is computed on the samples with |tilt| above this [deg].
  double level_tilt_deg = 0.5;
};

/// The supplementary table from a platform log. `vehicle` (validated) gives k_T, k_TY and b
/// for the separation above and the mixer for N_base. Rows with a count (PlatformLog::count)
/// weigh as that many samples: the table is the one of the log expanded to its counts.
[[nodiscard]] CorrelationTable platformCorrelations(const PlatformLog& log,
                                                    const model::VehicleParams& vehicle,
                                                    const CorrelationOptions& options = {});

}  // namespace geaware::ident
