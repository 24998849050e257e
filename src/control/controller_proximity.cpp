// SPDX-License-Identifier: BSD-3-Clause
// Ceiling and wall effects in the controller (ControllerParams::proximity_compensation; issue 13
// item 4, docs/controller.md "Ceilings and walls"): the image-method law of
// model/proximity_effect.hpp at each rotor's distance to what each single-beam ranger sees.
#include <cmath>
#include <cstddef>
#include <limits>

#include "controller_internal.hpp"
#include "geaware/control/controller.hpp"
#include "geaware/model/finite.hpp"
#include "geaware/model/proximity_effect.hpp"

namespace geaware::control {

namespace {
/// Two successive readings of a beam agree within this much plus kBeamAgreeFraction of the
/// range (a lone outlier, uniform over the whole range, rarely does) [m].
constexpr double kBeamAgreeM = 0.05;
constexpr double kBeamAgreeFraction = 0.05;
/// A beam whose world direction points down more steeply than this sees the floor, the
/// lattice's business, not a wall (sin 30°) [-].
constexpr double kBeamDownZ = -0.5;
}  // namespace

Controller::GroundShapeTerms Controller::proximityTerms(const ControllerInput& in, double thrust_N,
                                                        const Eigen::Matrix3d& R) noexcept {
  GroundShapeTerms g;
  mem_.proximity_active_ = false;
  if (!params_.proximity_compensation) return g;
  // Each beam that returns is taken to meet a plane square to it: the point it sees lies at
  // mount + range·u, the plane's normal toward the vehicle is −u, and rotor i is
  // (point − r_i)·u from it. Everything is in the body frame; the rotor axis is z_B.
  const Eigen::Vector3d a = Eigen::Vector3d::UnitZ();
  std::array<Eigen::Vector3d, 4> u{};
  for (Eigen::Vector3d& v : u) v.setZero();
  bool any = false;
  for (std::size_t k = 0; k < in.beams.size(); ++k) {
    const model::BeamReading& b = in.beams[k];
    const bool usable = b.valid && b.range_m > 0.0 && std::isfinite(b.range_m) && std::isfinite(b.t_s) &&
                        model::allFinite(b.direction_B) && model::allFinite(b.mount_B) &&
                        std::abs(b.direction_B.norm() - 1.0) <= 1e-3;
    if (!usable) {
      beam_mem_.last_range_m[k] = std::numeric_limits<double>::quiet_NaN();
      beam_mem_.consistent[k] = false;
      continue;
    }
    if (b.t_s != beam_mem_.last_t_s[k]) {  // a new reading: does it agree with the last one?
      const double last = beam_mem_.last_range_m[k];
      beam_mem_.consistent[k] =
          std::isfinite(last) && std::abs(b.range_m - last) <= kBeamAgreeM + kBeamAgreeFraction * b.range_m;
      beam_mem_.last_t_s[k] = b.t_s;
      beam_mem_.last_range_m[k] = b.range_m;
    }
    const Eigen::Vector3d dir = b.direction_B.normalized();
    if ((R * dir).z() < kBeamDownZ) continue;  // the floor
    mem_.proximity_active_ = true;  // a surface in view, agreed on or not: the learner waits
    if (!beam_mem_.consistent[k]) continue;
    const Eigen::Vector3d point = b.mount_B + b.range_m * dir;
    for (std::size_t i = 0; i < 4; ++i) {
      const double d = (point - rotors_B_[i]).dot(dir);
      if (d > 0.0) u[i] += model::imageInflow(d, propeller_radius_m_, -dir, a);
    }
    any = true;
  }
  if (!any) return g;
  // Rotor i must make a quarter of the reference thrust T together with its image's help: its
  // own free-air thrust is T/(4·ratio), and the surfaces add T/4·(1 − 1/ratio) along the axis
  // and T/(4·ratio)·s across it.
  Eigen::Vector3d force_B = Eigen::Vector3d::Zero();
  const double t_rotor = 0.25 * thrust_N;
  for (std::size_t i = 0; i < 4; ++i) {
    if (u[i].isZero(0.0)) continue;
    const model::ProximityResponse r = model::proximityResponse(u[i], a);
    const Eigen::Vector3d f = t_rotor * ((1.0 - 1.0 / r.thrust_ratio) * a + r.side_force_per_N / r.thrust_ratio);
    force_B += f;
    g.tau_B += rotors_B_[i].cross(f);
  }
  if (params_.acceleration != AccelerationCompensation::kIndi) g.a_W = R * force_B / mass_kg_;
  return g;
}

}  // namespace geaware::control
