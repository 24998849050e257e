// SPDX-License-Identifier: BSD-3-Clause
// F_G learned in flight (docs/controller.md, "F_G learned in flight"): the learner's start from
// the vehicle file or from nothing, and one sample per tick (control/ground_effect_learner.hpp).
#include <algorithm>
#include <cmath>
#include <utility>

#include "controller_internal.hpp"
#include "geaware/control/controller.hpp"
#include "geaware/model/finite.hpp"
#include "geaware/model/units.hpp"

namespace geaware::control {
namespace detail {

/// The learner's starting curve at its knots: the vehicle file's F_G, or none at all.
std::vector<double> learnerPrior(const model::VehicleModel& vehicle, const ControllerParams& p) {
  std::vector<double> prior;
  for (const double h : p.learner.knots_m) {
    prior.push_back(p.learn_ground_effect == GroundEffectLearning::kFromVehicle
                        ? vehicle.groundEffect().thrustRatio(h)
                        : 0.0);
  }
  return prior;
}

/// The vehicle with F_G as a table on the learner's knots, at the prior (learning on only).
model::VehicleModel learningVehicle(const model::VehicleModel& vehicle, const ControllerParams& p) {
  model::VehicleParams v = vehicle.params();
  v.additional_thrust.table.heights_m = p.learner.knots_m;
  v.additional_thrust.table.values = learnerPrior(vehicle, p);
  return model::VehicleModel(std::move(v));
}

}  // namespace detail

namespace {
constexpr double kLearnAboveGearM = 0.01;  ///< no sample this close above the gear's height [m]
}  // namespace

void Controller::learnInFlight(const ControllerInput& in, const Eigen::Vector3d& tau_hat_B) noexcept {
  // Both learners sample at the height the ranger measured this tick, and neither where its
  // estimate would hold more than the ground's cushion and leveling:
  // - within a centimetre of the landing gear's height the feet may be on the ground (standing
  //   before a take-off, touching down): their support would be learned as ground effect;
  // - under a ceiling or beside a wall the observer's estimate and the torque hold their pull;
  // - while the rotors do not carry the vehicle.
  if (!(in.height_valid && std::isfinite(in.height_m))) return;
  if (in.height_m <= min_rotor_plane_height_m_ + kLearnAboveGearM) return;
  if (mem_.proximity_active_) return;
  const double thrust_acc = mem_.thrust_acc_f_mps2_;
  if (!(thrust_acc > 0.5 * model::kGravity)) return;
  const Eigen::Matrix3d R = in.estimate.q_WB.normalized().toRotationMatrix();
  const double tilt = std::acos(std::clamp(R(2, 2), -1.0, 1.0));
  const double speed = in.estimate.v_W.head<2>().norm();

  // F_G: the paper's flight estimate F̃_G = m·z_Wᵀ·ã_ext/T_f, with the thrust filtered as the
  // observer filters it.
  if (in.external_accel_valid && model::allFinite(in.external_accel_W) &&
      learner_->update(in.height_m, in.external_accel_W.z() / thrust_acc, tilt, speed, in.estimate.v_W.z(),
                       mem_.fade_est_) == LearnerSample::kUsed) {
    ground_effect_.setThrustTableValues(learner_->values());
    reference_map_.setThrustTableValues(learner_->values());
  }

  // The leveling scale: the torque the rotors do not explain, from torque INDI's filtered
  // quantities (ω̇_f and τ̂_B through the same filter), y = J·ω̇_f + ω_f × J·ω_f − τ̂_B, against
  // the file's leveling torque at the measured height and the filtered thrust, faded like the
  // rest of the model: x = M̂_G(h)·T_f·Rᵀ·(z_B × z_W).
  const Eigen::Vector3d& w = mem_.last_w_f_;
  const Eigen::Vector3d y =
      inertia_kgm2_.cwiseProduct(mem_.last_w_dot_f_) + w.cross(inertia_kgm2_.cwiseProduct(w)) - tau_hat_B;
  const Eigen::Vector3d x = R.transpose() * (mem_.fade_est_ * ground_effect_.levelingShape(in.height_m) *
                                             mass_kg_ * thrust_acc * R.col(2).cross(Eigen::Vector3d::UnitZ()));
  const double before = leveling_learner_->scale();
  (void)leveling_learner_->update(x.head<2>(), y.head<2>(), tilt, speed, in.estimate.v_W.z());
  const double s = leveling_learner_->scale();
  if (s != before) {
    ground_effect_.setLevelingScale(s);
    reference_map_.setLevelingScale(s);
  }
}

}  // namespace geaware::control
