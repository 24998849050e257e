// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One simulated closed-loop flight (issue 4, "Closed loop"; the data path of
// ARCHITECTURE.md): the runner owns the clock and the order of every stage.
//
// Each plant step k (1 kHz by default, t = k/plant_rate):
//   1. sensors sample the true state at t (IMU, motion capture with latency, rotor telemetry,
//      lattice ranger), each at its own rate and with its own seeded noise;
//   2. the ESKF integrates the IMU sample, then fuses the motion-capture pose delivered now;
//   3. the lattice estimator turns a ranger frame into the rotor-plane height, with the ESKF
//      attitude;
//   4. on a control tick (every plant_rate/controller.rate_hz steps, 200 Hz by default) the
//      disturbance observer (paper eq. 6) runs on the controller's inputs, then the controller
//      runs on the latest estimate, height, rotor telemetry, the observer's ã_ext and the
//      reference of the trajectory; its throttles are held until the next tick; metrics and the
//      log observe the tick (they, and only they, also read the truth);
//   5. the plant advances one step with the held throttles (wind and turbulence included).
// The controller is built from the scenario's nominal vehicle and sees nothing else: its input
// is a control::ControllerInput filled from the estimators and the telemetry. The truth
// (PlantState, TruthParams, the terrain) reaches only the metrics, the log and the initial
// condition. Details and measured numbers: docs/closed-loop.md.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/control/controller.hpp"
#include "geaware/control/controller_params.hpp"
#include "geaware/control/land_detector.hpp"
#include "geaware/control/residual_force.hpp"
#include "geaware/estimation/disturbance_observer.hpp"
#include "geaware/estimation/eskf.hpp"
#include "geaware/estimation/lattice_height.hpp"
#include "geaware/experiments/faults.hpp"
#include "geaware/experiments/tracking_metrics.hpp"
#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/disturbances.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/sensors.hpp"
#include "geaware/sim/obstacles.hpp"
#include "geaware/sim/terrain.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware/traj/flat_output.hpp"
#include "geaware/traj/trajectory.hpp"

namespace geaware::experiments {

/// Disturbances of the truth that the controller does not know.
struct DisturbanceSettings {
  bool turbulence = true;  ///< near-ground recirculation buffeting
  sim::GroundTurbulenceParams turbulence_params;
  bool wind = false;  ///< air velocity handed to the plant every step
  sim::WindParams wind_params;
  bool unsteadiness = false;  ///< buffeting at any height (blade imbalance…), docs/world.md
  sim::UnsteadinessParams unsteadiness_params;
};

/// What closes the loop.
enum class LoopMode {
  kClosed,         ///< estimator + controller fly the trajectory
  kOpenLoopHover,  ///< throttles held at the initial hover; sensors run, no estimator or
                   ///< controller (benchmarks of the plant and sensors)
};

/// How the error-state filter starts. The filter always waits for the first motion-capture
/// pose (≈ latency after t = 0); with all offsets zero it initialises itself from that pose
/// (v and biases zero). Non-zero offsets start it from the pose *plus* these errors, with the
/// filter's initial covariance, to exercise convergence.
struct EstimatorStart {
  Eigen::Vector3d position_error_m = Eigen::Vector3d::Zero();    ///< added to the pose [m]
  Eigen::Vector3d velocity_error_mps = Eigen::Vector3d::Zero();  ///< initial velocity [m/s]
  Eigen::Vector3d attitude_error_rad = Eigen::Vector3d::Zero();  ///< q ⊗ Exp(δθ), body [rad]
};

/// Bins of the hover experiment's angle error E(h): true rotor-plane height in
/// [0, max_height_m) cut into bins of bin_width_m.
struct HeightBinning {
  double bin_width_m = 0.02;  ///< [m]
  double max_height_m = 2.0;  ///< heights at or above are not binned [m]
};

/// Everything that defines one flight. Same scenario and seed → bit-identical result and log.
struct FlightScenario {
  /// The vehicle the controller believes in (and the nominal vehicle of the truth).
  model::VehicleParams vehicle;
  /// The vehicle as it is; empty: sim::fromNominal(vehicle).
  std::optional<sim::TruthParams> truth;
  /// A seeded (seed below) mismatch applied to the truth; empty: none.
  std::optional<sim::MismatchSpec> mismatch;
  /// Surface under the vehicle; null: flat ground at z = 0.
  std::shared_ptr<const sim::Terrain> terrain;
  /// Boxes around it (ceilings, walls; sim/obstacles.hpp, docs/world.md §10; at most
  /// kMaxObstacles); null: none.
  std::shared_ptr<const sim::Obstacles> obstacles;
  /// The single-beam rangers that look up and sideways (at most
  /// control::ControllerInput::kMaxBeams); empty: sim::defaultBeamRangers() when there are
  /// obstacles, none otherwise.
  std::vector<sim::BeamRangerParams> beam_rangers;
  /// A beam reading older than this is not handed to the controller [s].
  double max_beam_age_s = 0.1;
  /// The reference; the vehicle starts hovering at its first point. Required.
  std::shared_ptr<const traj::Trajectory> trajectory;
  /// Gains, compensation switches and the control rate (controller.rate_hz).
  control::ControllerParams controller;
  /// The learned residual force, required for AccelerationCompensation::kNeural.
  std::shared_ptr<const control::ResidualForceModel> residual;
  sim::SensorSuiteParams sensors;
  estimation::EskfParams eskf;
  /// Lattice height estimator; empty: LatticeHeightParams::forVehicle(vehicle).
  std::optional<estimation::LatticeHeightParams> lattice;
  DisturbanceSettings disturbances;
  /// The plant's built-in contributions (all on by default; switch one off only for an
  /// ablation). step_s is ignored: the step is 1/plant_rate_hz.
  sim::PlantConfig plant;
  EstimatorStart estimator_start;
  HeightBinning hover_bins;
  LoopMode loop = LoopMode::kClosed;
  std::uint64_t seed = 1;         ///< sensors, disturbances and mismatch draw from it
  double plant_rate_hz = 1000.0;  ///< fixed plant step; a multiple of controller.rate_hz [Hz]
  double start_hover_s = 1.0;     ///< hover at the first point before the trajectory [s]
  double settle_s = 0.0;          ///< flown (at the last point) after the trajectory ends [s]
  /// The longest flight validate() lets fly: start hover + trajectory + settling, refused before
  /// it starts (`fly --max-sim-s`, scenario key max_sim_s) [s].
  double max_sim_s = 3600.0;
  /// A ranger height older than this is not handed to the controller (it keeps its last one
  /// and flags kFlagHeightInvalid) [s].
  double max_height_age_s = 0.05;
  /// Check before flying that the flat map's rotor speeds stay within the motors' range along
  /// the whole trajectory (nominal vehicle, ground effect at the reference's height above the
  /// terrain), sampled at the control rate.
  bool check_feasibility = true;
  /// Faults injected on purpose (experiments/faults.hpp; the fault campaign); empty: none.
  std::vector<Fault> faults;
  /// Start standing on the landing gear under the first reference point (level, at the
  /// reference's yaw, legs compressed by the weight, motors idling at throttle 0) instead of
  /// hovering at it: a take-off. Needs plant.ground_contact.
  bool start_on_ground = false;
  /// The land detector (control/land_detector.hpp) on the controller's side: once it finds the
  /// vehicle on its gear it takes the throttles to zero. Empty: none (the controller flies on).
  std::optional<control::LandDetectorParams> land_detector;
};

/// The most boxes a scenario may hold (each is evaluated at every RK4 stage for every rotor).
inline constexpr std::size_t kMaxObstacles = 1000;

/// Makes a landing or take-off flyable, from its trajectory (traj::Landing, traj::TakeOff):
/// ground contact on in the plant, the flight starts standing on the gear (take-off) or ends
/// with the land detector (landing), and the clearance guard, which holds the rotor plane above
/// the gear while tracking, is off (this flight goes down to the gear on purpose). Nothing for
/// other trajectories. Idempotent: called wherever a scenario is finished (fly, scenario files,
/// sweeps, Python), after its controller configuration is set.
void applyTouchdown(FlightScenario& s);

/// One problem with a scenario, e.g. {"controller.rate_hz", "300", "plant_rate_hz / rate_hz
/// an integer"}.
using ScenarioProblem = model::FieldError;

/// Thrown by runFlight() for an unusable scenario: what() lists every problem, one a line.
class InvalidScenario : public std::invalid_argument {
 public:
  explicit InvalidScenario(std::vector<ScenarioProblem> problems);
  [[nodiscard]] const std::vector<ScenarioProblem>& problems() const noexcept { return problems_; }

 private:
  std::vector<ScenarioProblem> problems_;
};

/// Every problem of the scenario (parameters of every stage, prefixed by the stage: "vehicle.",
/// "truth.", "controller.", "sensors.", "eskf.", "lattice.", "disturbances."; rates; and, when
/// the rest is valid and check_feasibility is on, the trajectory's feasibility). Empty when
/// the scenario can be flown.
/// What validate() can expect to be filled in.
enum class ScenarioStage {
  kFile,    ///< as a scenario file gives it: the residual network comes later (--neural-weights)
  kFlight,  ///< ready to fly: everything
};
[[nodiscard]] std::vector<ScenarioProblem> validate(const FlightScenario& scenario,
                                                    ScenarioStage stage = ScenarioStage::kFlight);

/// Number of controller flag bits (control::ControllerFlag) counted by the runner.
inline constexpr int kControllerFlagBits = 11;
/// Name of flag bit i ("non_finite_input", "height_invalid", …), "?" outside [0, 11).
[[nodiscard]] const char* controllerFlagName(int bit) noexcept;

/// Angle error E(h) of one height bin: the angle of the rotation between the controller's
/// desired attitude and the TRUE attitude, over the control ticks of the trajectory whose
/// true rotor-plane height fell in [h_low_m, h_high_m).
struct AngleErrorBin {
  double h_low_m = 0.0;
  double h_high_m = 0.0;
  std::uint64_t samples = 0;
  double mean_deg = 0.0;  ///< [deg]
  double rms_deg = 0.0;   ///< [deg]
  double max_deg = 0.0;   ///< [deg]
};

/// How well the estimators did (against the truth, for diagnosis; the controller never sees
/// these numbers).
struct EstimationSummary {
  estimation::EskfCounters eskf;
  std::uint64_t ranger_frames = 0;
  std::uint64_t height_valid_frames = 0;
  double position_rmse_m = 0.0;  ///< ESKF position vs truth, control ticks of the trajectory
  double velocity_rmse_mps = 0.0;
  double attitude_rmse_deg = 0.0;
  double height_rmse_m = 0.0;  ///< ranger height vs true height, valid frames of the trajectory
  /// Control ticks with each estimation::EskfFlag bit set: pose stale, IMU clipped, pose rejected.
  std::array<std::uint64_t, 3> eskf_flag_ticks{};
};

/// The F_G curve a controller learned in flight (configurations "+learn", "+learn0"; issue 13).
struct LearnedGroundEffect {
  std::vector<double> heights_m;  ///< the learner's knots [m]
  std::vector<double> f_g;        ///< F_G at each knot at the end of the flight [-]
  std::vector<bool> learned;      ///< whether enough samples reached the knot
  double offset = 0.0;            ///< the offset found far from the ground [-]
  std::uint64_t samples = 0;      ///< samples used for the curve
  /// The leveling torque's scale on the vehicle file's M_G in use at the end (the prior when
  /// never excited) [-], whether it was learned, and the samples it used.
  double leveling_scale = 1.0;
  bool leveling_learned = false;
  std::uint64_t leveling_samples = 0;

  /// The curve at h: linear between the knots, the end values held outside [-].
  [[nodiscard]] double ratio(double h_m) const noexcept;
};

/// Touchdown and lift-off, from the truth (flights with plant.ground_contact on).
struct GroundContactSummary {
  bool touched = false;  ///< a foot met the surface after the start (or the flight started on it)
  /// Plant time of the first foot contact of a flight that started in the air (NaN: none) [s].
  double touchdown_t_s = std::nan("");
  /// The geometric centre's true sinking speed at that step (positive down) [m/s].
  double touchdown_speed_mps = std::nan("");
  /// The highest the lowest foot rose above the surface, airborne again after the first
  /// touchdown: the bounce (0: none) [m].
  double bounce_m = 0.0;
  /// The largest leg compression of the flight [m].
  double max_compression_m = 0.0;
  /// The largest tilt of z_B from the vertical while a foot touched [deg].
  double max_tilt_on_ground_deg = 0.0;
  /// Plant time at which every foot had left the surface, for a flight started on it (NaN:
  /// never) [s]. Touchdown and bounce are not tracked for such a flight (a take-off).
  double liftoff_t_s = std::nan("");
  /// Airborne phases that ended on the ground again after the lift-off (a take-off's hops).
  int recontacts = 0;
  /// Feet touching at the end of the flight.
  int feet_down_at_end = 0;
  bool landed = false;              ///< the land detector's verdict
  double landed_t_s = std::nan("");  ///< its time [s]
};

struct FlightResult {
  /// Reference vs TRUE geometric centre, sampled at the control rate over [0, duration] of the
  /// trajectory (up to the crash, if any).
  TrackingMetrics tracking;
  /// Hover experiment data: every bin of scenario.hover_bins, empty ones included.
  std::vector<AngleErrorBin> angle_error_by_height;
  std::optional<sim::Crash> crash;       ///< set when the flight ended in a ground strike
  std::string crash_description;         ///< sim::describe(*crash), or empty
  bool completed = false;                ///< flew to the end without a crash
  std::uint64_t control_ticks = 0;       ///< every control tick, controller active or not
  std::uint64_t controller_updates = 0;  ///< ticks on which the controller ran
  std::array<std::uint64_t, kControllerFlagBits> flag_counts{};  ///< ticks with each flag set
  long throttle_faults = 0;  ///< non-finite throttles the plant replaced (expect 0)
  /// Time the clearance guard was active (controller ticks with kFlagClearanceGuard over the
  /// whole flight, start hover included); empty when the controller has no guard [s].
  std::optional<double> guard_active_s;
  EstimationSummary estimation;
  /// What the controller learned of F_G in flight; empty when it does not learn.
  std::optional<LearnedGroundEffect> learned_ground_effect;
  /// Touchdown, bounce and lift-off; empty unless the flight allows ground contact.
  std::optional<GroundContactSummary> ground_contact;
  /// With obstacles: the smallest distance from a rotor disc (its centre and eight points on its
  /// rim) to any box over the trajectory's control ticks (truth); empty without obstacles [m].
  std::optional<double> min_obstacle_clearance_m;
  double simulated_s = 0.0;       ///< plant time at the end [s]
  double wall_s = 0.0;            ///< wall time of the loop (not deterministic) [s]
  double real_time_factor = 0.0;  ///< simulated_s / wall_s [-]
};

/// What the runner exposes on every control tick (to the log, and to anyone collecting data,
/// e.g. Neural-Lander training). Valid only during the call.
struct FlightTick {
  double t_s = 0.0;                  ///< plant time [s]
  double t_traj_s = 0.0;             ///< trajectory time, t − start_hover_s [s]
  bool controller_active = false;    ///< false before the estimator has its first pose
  bool in_trajectory = false;        ///< t_traj ∈ [0, duration]: the tick counts in the metrics
  control::ControllerInput input;    ///< exactly what the controller was given
  /// The disturbance observer on this tick (paper eq. 6; estimation::DisturbanceObserver on the
  /// controller's own inputs: bias-corrected IMU, attitude estimate, rotor telemetry); invalid
  /// while the controller is inactive. Its ã_ext is also in `input`.
  estimation::DisturbanceEstimate disturbance;
  control::ControllerOutput output;  ///< its commands (zero when inactive)
  std::array<double, 4> throttle{};  ///< what goes to the motors until the next tick
  sim::PlantState truth;             ///< the true state at t (observers only)
  double true_height_m = 0.0;        ///< rotor-plane centre above the terrain under it [m]
  double attitude_error_rad = 0.0;   ///< angle between desired and true attitude [rad]
  std::uint32_t eskf_flags = 0;      ///< estimation::EskfFlag bits of the estimate the controller got
  std::uint32_t fault_bits = 0;      ///< bit i: scenario.faults[i] active (experiments/faults.hpp)
};

/// Receives every control tick. Must not throw from onTick (the runner is noexcept inside the
/// loop); report failures from finish().
class FlightObserver {
 public:
  virtual ~FlightObserver() = default;
  virtual void onTick(const FlightTick& tick) noexcept = 0;
  /// Called once after the loop, with the result.
  virtual void finish(const FlightResult& /*result*/) {}
};

/// Several observers behind one, called in the order they were added.
class ObserverList final : public FlightObserver {
 public:
  /// Adds `o` (not owned; null is ignored).
  void add(FlightObserver* o) {
    if (o != nullptr) observers_.push_back(o);
  }
  [[nodiscard]] bool empty() const noexcept { return observers_.empty(); }
  void onTick(const FlightTick& tick) noexcept override {
    for (auto* o : observers_) o->onTick(tick);
  }
  void finish(const FlightResult& result) override {
    for (auto* o : observers_) o->finish(result);
  }

 private:
  std::vector<FlightObserver*> observers_;
};

/// Flies the scenario. Throws InvalidScenario before flying when validate() finds problems;
/// otherwise runs to the end or to a ground strike (which is a result, not an error).
/// `observer` (optional) sees every control tick. No allocation inside the loop.
[[nodiscard]] FlightResult runFlight(const FlightScenario& scenario,
                                     FlightObserver* observer = nullptr);

}  // namespace geaware::experiments
