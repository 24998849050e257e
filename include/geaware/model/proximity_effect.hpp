// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Ceiling and wall effects of one rotor by the image method (docs/world.md §10), shared by the
// simulator's truth (sim/obstacles.hpp) and the controller's feed-forward (control/): the law
// has no free parameter, so both sides use the same closed form; they differ in what they know
// of the geometry (the truth: each rotor's exact distance to each surface; the controller:
// single-beam rangers and the assumption that the surface a beam meets is square to it).
//
// A rotor draws its inflow from the half-space above its disc, like a sink of strength
// Q = A·v_i (A = πR², v_i the induced velocity) at the disc centre. A plane at distance d, with
// unit normal n pointing from the plane to the rotor, is represented by the sink's mirror image
// at distance 2d behind the plane, which induces at the rotor the velocity
//     u = −Q/(4π·(2d)²)·n = −v_i·(R/(4d))²·n            (toward the surface).
// Its component along the rotor axis a opposes the inflow, which moves along −a (a ceiling:
// n = −a, u = +v_i·(R/(4d))²·a), so the air crosses the disc at v_i − u·a. At constant power
// (T times the inflow speed held, the argument of Cheeseman & Bennett 1955 for the ground) the
// thrust becomes
//     T/T∞ = 1/(1 − (u·a)/v_i) = 1/(1 − (R/(4d))²)        (ceiling: the same form as the ground),
// and its component across the axis is air arriving sideways that the rotor turns into its
// slipstream: the rotor takes its momentum, ṁ·u⊥ with ṁ = ρ·A·v_i and T = 2ρ·A·v_i², so
//     F⊥ = (T/2)·u⊥/v_i,  |F⊥| = T·R²/(32·d²)              (a wall: pulled toward it).
// The ground below the disc acts through the wake (the source image of Cheeseman & Bennett),
// which the ground-effect models already hold. A surface counts as upstream (sink image) with
// full weight while its normal toward the rotor is at least 60° from the rotor axis
// (n·a ≤ kUpstreamFullCos: a ceiling, a wall, and a wall seen from a vehicle tilted by up to 30°)
// and fades out linearly by n·a = kUpstreamFadeCos (a floor under a vehicle tilted by less than
// 37°), so that neither a tilt nor a sloping face switches it on or off at once.
//
// Literature: the ceiling effect is measured stronger than this image law near the ceiling
// (Conyers, Rutherford & Valavanis, ICUAS 2018; Hsiao & Chirarattananon, IEEE/ASME T-Mech
// 2019, who add the neighbouring rotors' inflow) and walls attract a hovering multirotor
// (Yang et al. 2025, "Wall Inspector", suction toward the wall growing with rotor speed and
// falling with distance). The image law is the closed form without fitted constants; the
// as-built world states how far it may be off (docs/world.md §10).

#include <algorithm>

#include <Eigen/Core>

namespace geaware::model {

/// Closer than this many radii the image law is held at its value there (it diverges at
/// d = R/4; at R/2 it gives T/T∞ = 4/3 and a side pull of T/8) [-].
inline constexpr double kProximityMinDistanceRadii = 0.5;
/// n·a up to which a surface has the sink image's full weight [-].
inline constexpr double kUpstreamFullCos = 0.5;
/// n·a at which a surface below the rotor plane has faded out of the sink-image law [-].
inline constexpr double kUpstreamFadeCos = 0.8;

/// The velocity the image of one plane induces at a rotor, per unit induced velocity v_i:
/// −(R/(4d))²·n·w, with d held at ≥ kProximityMinDistanceRadii·R and w the upstream weight
/// (1 for n·a ≤ kUpstreamFullCos, falling linearly to 0 at n·a = kUpstreamFadeCos) [-]. `n` is the plane's
/// unit normal toward the rotor, `a` the rotor's unit axis (thrust direction), both in one
/// frame; a non-positive or non-finite distance gives zero.
[[nodiscard]] inline Eigen::Vector3d imageInflow(double distance_m, double radius_m,
                                                 const Eigen::Vector3d& n,
                                                 const Eigen::Vector3d& a) noexcept {
  if (!(distance_m > 0.0) || !(radius_m > 0.0)) return Eigen::Vector3d::Zero();
  const double na = n.dot(a);
  const double w = na <= kUpstreamFullCos
                       ? 1.0
                       : std::max(0.0, (kUpstreamFadeCos - na) / (kUpstreamFadeCos - kUpstreamFullCos));
  if (w == 0.0) return Eigen::Vector3d::Zero();
  const double d = std::max(distance_m, kProximityMinDistanceRadii * radius_m);
  const double k = radius_m / (4.0 * d);
  return (-w * k * k) * n;
}

/// A rotor's response to the summed image velocity `u` (per unit v_i, imageInflow's sum): the
/// thrust ratio T/T∞ = 1/(1 − u·a) and the side force per newton of free-air thrust, u⊥/2.
struct ProximityResponse {
  double thrust_ratio = 1.0;                                   ///< T/T∞ [-]
  Eigen::Vector3d side_force_per_N = Eigen::Vector3d::Zero();  ///< F⊥/T∞, across a [-]
};

[[nodiscard]] inline ProximityResponse proximityResponse(const Eigen::Vector3d& u,
                                                         const Eigen::Vector3d& a) noexcept {
  ProximityResponse r;
  const double ua = u.dot(a);
  // Several surfaces at the closest allowed distance could together stop the inflow: the sum is
  // held at the single-surface bound ((1/(4·0.5))² = 1/4 along the axis: T/T∞ ≤ 4/3).
  const double k_max = 1.0 / (4.0 * kProximityMinDistanceRadii);
  r.thrust_ratio = 1.0 / (1.0 - std::min(ua, k_max * k_max));
  r.side_force_per_N = 0.5 * (u - ua * a);
  return r;
}

}  // namespace geaware::model
