// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The truth plant: rigid body + motors/ESC/battery + per-rotor aerodynamics over a
// terrain, advanced at a fixed step by RK4, with ground-strike detection. The forces and torques
// are a sum of independent contributions behind one small interface (STYLE.md point 7):
// gravity, rotor aerodynamics, motor reaction/gyroscopic torques, and any disturbance added
// later (turbulence, wind gusts) through addContribution().
//
// Centre of gravity: PlantState reports the GEOMETRIC centre (rotor-plane centre, body origin);
// the plant integrates the centre of mass, which sits at cog_offset_B from it, because Newton's
// law is simple there (m·a_CoM = f, torques about the CoM), and converts after every step:
//   p_geo = p_CoM − R·c,   v_geo = v_CoM − R·(ω × c),   a_geo = a_CoM − R·(ω̇ × c + ω × (ω × c)).
// The CoM state is the one carried from step to step, so no round-off accumulates in the
// conversion. Rotor positions handed to the aerodynamics are relative to the CoM; a CoG offset
// therefore gives the thrust a lever arm and tilts the vehicle, as it does on a real one.
//
// Terrain under the rotors: sampled once per step (height and normal under each rotor at the
// start of the step); at each RK4 stage the surface is continued from that sample along its
// tangent plane, so the vertical distance is exact for planes and first-order for curved
// terrain over the few millimetres a rotor moves in one step. A step edge is thus seen at the
// start of the step that crosses it. FlatGround is recognised and needs no terrain calls.
//
// Ground-effect fractions: by default the rotor aerodynamics' distance-dependent factors (φ_i,
// the near-ground drag factors) are evaluated once per step, at the rotor distances predicted
// for the middle of the step (p + R·r_i moved by dt/2 along its velocity, over the same tangent
// plane), and held over the four RK4 stages; everything else (rotor speeds, the forward-flight
// fade, drag, the rigid body) is evaluated at every stage. The held midpoint value is
// second-order accurate over the step, like a midpoint rule, where a value held from the start
// of the step would lag by half a step. PlantConfig::ground_effect_per_stage evaluates them at
// every stage instead. The difference and the speed-up are measured in docs/sim-aerodynamics.md
// ("Performance").
//
// As built (docs/world.md): the ESC/link dead time (MotorParams::dead_time_s) delays every
// throttle command through a ring sized at construction (ThrottleDelay); the quadratic airframe
// drag (RotorAeroParams::airframe_drag_area_m2 > 0) is a built-in contribution at the CoM; the
// ground-effect factors are the in-flight ones (RotorAerodynamics::flightFactors).
//
// Determinism: no randomness here; the same inputs give bit-identical states (contributions
// that draw noise must be seeded). No allocation in step().

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/sim/motors.hpp"
#include "geaware/sim/ground_contact.hpp"
#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/rigid_body.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/terrain.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware/sim/wrench.hpp"

namespace geaware::sim {

/// What every contribution sees at one evaluation of the dynamics (an RK4 stage).
struct ContributionContext {
  double t_s = 0.0;                                    ///< time of this evaluation [s]
  RigidBodyState body;                                 ///< CoM state at this evaluation
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();  ///< attitude as a rotation matrix
  std::array<double, 4> n_rpm{};                       ///< rotor speeds [rpm]
  std::array<double, 4> n_dot_rpm_per_s{};             ///< rotor accelerations [rpm/s]
  /// Each rotor's distance to the terrain at this evaluation. Filled when an added contribution
  /// may read it; the built-in aerodynamics use their own mid-step factors, held over the step,
  /// unless PlantConfig::ground_effect_per_stage.
  RotorSurroundings surroundings;
  Eigen::Vector3d wind_W = Eigen::Vector3d::Zero();    ///< air velocity at the vehicle [m/s]
};

/// One independent physical contribution to the wrench on the vehicle.
class Contribution {
 public:
  virtual ~Contribution() = default;
  [[nodiscard]] virtual const char* name() const noexcept = 0;
  /// Called once at the start of every step, before the stage evaluations: a stochastic
  /// disturbance draws its (seeded) noise here and holds it over the step. Default: nothing.
  virtual void beginStep(double /*t_s*/, double /*dt_s*/, const PlantState& /*state*/) noexcept {}
  /// Whether wrench() reads ctx.surroundings (the plant fills them at every stage only when some
  /// contribution does). Default: true.
  [[nodiscard]] virtual bool readsSurroundings() const noexcept { return true; }
  /// Body-frame force and torque about the CoM. Called four times per step; no allocation.
  [[nodiscard]] virtual Wrench wrench(const ContributionContext& ctx) noexcept = 0;
};

class Obstacles;

namespace detail {
class GravityContribution;
class RotorAeroContribution;
class AirframeDragContribution;
class MotorTorqueContribution;
}  // namespace detail

/// Which built-in contributions are on, and the step.
struct PlantConfig {
  double step_s = 1e-3;  ///< default fixed step (1 kHz) [s]
  bool gravity = true;   ///< m·g along −z_W
  bool rotor_aerodynamics =
      true;                    ///< per-rotor thrust with ground effect, k_I·n² torque, rotor drag
  bool motor_reaction = true;  ///< J_R·ṅ reaction torque
  bool gyroscopic = true;      ///< −ω × Σ J_R·Ω_i·d_i·z_B
  bool ground_strikes = true;  ///< end the run when a rotor rim or foot goes under the surface
  /// The landing gear touches the ground (TruthParams::landing_gear, sim/ground_contact.hpp):
  /// a foot under the surface is pushed back and rubs along it; only a rotor disc under the
  /// surface or a leg compressed beyond its max_compression_m is a strike. Off (the default):
  /// any foot under the surface is a strike. Needs a terrain and a gear with stiffness > 0.
  bool ground_contact = false;
  int rim_samples = 8;         ///< points sampled on each rotor-disc rim for strikes [-]
  /// Evaluate the ground-effect factors at every RK4 stage instead of once per step at the
  /// predicted mid-step rotor distances (see the header comment): ≈ 50 % more time per step,
  /// trajectories within a micrometre of each other over a low, fast flight.
  bool ground_effect_per_stage = false;
};

enum class StrikePart { kRotorDisc, kLandingFoot, kBody };

/// The end of a flight: something went under the terrain surface or into an obstacle.
struct Crash {
  double t_s = 0.0;                                   ///< time of the step that found it [s]
  Eigen::Vector3d point_W = Eigen::Vector3d::Zero();  ///< the deepest point under the surface [m]
  StrikePart part = StrikePart::kRotorDisc;           ///< what struck
  int index = 0;         ///< rotor (mixer order) or foot index, 0-based
  double depth_m = 0.0;  ///< how far under the surface [m] (0 for an obstacle)
  bool obstacle = false;  ///< into one of the obstacles (obstacles.hpp), not the terrain
};

/// One line for logs and the CLI, e.g. "t = 0.4350 s: landing foot 1 struck the ground at
/// (0.562, 0.562, -0.003) m, 3.1 mm deep" (rotors and feet numbered from 1 there), or
/// "… rotor disc 2 struck an obstacle at (…) m".
[[nodiscard]] std::string describe(const Crash& crash);

/// Outcome of one step.
struct StepResult {
  bool throttle_fault = false;  ///< a non-finite throttle was replaced (NaN → 0, ±∞ → 1/0)
  std::optional<Crash> crash;   ///< set once the vehicle has struck the terrain
};

/// `samples` unit vectors (cos θ_k, sin θ_k), θ_k = 2πk/samples, around a rotor disc's rim
/// (in the disc's own x–y axes): where strikes and clearances sample the disc.
[[nodiscard]] std::vector<Eigen::Vector2d> rimUnitCircle(int samples);

/// Each rotor's vertical distance to the terrain under it and the surface normal there, from
/// the CoM position and the rotor positions relative to the CoM. A null terrain gives ∞ and z_W.
[[nodiscard]] RotorSurroundings rotorSurroundings(
    const Terrain* terrain, const Eigen::Vector3d& p_com_W, const Eigen::Matrix3d& R_WB,
    const std::array<Eigen::Vector3d, 4>& rotor_from_com_B) noexcept;

class Plant {
 public:
  /// Throws std::invalid_argument listing every invalid field of `params` or `config`, or a
  /// non-finite initial state. The rotors start at `initial.n_rpm`. A null terrain means no
  /// ground (no ground effect, no strikes).
  Plant(const TruthParams& params, std::shared_ptr<const Terrain> terrain,
        const PlantConfig& config = {}, const PlantState& initial = {});

  /// Advance by the configured step / by dt (> 0 and finite, else nothing happens and the
  /// result carries throttle_fault). Throttles are clamped to [0, 1]; a non-finite one is a
  /// fault: NaN becomes 0, ±∞ is clamped, the step proceeds and the fault is counted. After a
  /// crash the state is frozen and every step returns the crash. No allocation.
  [[nodiscard]] StepResult step(const std::array<double, 4>& throttle);
  [[nodiscard]] StepResult step(const std::array<double, 4>& throttle, double dt_s);

  /// Add a disturbance (or any other contribution); it is summed from the next step on.
  void addContribution(std::unique_ptr<Contribution> contribution);

  /// Boxes around the vehicle from the next step on (sim/obstacles.hpp): their ceiling and wall
  /// effects are added as a contribution and, with ground_strikes on, a rotor rim, foot or the
  /// body inside one is a strike. Call at most once; null does nothing.
  void setObstacles(std::shared_ptr<const Obstacles> obstacles);
  [[nodiscard]] const Obstacles* obstacles() const noexcept { return obstacles_.get(); }

  /// Air velocity at the vehicle from now on (the aerodynamics see v_CoM − wind) [m/s].
  void setWind_W(const Eigen::Vector3d& wind_W) noexcept { wind_W_ = wind_W; }

  [[nodiscard]] const PlantState& state() const noexcept { return state_; }
  [[nodiscard]] const RigidBodyState& centreOfMassState() const noexcept { return body_; }
  [[nodiscard]] const std::optional<Crash>& crash() const noexcept { return crash_; }
  [[nodiscard]] long throttleFaults() const noexcept { return throttle_faults_; }
  [[nodiscard]] const TruthParams& params() const noexcept { return params_; }
  [[nodiscard]] const PlantConfig& config() const noexcept { return config_; }
  [[nodiscard]] const Motors& motors() const noexcept { return motors_; }
  /// A motor fault from the next step on (Motors::setSpeedScale).
  void setMotorSpeedScale(std::size_t i, double scale) noexcept { motors_.setSpeedScale(i, scale); }
  [[nodiscard]] const Terrain* terrain() const noexcept { return terrain_.get(); }
  /// The landing gear's contact with the ground; null unless PlantConfig::ground_contact is on
  /// with a terrain and a gear of stiffness > 0.
  [[nodiscard]] const GroundContact* contact() const noexcept {
    return contact_ ? &*contact_ : nullptr;
  }
  /// Aerodynamic outputs (per-rotor thrust and gain) at the end of the last step, from RK4's
  /// last stage like PlantState::a_W, with the step's ground-effect factors (all zero when the
  /// rotor aerodynamics are off).
  [[nodiscard]] const RotorAeroOutput& lastAero() const noexcept;
  /// The contributions, in summation order (built-ins first).
  [[nodiscard]] const std::vector<std::unique_ptr<Contribution>>& contributions() const noexcept {
    return contributions_;
  }

  /// The throttle that holds rotor speed n in steady state at the battery's present state [-].
  [[nodiscard]] double throttleForSteadySpeed(double n_rpm) const noexcept {
    return motors_.throttleForSteadySpeed(n_rpm);
  }

 private:
  /// Sum of the contributions and the rigid-body derivative at time t0 + s for the CoM state
  /// in ctx_.body (an RK4 stage), into `out`.
  void evaluate(double s, RigidBodyDerivative& out);
  /// Convert the CoM state (and its derivative at the end of the step) to PlantState:
  /// a_W and w_dot_B come from RK4's last stage, within O(dt²) of the final state's.
  void publish(const RigidBodyDerivative& end_derivative);
  [[nodiscard]] std::optional<Crash> detectStrike() const noexcept;
  /// Sample the terrain under each rotor at the start of a step.
  void sampleTerrain() noexcept;
  /// Height of the surface under the point c near rotor i, continued from the step's sample
  /// along its tangent plane (−∞ without terrain) [m].
  [[nodiscard]] double groundUnder(std::size_t i, const Eigen::Vector3d& c) const noexcept;
  /// Each rotor's vertical distance to the surface predicted for the middle of a step of dt [m].
  [[nodiscard]] std::array<double, 4> midStepGroundDistances(double dt_s) const noexcept;

  TruthParams params_;
  std::shared_ptr<const Terrain> terrain_;
  std::shared_ptr<const Obstacles> obstacles_;
  PlantConfig config_;
  MassProperties mass_;
  std::array<Eigen::Vector3d, 4> rotor_from_com_B_{};
  std::vector<Eigen::Vector2d> rim_unit_;  // (cos θ_k, sin θ_k) around each rotor disc
  Motors motors_;
  std::vector<std::unique_ptr<Contribution>> contributions_;
  // The built-ins among contributions_ (null when switched off), called through their final
  // types so that the compiler can inline them; added contributions follow them, virtually.
  detail::GravityContribution* gravity_ = nullptr;
  detail::RotorAeroContribution* aero_ = nullptr;
  detail::AirframeDragContribution* airframe_drag_ = nullptr;
  detail::MotorTorqueContribution* motor_torques_ = nullptr;
  std::optional<GroundContact> contact_;  // the landing gear on the ground (ground_contact)
  std::optional<ThrottleDelay> dead_time_;  // the ESC/link dead time (when > 0)
  std::size_t builtin_count_ = 0;
  bool stage_surroundings_ = true;  // fill ctx_.surroundings at every stage (someone reads them)
  const RotorAeroOutput* last_aero_ =
      nullptr;  // inside the aerodynamics contribution (heap: survives moves)
  ContributionContext ctx_;
  double t0_s_ = 0.0;                    // start time of the step in progress
  double stage_last_s_ = 0.0;            // s of RK4's last stage in the step in progress (dt)
  std::optional<double> flat_z_m_;       // the terrain is FlatGround at this level
  std::optional<double> terrain_top_m_;  // known highest point of the terrain (strike pre-check)
  std::array<Eigen::Vector3d, 4>
      ground_sample_W_{};  // (x, y, H) under each rotor at the step start
  std::array<Eigen::Vector3d, 4> ground_normal_W_{};  // the surface normal there
  RigidBodyState body_;
  Eigen::Matrix3d R_WB_ = Eigen::Matrix3d::Identity();  // rotation of body_.q_WB (unit)
  PlantState state_;
  Eigen::Vector3d wind_W_ = Eigen::Vector3d::Zero();
  std::optional<Crash> crash_;
  long throttle_faults_ = 0;
};

}  // namespace geaware::sim
