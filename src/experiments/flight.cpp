// SPDX-License-Identifier: BSD-3-Clause
// The closed-loop flight runner: see flight.hpp for the order of the stages and
// docs/closed-loop.md for the choices made here.
#include "geaware/experiments/flight.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <memory>
#include <optional>
#include <utility>

#include "flight_internal.hpp"
#include "geaware/experiments/flight_metrics.hpp"
#include "geaware/model/rotation.hpp"
#include "geaware/model/units.hpp"
#include "geaware/model/vehicle_model.hpp"
#include "geaware/sim/terrains.hpp"

namespace geaware::experiments {
namespace {

using detail::decimationOf;
using detail::heightAbove;
using detail::initialState;
using detail::plantConfigOf;
using detail::terrainOf;
using detail::truthOf;

}  // namespace

const char* controllerFlagName(int bit) noexcept {
  switch (bit) {
    case 0:
      return "non_finite_input";
    case 1:
      return "height_invalid";
    case 2:
      return "reference_invalid";
    case 3:
      return "tilt_limited";
    case 4:
      return "yaw_saturated";
    case 5:
      return "roll_pitch_saturated";
    case 6:
      return "thrust_saturated";
    case 7:
      return "clearance_guard";
    case 8:
      return "integral_held";
    case 9:
      return "motor_failure";
    case 10:
      return "terminated";
    default:
      return "?";
  }
}

namespace {

/// The disturbance observer runs on the controller's ticks with the controller's filter, so its
/// filtered quantities are delayed like the controller's own (paper: one "(·)_f").
estimation::DisturbanceObserverParams observerParamsOf(const control::ControllerParams& c) {
  estimation::DisturbanceObserverParams p;
  p.rate_hz = c.rate_hz;
  p.filter_cutoff_hz = c.filter_cutoff_hz;
  return p;
}

/// One flight: everything is allocated by the constructor, nothing in run().
class FlightLoop {
 public:
  explicit FlightLoop(const FlightScenario& s)
      : s_(s),
        vehicle_(s.vehicle),
        terrain_(terrainOf(s)),
        duration_(s.trajectory->duration()),
        dt_(1.0 / s.plant_rate_hz),
        decimation_(decimationOf(s.plant_rate_hz, s.controller.rate_hz)),
        closed_(s.loop == LoopMode::kClosed),
        truth_(truthOf(s)),
        x0_(s.start_on_ground ? detail::restingState(truth_, *terrain_, *s.trajectory)
                              : initialState(truth_, *terrain_, *s.trajectory)),
        plant_(truth_, terrain_, plantConfigOf(s), x0_),
        sensors_(s.sensors, s.seed),
        eskf_(std::make_unique<estimation::Eskf>(s.eskf)),  // ≈ 125 kB: on the heap
        lattice_(s.lattice.value_or(estimation::LatticeHeightParams::forVehicle(s.vehicle))),
        observer_(vehicle_, observerParamsOf(s.controller)),
        bins_(s.hover_bins),
        faults_(s.faults, s.seed, s.start_hover_s),
        telemetry_rpm_(Eigen::Vector4d::Constant(x0_.n_rpm[0])) {  // replaced by the first sample
    plant_.setObstacles(s.obstacles);
    const std::vector<sim::BeamRangerParams> beams =
        !s.beam_rangers.empty() ? s.beam_rangers
        : s.obstacles           ? sim::defaultBeamRangers()
                                : std::vector<sim::BeamRangerParams>{};
    for (std::size_t k = 0; k < beams.size(); ++k) beams_.emplace_back(beams[k], s.seed, k);
    if (s.obstacles && !s.obstacles->empty()) result_.min_obstacle_clearance_m = std::numeric_limits<double>::infinity();
    detail::addDisturbances(s, truth_, plant_, wind_);
    if (auto kick = faults_.kickContribution()) plant_.addContribution(std::move(kick));
    // Motors at the throttle that holds the initial rotor speed.
    throttle_.fill(plant_.throttleForSteadySpeed(x0_.n_rpm[0]));
    if (closed_) controller_.emplace(vehicle_, s.controller, s.residual);
    if (closed_ && s.land_detector) {
      land_.emplace(s.vehicle.min_rotor_plane_height_m, *s.land_detector, s.controller.rate_hz);
    }
    if (plant_.contact() != nullptr) {
      contact_.emplace();
      airborne_ = !s.start_on_ground;
      ground_idle_ = s.start_on_ground && closed_;
      contact_->touched = s.start_on_ground;
    }
    perturbed_start_ = !s.estimator_start.position_error_m.isZero(0.0) ||
                       !s.estimator_start.velocity_error_mps.isZero(0.0) ||
                       !s.estimator_start.attitude_error_rad.isZero(0.0);
    metrics_.add(&tracking_);
    metrics_.add(&bins_);
    metrics_.add(&estimation_);
  }

  FlightResult run(FlightObserver* observer) {
    const double t_end = s_.start_hover_s + duration_ + s_.settle_s;
    const auto last_step = static_cast<long>(std::ceil(t_end * s_.plant_rate_hz - 1e-9));
    const auto wall_start = std::chrono::steady_clock::now();
    for (long k = 0;; ++k) {
      const double t = static_cast<double>(k) * dt_;
      sense(t);
      if (k % decimation_ == 0) {
        controlTick(t);
        metrics_.onTick(tick_);
        if (observer != nullptr) observer->onTick(tick_);
      }
      if (k >= last_step) break;
      // 5. Plant step with the held throttles.
      if (faults_.empty()) {
        if (wind_) plant_.setWind_W(wind_->advance(dt_));
      } else {
        const Eigen::Vector3d base = wind_ ? wind_->advance(dt_) : Eigen::Vector3d::Zero();
        plant_.setWind_W(base + faults_.windAt(t));
        faults_.applyToMotors(t, plant_);
      }
      const sim::StepResult step = plant_.step(throttle_);
      if (contact_) observeContact();
      if (step.crash) {
        result_.crash = step.crash;
        break;
      }
    }
    const auto wall_end = std::chrono::steady_clock::now();
    finish(std::chrono::duration<double>(wall_end - wall_start).count());
    if (observer != nullptr) observer->finish(result_);
    return result_;
  }

 private:
  [[nodiscard]] bool inTrajectory(double t) const noexcept {
    const double t_traj = t - s_.start_hover_s;
    return t_traj >= -0.5 * dt_ && t_traj <= duration_ + 0.5 * dt_;
  }

  /// Stages 1–3: sensors at the true state, the estimator, the height from the ranger.
  void sense(double t) noexcept {
    const sim::PlantState& x = plant_.state();
    sim::SensorReadings r = sensors_.step(x, terrain_.get());
    for (std::size_t k = 0; k < beams_.size(); ++k) {
      if (auto b = beams_[k].sample(x, s_.obstacles.get(), terrain_.get())) beam_[k] = *b;
    }
    if (!closed_) return;
    if (!faults_.empty()) faults_.onSensors(t, r);
    // 2. Estimator: the IMU sample first, then the pose delivered now.
    if (r.imu) {
      (void)eskf_->addImu(*r.imu);
      last_imu_t_s_ = r.imu->t_s;
    }
    if (r.mocap) fusePose(*r.mocap);
    if (r.rotors) {
      telemetry_rpm_ = r.rotors->n_rpm;
      have_telemetry_ = true;
    }
    // 3. Height from the ranger, with the attitude estimate.
    if (r.ranger && eskf_->initialised()) {
      ++result_.estimation.ranger_frames;
      const estimation::LatticeHeight lh = lattice_.estimate(*r.ranger, eskf_->state().q_WB);
      if (lh.valid) {
        ++result_.estimation.height_valid_frames;
        height_m_ = lh.height_m;
        rotor_height_offset_m_ = lh.rotor_height_offset_m;
        ground_normal_W_ = lh.normal_W;
        height_t_s_ = r.ranger->t_s;
        have_height_ = true;
        if (inTrajectory(t)) est_h_.add(lh.height_m - heightAbove(*terrain_, x.p_W));
      }
    }
  }

  void fusePose(const model::MocapSample& m) noexcept {
    if (!eskf_->initialised() && perturbed_start_) {
      const EstimatorStart& e = s_.estimator_start;
      estimation::EskfState e0;
      e0.p_W = m.p_W + e.position_error_m;
      e0.v_W = e.velocity_error_mps;
      e0.q_WB = (m.q_WB * model::expMap(e.attitude_error_rad)).normalized();
      eskf_->initialise(e0, last_imu_t_s_);
    } else {
      (void)eskf_->addMocap(m);
    }
  }

  /// Stage 4: the controller on the latest estimate, height and telemetry.
  void controlTick(double t) noexcept {
    const sim::PlantState& x = plant_.state();
    const double t_traj = t - s_.start_hover_s;
    tick_.t_s = x.t_s;
    tick_.t_traj_s = t_traj;
    tick_.in_trajectory = inTrajectory(t);
    tick_.truth = x;
    tick_.true_height_m = heightAbove(*terrain_, x.p_W);
    if (result_.min_obstacle_clearance_m && tick_.in_trajectory) {
      // Each disc's centre and eight points on its rim.
      const Eigen::Matrix3d R = x.q_WB.toRotationMatrix();
      const Eigen::Vector3d ex = truth_.propeller_radius_m * R.col(0);
      const Eigen::Vector3d ey = truth_.propeller_radius_m * R.col(1);
      double& c = *result_.min_obstacle_clearance_m;
      for (const Eigen::Vector3d& r : truth_.rotor_position_B) {
        const Eigen::Vector3d centre = x.p_W + R * r;
        c = std::min(c, s_.obstacles->clearance(centre));
        for (const Eigen::Vector2d& u : rim_unit_) c = std::min(c, s_.obstacles->clearance(centre + u.x() * ex + u.y() * ey));
      }
    }
    control::ControllerInput& in = tick_.input;
    in.t_s = x.t_s;
    in.reference = s_.trajectory->sample(t_traj);
    // The battery's terminal voltage as the flight controller's power module measures it (its
    // noise, ≈ 10 mV, is far below the sag it compensates and is left out). The controller uses
    // it only when the vehicle file gives the throttle curve's voltage dependence.
    in.battery_voltage_V = plant_.motors().voltageV();
    tick_.controller_active = closed_ && eskf_->initialised() && have_telemetry_;
    if (tick_.controller_active) {
      const estimation::EskfOutput eo = eskf_->output();
      tick_.eskf_flags = eo.flags;
      if (tick_.in_trajectory) {
        for (std::size_t b = 0; b < result_.estimation.eskf_flag_ticks.size(); ++b) {
          if ((eo.flags >> b) & 1u) ++result_.estimation.eskf_flag_ticks[b];
        }
      }
      in.estimate = eo.estimate;
      in.gyro_B = eo.gyro_B;
      in.accel_B = eo.accel_B;
      in.height_valid = have_height_ && t - height_t_s_ <= s_.max_height_age_s + 0.5 * dt_;
      in.height_m = height_m_;
      in.rotor_height_offset_m = rotor_height_offset_m_;
      in.ground_normal_W = ground_normal_W_;
      in.ground_shape_valid = in.height_valid;
      in.rotor_speeds_rpm = telemetry_rpm_;
      for (std::size_t k = 0; k < beams_.size(); ++k) {
        in.beams[k] = beam_[k];
        in.beams[k].valid = beam_[k].valid && t - beam_[k].t_s <= s_.max_beam_age_s + 0.5 * dt_;
      }
      // The disturbance observer (paper eq. 6) on exactly the controller's inputs.
      if (ground_idle_ &&
          !control::referenceOnTheGround(in, s_.vehicle.min_rotor_plane_height_m, 0.01)) {
        ground_idle_ = false;  // the climb starts: from here on the controller flies
        observer_.reset();
      }
      tick_.disturbance = observer_.update({in.t_s, in.gyro_B, in.accel_B, in.rotor_speeds_rpm,
                                            in.estimate.q_WB});
      in.external_accel_W = tick_.disturbance.a_ext_W;
      in.external_accel_valid = tick_.disturbance.valid;
      if (ground_idle_) {
        // A take-off before its reference leaves the ground: armed, motors idling, the controller
        // not yet flying (it would read the idle as failing motors and the ground's support as a
        // disturbance). The observer starts afresh when the climb does.
        tick_.output = control::ControllerOutput{};
        throttle_.fill(0.0);
        tick_.output.throttle = throttle_;
      } else if (land_ && land_->landed()) {
        // Down: the flight controller disarms; the controller no longer runs (its motor monitor
        // would read the spool-down as failing motors) and the last throttles fall to zero.
        tick_.output = control::ControllerOutput{};
        const double scale = land_->update(in);
        for (std::size_t i = 0; i < 4; ++i) throttle_[i] = landed_throttle_[i] * scale;
        tick_.output.throttle = throttle_;
      } else {
        tick_.output = controller_->update(in);
        throttle_ = tick_.output.throttle;
        if (land_) {
          (void)land_->update(in);  // the verdict acts from the next tick on
          landed_throttle_ = throttle_;
        }

        ++result_.controller_updates;
      }
      tick_.attitude_error_rad = model::angleBetween(x.q_WB, tick_.output.q_des_WB);
    } else {
      tick_.disturbance = estimation::DisturbanceEstimate{};
      tick_.eskf_flags = 0;
      in.external_accel_W.setZero();
      in.external_accel_valid = false;
      tick_.output = control::ControllerOutput{};
      tick_.output.throttle = throttle_;
      tick_.attitude_error_rad = 0.0;
    }
    tick_.throttle = throttle_;
    tick_.fault_bits = faults_.empty() ? 0u : faults_.activeBits(t);
    ++result_.control_ticks;
  }

  /// Touchdown, bounce and lift-off from the truth after each plant step (metrics side).
  void observeContact() noexcept {
    const sim::GroundContact& c = *plant_.contact();
    const sim::PlantState& x = plant_.state();
    GroundContactSummary& g = *contact_;
    const int down = c.touchingFeet();
    if (down > 0) {
      for (const sim::FootContact& f : c.feet()) g.max_compression_m = std::max(g.max_compression_m, f.compression_m);
      const double cos_tilt = std::clamp(x.q_WB.toRotationMatrix()(2, 2), -1.0, 1.0);
      g.max_tilt_on_ground_deg = std::max(g.max_tilt_on_ground_deg, std::acos(cos_tilt) * 180.0 / std::numbers::pi);
      if (airborne_ && !std::isnan(g.liftoff_t_s)) ++g.recontacts;
      if (airborne_ && !s_.start_on_ground && std::isnan(g.touchdown_t_s)) {
        g.touchdown_t_s = x.t_s;
        g.touchdown_speed_mps = -x.v_W.z();
      }
      g.touched = true;
      airborne_ = false;
    } else {
      if (!airborne_ && s_.start_on_ground && std::isnan(g.liftoff_t_s)) g.liftoff_t_s = x.t_s;
      airborne_ = true;
      if (!std::isnan(g.touchdown_t_s)) {
        // The lowest foot's clearance above the surface under it.
        const Eigen::Matrix3d R = x.q_WB.toRotationMatrix();
        double clearance = std::numeric_limits<double>::infinity();
        for (const Eigen::Vector3d& f : truth_.landing_feet_B) {
          const Eigen::Vector3d p = x.p_W + R * f;
          clearance = std::min(clearance, p.z() - terrain_->heightAt(p.x(), p.y()));
        }
        g.bounce_m = std::max(g.bounce_m, clearance);
      }
    }
    g.feet_down_at_end = down;
  }

  void finish(double wall_s) {
    tracking_.writeTo(result_);
    bins_.writeTo(result_);
    estimation_.writeTo(result_);
    if (result_.crash) result_.crash_description = sim::describe(*result_.crash);
    result_.completed = !result_.crash.has_value();
    result_.throttle_faults = plant_.throttleFaults();
    if (closed_ && s_.controller.clearance_guard) {
      static_assert(control::kFlagClearanceGuard == (1u << 7));
      result_.guard_active_s = static_cast<double>(result_.flag_counts[7]) / s_.controller.rate_hz;
    }
    if (controller_ && controller_->learner() != nullptr) {
      const control::GroundEffectLearner& l = *controller_->learner();
      LearnedGroundEffect g;
      for (std::size_t k = 0; k < l.knots(); ++k) {
        g.heights_m.push_back(l.knot_m(k));
        g.f_g.push_back(l.value(k));
        g.learned.push_back(l.learned(k));
      }
      g.offset = l.offset();
      g.samples = l.used();
      if (const control::LevelingLearner* ll = controller_->levelingLearner(); ll != nullptr) {
        g.leveling_scale = ll->scale();
        g.leveling_learned = ll->learned();
        g.leveling_samples = ll->used();
      }
      result_.learned_ground_effect = std::move(g);
    }
    if (contact_) {
      if (land_) {
        contact_->landed = land_->landed();
        // The detector's clock is the controller's input time, the plant's.
        contact_->landed_t_s = land_->landedAt();
      }
      result_.ground_contact = *contact_;
    }
    result_.estimation.eskf = eskf_->counters();
    result_.estimation.height_rmse_m = est_h_.value();
    result_.simulated_s = plant_.state().t_s;
    result_.wall_s = wall_s;
    result_.real_time_factor = result_.wall_s > 0.0 ? result_.simulated_s / result_.wall_s : 0.0;
  }

  const FlightScenario& s_;
  // The truth side.
  const model::VehicleModel vehicle_;
  const std::shared_ptr<const sim::Terrain> terrain_;
  const double duration_;
  const double dt_;
  const long decimation_;
  const bool closed_;
  const sim::TruthParams truth_;
  const sim::PlantState x0_;
  sim::Plant plant_;
  std::optional<sim::Wind> wind_;
  sim::SensorSuite sensors_;
  std::vector<sim::BeamRanger> beams_;  // up and sideways (scenario.beam_rangers)
  const std::vector<Eigen::Vector2d> rim_unit_ = sim::rimUnitCircle(8);  // disc clearance samples
  std::array<model::BeamReading, control::ControllerInput::kMaxBeams> beam_{};  // their latest
  // The controller side: built from the nominal vehicle and sensor data only.
  std::unique_ptr<estimation::Eskf> eskf_;
  const estimation::LatticeHeightEstimator lattice_;
  estimation::DisturbanceObserver observer_;  // paper eq. 6, on the controller's inputs
  std::optional<control::Controller> controller_;
  std::optional<control::LandDetector> land_;  // scenario.land_detector
  std::array<double, 4> landed_throttle_{};     // the throttles when it found the vehicle down
  bool ground_idle_ = false;  // a take-off before its reference leaves the ground: motors idle
  std::optional<GroundContactSummary> contact_;  // with ground contact: touchdown, bounce (truth)
  bool airborne_ = true;
  bool perturbed_start_ = false;
  std::array<double, 4> throttle_{};
  // Metrics (they, and only they besides the caller's observer, read the truth).
  TrackingObserver tracking_;
  AngleErrorBinsObserver bins_;
  EstimationObserver estimation_;
  ObserverList metrics_;
  StreamingRms est_h_;
  FaultInjector faults_;  // scenario.faults: between the truth and the controller side
  // Latest sensor-derived values the controller flies on.
  Eigen::Vector4d telemetry_rpm_;
  bool have_telemetry_ = false;
  double height_m_ = 0.0;
  std::array<double, 4> rotor_height_offset_m_{};  // the last valid frame's, LatticeHeight [m]
  Eigen::Vector3d ground_normal_W_ = Eigen::Vector3d::UnitZ();
  double height_t_s_ = -1.0;
  bool have_height_ = false;
  double last_imu_t_s_ = 0.0;
  FlightTick tick_;
  FlightResult result_;
};

}  // namespace

double LearnedGroundEffect::ratio(double h_m) const noexcept {
  if (heights_m.size() < 2 || f_g.size() != heights_m.size()) return std::nan("");
  return control::knotCurve(heights_m.data(), f_g.data(), heights_m.size(), h_m);
}

FlightResult runFlight(const FlightScenario& s, FlightObserver* observer) {
  if (auto problems = validate(s); !problems.empty()) throw InvalidScenario(std::move(problems));
  FlightLoop loop(s);
  return loop.run(observer);
}

}  // namespace geaware::experiments
