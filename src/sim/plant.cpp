// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/plant.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "geaware/model/field_check.hpp"
#include "geaware/model/finite.hpp"
#include "geaware/sim/obstacles.hpp"
#include "geaware/sim/terrains.hpp"

namespace geaware::sim {
namespace detail {

// ---------------------------------------------------------------------------------------------
// The built-in contributions.
// ---------------------------------------------------------------------------------------------

/// Weight, m·g along −z_W, expressed in the body frame. No torque about the CoM.
class GravityContribution final : public Contribution {
 public:
  GravityContribution(double mass_kg, double g_mps2) : weight_N_(mass_kg * g_mps2) {}
  [[nodiscard]] const char* name() const noexcept override { return "gravity"; }
  [[nodiscard]] Wrench wrench(const ContributionContext& ctx) noexcept override {
    Wrench w;
    w.force_B = ctx.R_WB.row(2).transpose() * -weight_N_;  // Rᵀ·(0, 0, −m·g)
    return w;
  }

 private:
  double weight_N_;
};

/// The per-rotor aerodynamics (thrust with ground effect, k_I·n² torque, rotor drag).
class RotorAeroContribution final : public Contribution {
 public:
  RotorAeroContribution(const RotorGeometry& geometry, const RotorAeroParams& params)
      : aero_(geometry, params) {}
  [[nodiscard]] const char* name() const noexcept override { return "rotor_aerodynamics"; }
  [[nodiscard]] Wrench wrench(const ContributionContext& ctx) noexcept override {
    return stageWrench(ctx, true);
  }
  /// The wrench at one RK4 stage; the per-rotor outputs (last()) are kept only when asked for
  /// (the plant asks at the last stage, the one lastAero() reports).
  [[nodiscard]] Wrench stageWrench(const ContributionContext& ctx, bool keep_outputs) noexcept {
    const Eigen::Vector3d v_air_W = ctx.body.v_W - ctx.wind_W;
    if (!held_) factors_ = aero_.flightFactors(ctx.surroundings.ground_distance_m);
    if (!keep_outputs) return aero_.wrench(ctx.n_rpm, ctx.R_WB, v_air_W, ctx.body.w_B, factors_);
    last_ = aero_.compute(ctx.n_rpm, ctx.R_WB, v_air_W, ctx.body.w_B, factors_);
    return last_.wrench;
  }
  [[nodiscard]] const RotorAeroOutput& last() const noexcept { return last_; }
  [[nodiscard]] const RotorAerodynamics& model() const noexcept { return aero_; }
  /// Use these ground factors at every evaluation until the next hold() (once per step).
  void hold(const RotorGroundFactors& factors) noexcept {
    factors_ = factors;
    held_ = true;
  }

 private:
  RotorAerodynamics aero_;
  RotorAeroOutput last_;
  RotorGroundFactors factors_;
  bool held_ = false;  // false: from ctx.surroundings at every evaluation
};

/// Quadratic airframe drag at the CoM, F = −½·ρ·C_dA·|v_air|·v_air (body frame; no torque).
/// Only built when C_dA > 0.
class AirframeDragContribution final : public Contribution {
 public:
  explicit AirframeDragContribution(const RotorAeroParams& p)
      : half_rho_cda_(0.5 * p.air_density_kg_per_m3 * p.airframe_drag_area_m2) {}
  [[nodiscard]] const char* name() const noexcept override { return "airframe_drag"; }
  [[nodiscard]] Wrench wrench(const ContributionContext& ctx) noexcept override {
    const Eigen::Vector3d v_air_W = ctx.body.v_W - ctx.wind_W;
    Wrench w;
    w.force_B = ctx.R_WB.transpose() * (-half_rho_cda_ * v_air_W.norm() * v_air_W);
    return w;
  }

 private:
  double half_rho_cda_;  // ½·ρ·C_dA [kg/m]
};

/// Motor reaction (J_R·ṅ) and gyroscopic torques.
class MotorTorqueContribution final : public Contribution {
 public:
  MotorTorqueContribution(const TruthParams& p, bool reaction, bool gyroscopic)
      : J_R_kgm2_(p.motor.J_R_kgm2),
        yaw_sign_(p.yaw_sign),
        reaction_(reaction),
        gyroscopic_(gyroscopic) {}
  [[nodiscard]] const char* name() const noexcept override { return "motor_torques"; }
  [[nodiscard]] Wrench wrench(const ContributionContext& ctx) noexcept override {
    return motorTorques(J_R_kgm2_, yaw_sign_, ctx.n_rpm, ctx.n_dot_rpm_per_s, ctx.body.w_B,
                        reaction_, gyroscopic_);
  }

 private:
  double J_R_kgm2_;
  std::array<double, 4> yaw_sign_;
  bool reaction_;
  bool gyroscopic_;
};

}  // namespace detail

namespace {

const TruthParams& validated(const TruthParams& p, const PlantConfig& c, const PlantState& s) {
  std::vector<model::FieldError> errors = p.validate();
  if (!(std::isfinite(c.step_s) && c.step_s > 0.0 && c.step_s <= 0.1)) {
    errors.push_back({"config.step_s", std::to_string(c.step_s), "a finite step in (0, 0.1] s"});
  }
  if (c.rim_samples < 3 || c.rim_samples > 64) {
    errors.push_back({"config.rim_samples", std::to_string(c.rim_samples), "3…64"});
  }
  bool rpm_ok = true;
  for (double n : s.n_rpm) rpm_ok &= std::isfinite(n);
  if (!std::isfinite(s.t_s) || !model::allFinite(s.p_W) || !model::allFinite(s.v_W) ||
      !model::allFinite(s.q_WB.coeffs()) || !(s.q_WB.norm() > 0.5) || !model::allFinite(s.w_B) || !rpm_ok) {
    errors.push_back({"initial state", "non-finite or degenerate",
                      "finite values and a non-degenerate quaternion"});
  }
  if (!errors.empty()) {
    throw std::invalid_argument(model::describeErrors("Plant: invalid parameters:", errors));
  }
  return p;
}

}  // namespace

std::string describe(const Crash& crash) {
  char buf[200];
  const char* part = crash.part == StrikePart::kRotorDisc     ? "rotor disc"
                     : crash.part == StrikePart::kLandingFoot ? "landing foot"
                                                              : "body";
  if (crash.obstacle) {
    std::snprintf(buf, sizeof buf, "t = %.4f s: %s %d struck an obstacle at (%.3f, %.3f, %.3f) m",
                  crash.t_s, part, crash.index + 1, crash.point_W.x(), crash.point_W.y(),
                  crash.point_W.z());
    return buf;
  }
  std::snprintf(buf, sizeof buf,
                "t = %.4f s: %s %d struck the ground at (%.3f, %.3f, %.3f) m, %.1f mm deep",
                crash.t_s, part, crash.index + 1, crash.point_W.x(), crash.point_W.y(),
                crash.point_W.z(), crash.depth_m * 1e3);
  return buf;
}

std::vector<Eigen::Vector2d> rimUnitCircle(int samples) {
  std::vector<Eigen::Vector2d> out;
  for (int k = 0; k < samples; ++k) {
    const double a = 2.0 * std::numbers::pi * k / samples;
    out.emplace_back(std::cos(a), std::sin(a));
  }
  return out;
}

RotorSurroundings rotorSurroundings(
    const Terrain* terrain, const Eigen::Vector3d& p_com_W, const Eigen::Matrix3d& R_WB,
    const std::array<Eigen::Vector3d, 4>& rotor_from_com_B) noexcept {
  RotorSurroundings s;
  for (std::size_t i = 0; i < 4; ++i) {
    if (terrain == nullptr) {
      s.ground_distance_m[i] = std::numeric_limits<double>::infinity();
      s.ground_normal_W[i] = Eigen::Vector3d::UnitZ();
      continue;
    }
    const Eigen::Vector3d c = p_com_W + R_WB * rotor_from_com_B[i];
    s.ground_distance_m[i] = c.z() - terrain->heightAt(c.x(), c.y());
    s.ground_normal_W[i] = terrain->normalAt(c.x(), c.y());
  }
  return s;
}

Plant::Plant(const TruthParams& params, std::shared_ptr<const Terrain> terrain,
             const PlantConfig& config, const PlantState& initial)
    : params_(validated(params, config, initial)),
      terrain_(std::move(terrain)),
      config_(config),
      mass_(params.mass_kg, params.inertia_kgm2),
      motors_(params, initial.n_rpm) {
  if (params_.motor.dead_time_s > 0.0)
    dead_time_.emplace(params_.motor.dead_time_s, config_.step_s);
  for (std::size_t i = 0; i < 4; ++i)
    rotor_from_com_B_[i] = params_.rotor_position_B[i] - params_.cog_offset_B;
  rim_unit_ = rimUnitCircle(config_.rim_samples);
  if (config_.gravity) {
    auto gravity =
        std::make_unique<detail::GravityContribution>(params_.mass_kg, params_.gravity_mps2);
    gravity_ = gravity.get();
    contributions_.push_back(std::move(gravity));
  }
  if (config_.rotor_aerodynamics) {
    auto aero =
        std::make_unique<detail::RotorAeroContribution>(params_.rotorGeometry(), params_.aero);
    aero_ = aero.get();
    last_aero_ = &aero->last();
    contributions_.push_back(std::move(aero));
  }
  if (config_.rotor_aerodynamics && params_.aero.airframe_drag_area_m2 > 0.0) {
    auto drag = std::make_unique<detail::AirframeDragContribution>(params_.aero);
    airframe_drag_ = drag.get();
    contributions_.push_back(std::move(drag));
  }
  if (config_.motor_reaction || config_.gyroscopic) {
    auto motor = std::make_unique<detail::MotorTorqueContribution>(params_, config_.motor_reaction,
                                                                   config_.gyroscopic);
    motor_torques_ = motor.get();
    contributions_.push_back(std::move(motor));
  }
  if (config_.ground_contact && terrain_ != nullptr && params_.landing_gear.enabled()) {
    std::vector<Eigen::Vector3d> feet;
    for (const Eigen::Vector3d& f : params_.landing_feet_B) feet.push_back(f - params_.cog_offset_B);
    contact_.emplace(params_.landing_gear, std::move(feet), params_.mass_kg);
  }
  builtin_count_ = contributions_.size();
  // Only the aerodynamics evaluated per stage and added contributions read the per-stage
  // distances (addContribution switches them back on).
  stage_surroundings_ = config_.ground_effect_per_stage;

  // The CoM state from the geometric-centre state (see the header).
  state_ = initial;
  state_.q_WB.normalize();
  R_WB_ = state_.q_WB.toRotationMatrix();
  const Eigen::Matrix3d& R = R_WB_;
  const Eigen::Vector3d& c = params_.cog_offset_B;
  body_.p_W = state_.p_W + R * c;
  body_.v_W = state_.v_W + R * state_.w_B.cross(c);
  body_.q_WB = state_.q_WB;
  body_.w_B = state_.w_B;
  state_.n_rpm = motors_.speedsRpm();
  t0_s_ = state_.t_s;
  // Shortcuts the terrain offers: no virtual calls on flat ground, a strike pre-check against
  // its highest point. Other terrains take the general path.
  if (terrain_ != nullptr) {
    flat_z_m_ = terrain_->flatLevel();
    terrain_top_m_ = terrain_->heightBound();
  }
  for (auto& n : ground_normal_W_) n = Eigen::Vector3d::UnitZ();
}

void Plant::sampleTerrain() noexcept {
  if (terrain_ == nullptr || flat_z_m_) return;
  const Eigen::Matrix3d& R = R_WB_;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d c = body_.p_W + R * rotor_from_com_B_[i];
    ground_sample_W_[i] = Eigen::Vector3d(c.x(), c.y(), terrain_->heightAt(c.x(), c.y()));
    ground_normal_W_[i] = terrain_->normalAt(c.x(), c.y());
  }
}

double Plant::groundUnder(std::size_t i, const Eigen::Vector3d& c) const noexcept {
  if (flat_z_m_) return *flat_z_m_;
  if (terrain_ == nullptr) return -std::numeric_limits<double>::infinity();  // infinitely far
  // The tangent plane at the step's sample: z = H0 − (n_x·Δx + n_y·Δy)/n_z.
  const Eigen::Vector3d& g = ground_sample_W_[i];
  const Eigen::Vector3d& n = ground_normal_W_[i];
  return g.z() - (n.x() * (c.x() - g.x()) + n.y() * (c.y() - g.y())) / n.z();
}

std::array<double, 4> Plant::midStepGroundDistances(double dt_s) const noexcept {
  // Rotor centre c_i = p + R·r_i moves at v + ω_W × R·r_i; half a step along that velocity.
  const Eigen::Matrix3d& R = R_WB_;
  const Eigen::Vector3d w_W = R * body_.w_B;
  std::array<double, 4> d{};
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d r_W = R * rotor_from_com_B_[i];
    const Eigen::Vector3d c = body_.p_W + r_W + (0.5 * dt_s) * (body_.v_W + w_W.cross(r_W));
    d[i] = c.z() - groundUnder(i, c);
  }
  return d;
}

const RotorAeroOutput& Plant::lastAero() const noexcept {
  static const RotorAeroOutput kNone{};
  return last_aero_ != nullptr ? *last_aero_ : kNone;
}

void Plant::addContribution(std::unique_ptr<Contribution> contribution) {
  if (contribution == nullptr)
    throw std::invalid_argument("Plant::addContribution: null contribution");
  if (contribution->readsSurroundings()) stage_surroundings_ = true;
  contributions_.push_back(std::move(contribution));
}

StepResult Plant::step(const std::array<double, 4>& throttle) {
  return step(throttle, config_.step_s);
}

StepResult Plant::step(const std::array<double, 4>& throttle, double dt_s) {
  StepResult result;
  if (crash_) {
    result.crash = crash_;
    return result;
  }
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
    // A broken clock is the caller's fault like a broken throttle: refuse, flag, keep the state.
    result.throttle_fault = true;
    ++throttle_faults_;
    return result;
  }
  // 1. Guard the inputs: never a NaN into the motors.
  std::array<double, 4> t{};
  for (std::size_t i = 0; i < 4; ++i) {
    if (std::isnan(throttle[i])) {
      t[i] = 0.0;
      result.throttle_fault = true;
    } else {
      if (std::isinf(throttle[i])) result.throttle_fault = true;
      t[i] = std::clamp(throttle[i], 0.0, 1.0);
    }
  }
  if (result.throttle_fault) ++throttle_faults_;

  // 2. Fix the motor targets, the ground-effect factors (at the rotor distances predicted for
  //    mid-step, see plant.hpp) and the disturbances' noise for this step.
  t0_s_ = state_.t_s;
  motors_.beginStep(dead_time_ ? dead_time_->apply(t0_s_, t) : t, dt_s);
  sampleTerrain();
  if (contact_) contact_->sample(terrain_.get(), flat_z_m_ ? &*flat_z_m_ : nullptr, body_, R_WB_);
  if (aero_ != nullptr && !config_.ground_effect_per_stage)
    aero_->hold(aero_->model().flightFactors(midStepGroundDistances(dt_s)));
  for (std::size_t k = builtin_count_; k < contributions_.size(); ++k)
    contributions_[k]->beginStep(t0_s_, dt_s, state_);

  // 3. RK4 over the CoM state; each stage sees the exact motor speeds at its time. The last
  //    stage's derivative (time t + dt, state x + dt·k3) is kept for a_W, ω̇ and lastAero(): it
  //    is within O(dt²) of the derivative at the final state (≈ 1e-5 m/s² at 1 kHz, far below
  //    any sensor's noise) and saves a fifth evaluation of every contribution.
  //    The scheme is rk4Step's, written out so that each stage state is built where the
  //    contributions read it (ctx_.body) rather than copied there: copying freshly written
  //    stage states stalls on store forwarding (≈ 5 % of the step).
  stage_last_s_ = dt_s;
  const double h = dt_s;
  RigidBodyDerivative k1;
  RigidBodyDerivative k2;
  RigidBodyDerivative k3;
  RigidBodyDerivative k4;
  ctx_.body = body_;
  evaluate(0.0, k1);
  ctx_.body = advance(body_, k1, 0.5 * h);
  evaluate(0.5 * h, k2);
  ctx_.body = advance(body_, k2, 0.5 * h);
  evaluate(0.5 * h, k3);
  ctx_.body = advance(body_, k3, h);
  evaluate(h, k4);
  RigidBodyDerivative sum;
  sum.p_dot = k1.p_dot + 2.0 * k2.p_dot + 2.0 * k3.p_dot + k4.p_dot;
  sum.v_dot = k1.v_dot + 2.0 * k2.v_dot + 2.0 * k3.v_dot + k4.v_dot;
  sum.q_dot = k1.q_dot + 2.0 * k2.q_dot + 2.0 * k3.q_dot + k4.q_dot;
  sum.w_dot = k1.w_dot + 2.0 * k2.w_dot + 2.0 * k3.w_dot + k4.w_dot;
  body_ = advance(body_, sum, h / 6.0);
  body_.q_WB.normalize();
  motors_.endStep();
  state_.t_s = t0_s_ + dt_s;
  publish(k4);

  // 5. Ground strikes, then obstacles.
  if (config_.ground_strikes && terrain_ != nullptr) {
    crash_ = detectStrike();
    result.crash = crash_;
  }
  if (config_.ground_strikes && obstacles_ && !crash_) {
    crash_ = obstacleStrike(*obstacles_, params_, state_.p_W, R_WB_, state_.t_s, rim_unit_);
    result.crash = crash_;
  }
  return result;
}

void Plant::setObstacles(std::shared_ptr<const Obstacles> obstacles) {
  if (!obstacles || obstacles->empty()) return;
  if (obstacles_) throw std::logic_error("Plant::setObstacles: obstacles are already set");
  obstacles_ = std::move(obstacles);
  if (config_.rotor_aerodynamics) addContribution(std::make_unique<ProximityContribution>(params_, obstacles_));
}

void Plant::evaluate(double s, RigidBodyDerivative& out) {
  const RigidBodyState& x = ctx_.body;
  ctx_.t_s = t0_s_ + s;
  ctx_.R_WB = rotationOf(x.q_WB);
  motors_.speedsAt(s, ctx_.n_rpm, ctx_.n_dot_rpm_per_s);
  if (stage_surroundings_) {
    for (std::size_t i = 0; i < 4; ++i) {
      const Eigen::Vector3d c = x.p_W + ctx_.R_WB * rotor_from_com_B_[i];
      ctx_.surroundings.ground_distance_m[i] = c.z() - groundUnder(i, c);
      ctx_.surroundings.ground_normal_W[i] = ground_normal_W_[i];
    }
  }
  ctx_.wind_W = wind_W_;
  // Summed in the order of contributions_ (built-ins first), the same in every run.
  Wrench total;
  if (gravity_ != nullptr) total += gravity_->wrench(ctx_);
  if (aero_ != nullptr) total += aero_->stageWrench(ctx_, s == stage_last_s_);
  if (airframe_drag_ != nullptr) total += airframe_drag_->wrench(ctx_);
  if (motor_torques_ != nullptr) total += motor_torques_->wrench(ctx_);
  if (contact_) total += contact_->wrench(x, ctx_.R_WB, s == stage_last_s_);
  for (std::size_t k = builtin_count_; k < contributions_.size(); ++k)
    total += contributions_[k]->wrench(ctx_);
  out = rigidBodyDerivative(x, ctx_.R_WB, total, mass_);
}

void Plant::publish(const RigidBodyDerivative& end) {
  R_WB_ = body_.q_WB.toRotationMatrix();
  const Eigen::Matrix3d& R = R_WB_;
  const Eigen::Vector3d& c = params_.cog_offset_B;
  const Eigen::Vector3d& w = body_.w_B;
  state_.q_WB = body_.q_WB;
  state_.w_B = w;
  state_.p_W = body_.p_W - R * c;
  state_.v_W = body_.v_W - R * w.cross(c);
  state_.a_W = end.v_dot - R * (end.w_dot.cross(c) + w.cross(w.cross(c)));
  state_.w_dot_B = end.w_dot;
  state_.n_rpm = motors_.speedsRpm();
}

std::optional<Crash> Plant::detectStrike() const noexcept {
  const Eigen::Matrix3d& R = R_WB_;  // state_.q_WB is body_.q_WB
  const Terrain& terrain = *terrain_;
  std::optional<Crash> worst;
  // With ground contact a foot may sink into the surface as far as its leg gives.
  const double foot_allowance_m = contact_ ? params_.landing_gear.max_compression_m : 0.0;
  const auto check = [&](const Eigen::Vector3d& pt, StrikePart part, int index) {
    const double ground_z = flat_z_m_ ? *flat_z_m_ : terrain.heightAt(pt.x(), pt.y());
    const double depth = ground_z - pt.z();
    const double allowance = part == StrikePart::kLandingFoot ? foot_allowance_m : 0.0;
    if (depth > allowance && (!worst || depth > worst->depth_m))
      worst = Crash{state_.t_s, pt, part, index, depth};
  };
  if (terrain_top_m_) {
    // The lowest point of a disc of radius r with axis z_B lies r·|(R₂₀, R₂₁)| below its
    // centre. When every disc's lowest point and every foot are at or above the terrain's highest
    // point, nothing struck and the sampling below is skipped (on flat ground this is exact).
    const double drop =
        params_.propeller_radius_m * std::sqrt(R(2, 0) * R(2, 0) + R(2, 1) * R(2, 1));
    double lowest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& r : params_.rotor_position_B)
      lowest = std::min(lowest, R.row(2).dot(r) - drop);
    for (const Eigen::Vector3d& f : params_.landing_feet_B)
      lowest = std::min(lowest, R.row(2).dot(f) + foot_allowance_m);
    if (state_.p_W.z() + lowest >= *terrain_top_m_) return std::nullopt;
  }
  const Eigen::Vector3d ex = params_.propeller_radius_m * R.col(0);
  const Eigen::Vector3d ey = params_.propeller_radius_m * R.col(1);
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d centre = state_.p_W + R * params_.rotor_position_B[i];
    for (const Eigen::Vector2d& u : rim_unit_)
      check(centre + u.x() * ex + u.y() * ey, StrikePart::kRotorDisc, static_cast<int>(i));
  }
  for (std::size_t k = 0; k < params_.landing_feet_B.size(); ++k) {
    check(state_.p_W + R * params_.landing_feet_B[k], StrikePart::kLandingFoot,
          static_cast<int>(k));
  }
  return worst;
}

}  // namespace geaware::sim
