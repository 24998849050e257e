// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The ground effect's forward-flight fade from a flight log near the ground at two or more speeds
// (issue 13 item 2; the vehicle file's ground_effect.forward_fade.induced_velocity_mps,
// model::GroundEffectModel::forwardFade). Along the thrust axis z_B the whole force is the
// rotors' thrust with its ground cushion (rotor drag lies in the rotor plane):
//   m·z_Bᵀa_ext + k_T·Σn² = k_T'·Σn²·(1 + c_TL·V² + s·F_G(h)·fade(V)),  fade(V) = 1/(1 + w·V²),
// with F_G(h) the vehicle's curve, V the horizontal speed, and four parameters: k_T' (the
// flight's own k_T), c_TL (translational lift, at every height: a rotor moving edgewise gains
// thrust, 1–5 % at 3–5 m/s on small multirotors), s (the cushion in this flight against the
// vehicle's F_G: 1 when F_G was fitted in flight, ≈ 0.4 for a platform's curve flown,
// docs/world.md §3) and w = 1/v_i². Translational lift grows with V² where the fade shrinks the
// cushion: at one height the two are one V² term, so the log must fly the same speeds out of
// ground effect too. Fitted with Ceres and a robust loss, w ≥ 0 (w = 0: no fade). v_i = 1/√w,
// its standard error by the delta method, σ_v = σ_w/(2·w^1.5). No level-attitude assumption:
// every term is along z_B.

#include <string>
#include <vector>

#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::ident {

struct ForwardFadeFit {
  Estimate k_T_N_per_rpm2;         ///< k_T' [N/rpm²]
  Estimate cushion_scale;          ///< s [-]
  Estimate w_s2_per_m2;            ///< w = 1/v_i² [s²/m²]
  Estimate induced_velocity_mps;   ///< v_i [m/s]; NaN when w ≤ 0 (no fade seen)
  Estimate translational_lift_per_mps2;  ///< c_TL [s²/m²]
  FitStats stats;                  ///< residuals in N
  std::size_t near_ground = 0;     ///< samples where the vehicle's F_G(h) ≥ kFadeMinThrustRatio
  std::size_t far_from_ground = 0; ///< samples below it faster than 1 m/s
  double max_speed_near_ground_mps = 0.0;  ///< the fastest of them [m/s]
  std::vector<std::string> warnings;
  std::vector<std::string> blocking;
};

/// F_G(h) at or above this counts as near the ground for the fade fit [-].
inline constexpr double kFadeMinThrustRatio = 0.02;

/// `base` gives the mass, the k_T the log's a_ext was computed with and F_G(h); the log needs
/// height, attitude, velocity, a_ext and rotor speeds. Throws IdentError when the log has fewer
/// than 20 samples near the ground or cannot constrain the parameters.
[[nodiscard]] ForwardFadeFit fitForwardFade(const FlightLog& log, const model::VehicleParams& base,
                                            const RobustOptions& robust = {});

}  // namespace geaware::ident
