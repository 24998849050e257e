// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Ground contact of the landing gear (issue 13 item 5): each foot is a point on a massless
// spring–damper leg that pushes along the surface normal and rubs along the surface.
//
// For foot k at CoM-relative position r_k (body), over the tangent plane of the terrain sampled
// under it at the start of the step (height H, unit normal n):
//   compression   δ_k = (H(x, y) − z)·n_z                 (the distance under the plane along n)
//   foot velocity v_k = v_CoM + R·(ω × r_k)
//   normal force  F_n = max(0, k·δ − c·(v_k·n))  while δ > 0   (it pushes, never pulls)
//   friction      F_t = −μ·F_n·v_t / √(|v_t|² + v_s²),   v_t = v_k − (v_k·n)·n
// with c = 2·ζ·√(k·m/N) the damping of the foot's share of the mass (N feet). The friction is
// Coulomb's, regularised below the slip speed v_s: a foot standing still on a slope creeps at
// v_s·tan θ/√(μ² − tan² θ) instead of sticking (docs/world.md §9).
//
// Closed forms (tests/sim/ground_contact_test.cpp): on level ground at rest each of N feet is
// compressed by m·g/(N·k); a level drop at v₀ onto N feet without gravity leaves at the
// velocity of the damped oscillator x(t) = v₀/ω_d·e^(−ζωt)·sin(ω_d t) at the instant its force
// k·x + c·ẋ returns to zero; a sliding vehicle decelerates at μ·g.
//
// No allocation after construction; deterministic.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "geaware/sim/rigid_body.hpp"
#include "geaware/sim/terrain.hpp"
#include "geaware/sim/wrench.hpp"

namespace geaware::sim {

/// The landing gear's legs and feet (TruthParams::landing_gear). Per foot; the defaults of
/// sim::fromNominal are documented there and in docs/truth-file.md.
struct LandingGearParams {
  /// Leg stiffness per foot along the surface normal [N/m]. 0: no contact model (a foot under
  /// the surface is a strike, as before issue 13).
  double stiffness_N_per_m = 0.0;
  /// Damping ratio of one foot's spring with the foot's share of the mass, m/N [-].
  double damping_ratio = 0.0;
  /// Coulomb friction coefficient between a foot and the surface [-].
  double friction_coefficient = 0.0;
  /// Below this sliding speed the friction is regularised (viscous) [m/s].
  double slip_speed_mps = 0.01;
  /// A foot compressed more than this has broken its leg or bottomed out: a strike [m].
  double max_compression_m = 0.02;

  [[nodiscard]] bool enabled() const noexcept { return stiffness_N_per_m > 0.0; }
};

/// One foot at the end of a step (RK4's last stage).
struct FootContact {
  double compression_m = 0.0;   ///< δ, 0 when clear of the surface [m]
  double normal_force_N = 0.0;  ///< F_n [N]
  bool touching = false;        ///< δ > 0
};

class GroundContact {
 public:
  /// `feet_from_com_B`: foot positions relative to the CoM, body [m]; `mass_kg` the vehicle's.
  GroundContact(const LandingGearParams& params, std::vector<Eigen::Vector3d> feet_from_com_B,
                double mass_kg);

  /// Samples the terrain under each foot for the coming step (height and normal); on flat
  /// ground (flat_z) no terrain call is made. `terrain` null: no ground, no contact.
  void sample(const Terrain* terrain, const double* flat_z_m, const RigidBodyState& body,
              const Eigen::Matrix3d& R_WB) noexcept;

  /// Body-frame force and torque about the CoM at one RK4 stage; records the feet when `keep`.
  [[nodiscard]] Wrench wrench(const RigidBodyState& x, const Eigen::Matrix3d& R_WB,
                              bool keep) noexcept;

  /// Each foot at the last kept stage (the end of the last step).
  [[nodiscard]] const std::vector<FootContact>& feet() const noexcept { return feet_; }
  /// Feet touching at the end of the last step.
  [[nodiscard]] int touchingFeet() const noexcept;
  /// The damping coefficient c of one foot [N·s/m].
  [[nodiscard]] double dampingNsPerM() const noexcept { return damping_Ns_per_m_; }
  [[nodiscard]] const LandingGearParams& params() const noexcept { return params_; }

 private:
  LandingGearParams params_;
  std::vector<Eigen::Vector3d> feet_B_;       // relative to the CoM
  std::vector<Eigen::Vector3d> ground_W_;     // (x, y, H) sampled under each foot
  std::vector<Eigen::Vector3d> normal_W_;     // unit normal there
  std::vector<FootContact> feet_;
  double damping_Ns_per_m_ = 0.0;
  bool has_ground_ = false;
};

}  // namespace geaware::sim
