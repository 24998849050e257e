// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Identification from flight logs (formats in ident/rig_logs.hpp):
//
//  - F_G and k_T from a hover descent (paper eq. 10): F̃_G = m·z_Wᵀã_ext/T̃ with T̃ = k_T·Σn²,
//    where the external-acceleration observer used the vehicle's k_T. The total z force
//    m·a_ext,z + k_T·Σn² is fitted as k_T'·Σn²·(1 + g2/(h² + g1)), with Ceres and a robust loss:
//    k_T' is the hover's own k_T (it equals k_T when the observer's k_T was right), fixed by the
//    heights out of ground effect. Assumes a near-level attitude (z_Wᵀz_B ≈ 1), as in a hover.
//  - k_T alone from a hover out of ground effect (the paper's third k_T, from its hovering
//    flight): the same total z force fitted as k_T'·Σn²·(1 + F_G(h)) with the base vehicle's
//    F_G (≈ 0 above 1 m), one linear parameter; the log's heights need not vary.
//  - the drag table D(h) (paper eq. 20): in the body frame the in-plane external force is the
//    rotor drag, m·x_Bᵀã_ext = −d_x·x_Bᵀv and m·y_Bᵀã_ext = −d_y·y_Bᵀv (f_G is along z_B and
//    does not enter); per height band, linear least squares gives d_x(h) and d_y(h).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/platform_fit.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::ident {

/// k_T_N_per_rpm2: the k_T the log's external acceleration was computed with. The result is
/// the level board's kind: k_T in hover, g1, g2, their covariance, residuals in N. Throws
/// IdentError when the log cannot constrain k_T, g1 and g2.
[[nodiscard]] AdditionalThrustFit fitHoverAdditionalThrust(const FlightLog& log, double mass_kg,
                                                      double k_T_N_per_rpm2,
                                                      const RobustOptions& robust = {});

/// k_T in hover out of ground effect (one parameter; F_G(h) is `base`'s curve, not fitted).
struct HoverThrustFit {
  Estimate k_T_N_per_rpm2;  ///< the hover's own k_T' [N/rpm²]
  FitStats stats;           ///< residuals in N
  double h_min_m = kNaN;    ///< lowest and highest logged height [m]
  double h_max_m = kNaN;
  std::vector<std::string> warnings;
};

/// `base` gives the mass and the k_T the log's external acceleration was computed with, and
/// F_G(h). Warns when the log goes below `min_height_m` (F_G is then not negligible and its
/// error enters k_T'). Throws IdentError when the log has no usable sample.
[[nodiscard]] HoverThrustFit fitHoverThrust(const FlightLog& log, const model::VehicleParams& base,
                                            double min_height_m = 1.0,
                                            const RobustOptions& robust = {});

/// k_T alone from a hover that never comes near the ground (every logged height at or above
/// 3 rotor radii, where `identify flight --hover` takes F_G as 0): m·a_ext,z + k_T·Σn² = k_T'·Σn²,
/// one linear parameter. k_T_N_per_rpm2 is the k_T the log's external acceleration was computed
/// with. Throws IdentError when the log has no usable sample.
[[nodiscard]] HoverThrustFit fitHoverThrustOutOfGroundEffect(const FlightLog& log, double mass_kg,
                                                             double k_T_N_per_rpm2,
                                                             const RobustOptions& robust = {});

/// Heights at or above this many rotor radii count as out of ground effect for the hover fit.
inline constexpr double kHoverGroundEffectRadii = 3.0;

struct DragFitOptions {
  RobustOptions robust;
  int height_bands = 5;               ///< equal-count height bands
  std::size_t min_band_samples = 50;  ///< bands with fewer samples are not fitted
};

struct DragBand {
  double h_min_m = kNaN;
  double h_max_m = kNaN;
  double h_mean_m = kNaN;
  std::size_t count = 0;
  Estimate d_x_N_per_mps;
  Estimate d_y_N_per_mps;
  FitStats x, y;  ///< residuals in N
};

struct DragFit {
  std::vector<DragBand> bands;  ///< lowest first, only bands that could be fitted
  std::vector<std::string> warnings;
};

/// Throws IdentError when no band can be fitted (too few samples, no horizontal speed).
[[nodiscard]] DragFit fitDrag(const FlightLog& log, double mass_kg,
                              const DragFitOptions& options = {});

/// The drag table of a vehicle file from the fitted bands (heights: the bands' mean heights,
/// exactly the logged height for a band flown at one height). A band with a coefficient fitted
/// negative is left out (never written as 0); no band left: an empty table.
[[nodiscard]] model::DragTableParams dragTable(const DragFit& fit);

}  // namespace geaware::ident
