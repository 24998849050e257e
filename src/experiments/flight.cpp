// The closed-loop flight runner: see flight.hpp for the order of the stages and
// docs/closed-loop.md for the choices made here.
#include "geaware/experiments/flight.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

#include "geaware/flatness/flat_map.hpp"
#include "geaware/model/rotation.hpp"
#include "geaware/model/units.hpp"
#include "geaware/model/vehicle_model.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/terrains.hpp"

namespace geaware::experiments {
namespace {

constexpr double kRadToDeg = 1.0 / model::kDegToRad;

std::string show(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string describe(const std::vector<ScenarioProblem>& problems) {
  std::string s = "invalid flight scenario:";
  for (const auto& p : problems)
    s += "\n  " + p.field + " = " + p.value + ": expected " + p.expected;
  return s;
}

void append(std::vector<ScenarioProblem>& out, std::vector<model::FieldError> errors,
            const std::string& prefix) {
  for (auto& e : errors) {
    e.field = prefix + e.field;
    out.push_back(std::move(e));
  }
}

bool finiteNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

void nonNegative(std::vector<ScenarioProblem>& out, const std::string& field, double v) {
  if (!finiteNonNegative(v)) out.push_back({field, show(v), "a finite number >= 0"});
}

void positive(std::vector<ScenarioProblem>& out, const std::string& field, double v) {
  if (!(std::isfinite(v) && v > 0.0)) out.push_back({field, show(v), "a finite number > 0"});
}

void finite3(std::vector<ScenarioProblem>& out, const std::string& field,
             const Eigen::Vector3d& v) {
  if (!v.allFinite()) {
    out.push_back(
        {field, "(" + show(v.x()) + ", " + show(v.y()) + ", " + show(v.z()) + ")", "finite"});
  }
}

/// Plant steps per control tick, or 0 when the plant rate is not a multiple of the control rate.
long decimationOf(double plant_rate_hz, double control_rate_hz) {
  if (!(std::isfinite(plant_rate_hz) && plant_rate_hz > 0.0 && std::isfinite(control_rate_hz) &&
        control_rate_hz > 0.0)) {
    return 0;
  }
  const double ratio = plant_rate_hz / control_rate_hz;
  const double n = std::round(ratio);
  if (n < 1.0 || std::abs(ratio - n) > 1e-9 * ratio) return 0;
  return static_cast<long>(n);
}

std::shared_ptr<const sim::Terrain> terrainOf(const FlightScenario& s) {
  return s.terrain ? s.terrain : std::make_shared<sim::FlatGround>(0.0);
}

/// Vertical distance from the rotor-plane centre to the terrain under it [m].
double heightAbove(const sim::Terrain& terrain, const Eigen::Vector3d& p_W) noexcept {
  return p_W.z() - terrain.heightAt(p_W.x(), p_W.y());
}

/// The flat map of the nominal vehicle along the trajectory, at the control rate: the rotor
/// speeds it asks for must lie within the throttle curve's range. A reference through the
/// ground is not an error here (the flight will end in a strike, which is a result).
void checkFeasibility(const FlightScenario& s, std::vector<ScenarioProblem>& out) {
  const model::VehicleModel vehicle(s.vehicle);
  const flatness::FlatMap map(vehicle, flatness::GroundEffectTerms::all());
  const auto terrain = terrainOf(s);
  const double duration = s.trajectory->duration();
  const double dt = 1.0 / s.controller.rate_hz;
  const auto steps = static_cast<long>(std::ceil(duration / dt));
  const double n_lo = vehicle.throttleCurve().minSpeedRpm();
  const double n_hi = vehicle.throttleCurve().maxSpeedRpm();
  double worst_hi = 0.0;
  double worst_lo = n_hi;
  double first_t = -1.0;
  Eigen::Vector4d first_n = Eigen::Vector4d::Zero();
  for (long k = 0; k <= steps; ++k) {
    const double t = std::min(static_cast<double>(k) * dt, duration);
    const traj::FlatOutput ref = s.trajectory->sample(t);
    if (!ref.allFinite()) {
      out.push_back({"trajectory", "t = " + show(t) + " s", "finite flat outputs"});
      return;
    }
    const double h = std::max(heightAbove(*terrain, ref.p_W), 0.0);
    const flatness::FlatState st = map.evaluate(ref, h);
    if (!st.ok()) {
      out.push_back({"trajectory", "t = " + show(t) + " s: " + flatness::toString(st.status),
                     "a reference the flat map can invert (positive collective thrust)"});
      return;
    }
    const double hi = st.rotor_speeds_rpm.maxCoeff();
    const double lo = std::sqrt(std::max(st.n_sq_rpm2.minCoeff(), 0.0));
    worst_hi = std::max(worst_hi, hi);
    worst_lo = std::min(worst_lo, lo);
    if (!st.rotor_speeds_feasible && first_t < 0.0) {
      first_t = t;
      first_n = st.rotor_speeds_rpm;
    }
  }
  if (first_t >= 0.0) {
    out.push_back({"trajectory",
                   "rotor speeds beyond the motors from t = " + show(first_t) +
                       " s (n = " + show(first_n(0)) + ", " + show(first_n(1)) + ", " +
                       show(first_n(2)) + ", " + show(first_n(3)) + " rpm; over the flight " +
                       show(worst_lo) + " to " + show(worst_hi) + " rpm)",
                   "rotor speeds of the flat map (nominal vehicle) within the throttle curve's [" +
                       show(n_lo) + ", " + show(n_hi) +
                       "] rpm: fly slower, wider or with less "
                       "acceleration"});
  }
}

/// Rotor speed at which the truth hovers level at its initial pose (with its own ground
/// effect): the thrust is exactly quadratic in a common rotor speed at rest, so one
/// evaluation of the truth aerodynamics at a reference speed gives it.
double truthHoverSpeed(const sim::TruthParams& truth, const sim::Terrain& terrain,
                       const Eigen::Vector3d& p_W, const Eigen::Quaterniond& q_WB) {
  const sim::RotorGeometry geometry = truth.rotorGeometry();
  const sim::RotorAerodynamics aero(geometry, truth.aero);
  const Eigen::Matrix3d R = q_WB.toRotationMatrix();
  const Eigen::Vector3d p_com = p_W + R * truth.cog_offset_B;
  const sim::RotorSurroundings around =
      sim::rotorSurroundings(&terrain, p_com, R, geometry.position_B);
  constexpr double kRef = 1000.0;  // [rpm]
  const sim::RotorAeroOutput out = aero.compute(
      {kRef, kRef, kRef, kRef}, R, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), around);
  const double thrust = out.wrench.force_B.z();
  return kRef * std::sqrt(truth.mass_kg * truth.gravity_mps2 / thrust);
}

/// Streaming RMS.
struct Rms {
  double sum_sq = 0.0;
  std::uint64_t n = 0;
  void add(double e) noexcept {
    if (!std::isfinite(e)) return;
    sum_sq += e * e;
    ++n;
  }
  [[nodiscard]] double value() const noexcept {
    return n ? std::sqrt(sum_sq / static_cast<double>(n)) : 0.0;
  }
};

struct BinAccumulator {
  std::uint64_t n = 0;
  double sum = 0.0;
  double sum_sq = 0.0;
  double max = 0.0;
};

}  // namespace

InvalidScenario::InvalidScenario(std::vector<ScenarioProblem> problems)
    : std::invalid_argument(describe(problems)), problems_(std::move(problems)) {}

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
    default:
      return "?";
  }
}

std::vector<ScenarioProblem> validate(const FlightScenario& s) {
  std::vector<ScenarioProblem> out;
  const auto vehicle_errors = s.vehicle.validate();
  append(out, vehicle_errors, "vehicle.");
  if (s.truth) {
    append(out, s.truth->validate(), "truth.");
  } else if (vehicle_errors.empty()) {
    append(out, sim::fromNominal(s.vehicle).validate(), "truth.");
  }
  if (s.mismatch) {
    const sim::MismatchSpec& m = s.mismatch.value();
    const auto bounded = [&out](const std::string& f, double v, double hi) {
      if (!(std::isfinite(v) && v >= 0.0 && v < hi)) {
        out.push_back({"mismatch." + f, show(v), "a finite number in [0, " + show(hi) + ")"});
      }
    };
    bounded("mass_rel", m.mass_rel, 0.5);
    bounded("inertia_rel", m.inertia_rel, 0.5);
    bounded("cog_offset_m", m.cog_offset_m, 0.05);
    bounded("cog_offset_z_m", m.cog_offset_z_m, 0.05);
    bounded("thrust_spread_rel", m.thrust_spread_rel, 0.5);
  }
  if (!s.trajectory) {
    out.push_back({"trajectory", "none", "a trajectory to fly"});
  } else if (!finiteNonNegative(s.trajectory->duration())) {
    out.push_back({"trajectory", "duration " + show(s.trajectory->duration()) + " s",
                   "a finite duration >= 0"});
  }
  append(out, s.controller.validate(), "controller.");
  if (s.controller.acceleration == control::AccelerationCompensation::kNeural && !s.residual) {
    out.push_back({"residual", "none",
                   "a trained residual-force network for acceleration compensation 'neural' "
                   "(load one with neural::loadWeights)"});
  }
  append(out, s.sensors.validate(), "sensors.");
  append(out, s.eskf.validate(), "eskf.");
  if (std::abs(s.eskf.imu_rate_hz - s.sensors.imu.rate_Hz) > 1e-9 * s.sensors.imu.rate_Hz) {
    out.push_back({"eskf.imu_rate_hz", show(s.eskf.imu_rate_hz),
                   "the IMU's rate, sensors.imu.rate_Hz = " + show(s.sensors.imu.rate_Hz)});
  }
  if (s.lattice) append(out, s.lattice->validate(), "lattice.");
  if (s.disturbances.turbulence) {
    append(out, s.disturbances.turbulence_params.validate(), "disturbances.turbulence.");
  }
  if (s.disturbances.wind) append(out, s.disturbances.wind_params.validate(), "disturbances.wind.");
  positive(out, "plant_rate_hz", s.plant_rate_hz);
  if (std::isfinite(s.plant_rate_hz) && s.plant_rate_hz > 0.0 &&
      decimationOf(s.plant_rate_hz, s.controller.rate_hz) == 0) {
    out.push_back({"plant_rate_hz", show(s.plant_rate_hz),
                   "an integer multiple of controller.rate_hz = " + show(s.controller.rate_hz)});
  }
  nonNegative(out, "start_hover_s", s.start_hover_s);
  nonNegative(out, "settle_s", s.settle_s);
  positive(out, "max_height_age_s", s.max_height_age_s);
  positive(out, "hover_bins.bin_width_m", s.hover_bins.bin_width_m);
  positive(out, "hover_bins.max_height_m", s.hover_bins.max_height_m);
  if (std::isfinite(s.hover_bins.bin_width_m) && s.hover_bins.bin_width_m > 0.0 &&
      std::isfinite(s.hover_bins.max_height_m) &&
      s.hover_bins.max_height_m / s.hover_bins.bin_width_m > 100000.0) {
    out.push_back({"hover_bins.bin_width_m", show(s.hover_bins.bin_width_m),
                   "at most 100000 bins up to max_height_m"});
  }
  finite3(out, "estimator_start.position_error_m", s.estimator_start.position_error_m);
  finite3(out, "estimator_start.velocity_error_mps", s.estimator_start.velocity_error_mps);
  finite3(out, "estimator_start.attitude_error_rad", s.estimator_start.attitude_error_rad);
  if (out.empty() && s.check_feasibility) checkFeasibility(s, out);
  return out;
}

FlightResult runFlight(const FlightScenario& s, FlightObserver* observer) {
  if (auto problems = validate(s); !problems.empty()) throw InvalidScenario(std::move(problems));

  // ---- Set-up (everything allocated here, nothing in the loop) ------------------------------
  const model::VehicleModel vehicle(s.vehicle);
  sim::TruthParams truth = s.truth ? *s.truth : sim::fromNominal(s.vehicle);
  if (s.mismatch) truth = sim::perturbed(truth, *s.mismatch, s.seed);
  const std::shared_ptr<const sim::Terrain> terrain = terrainOf(s);
  const traj::Trajectory& trajectory = *s.trajectory;
  const double duration = trajectory.duration();
  const double dt = 1.0 / s.plant_rate_hz;
  const long decimation = decimationOf(s.plant_rate_hz, s.controller.rate_hz);
  const bool closed = s.loop == LoopMode::kClosed;

  // Initial condition: hovering level (at the reference's yaw) at the first point, rotors at
  // the speed that carries the truth there, motors at the throttle that holds that speed.
  const traj::FlatOutput first = trajectory.sample(0.0);
  sim::PlantState x0;
  x0.p_W = first.p_W;
  x0.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(first.yaw_rad, Eigen::Vector3d::UnitZ()));
  const double n0 = truthHoverSpeed(truth, *terrain, x0.p_W, x0.q_WB);
  x0.n_rpm = {n0, n0, n0, n0};
  sim::PlantConfig plant_config = s.plant;
  plant_config.step_s = dt;
  sim::Plant plant(truth, terrain, plant_config, x0);
  if (s.disturbances.turbulence) {
    plant.addContribution(
        std::make_unique<sim::GroundTurbulence>(s.disturbances.turbulence_params, s.seed));
  }
  std::optional<sim::Wind> wind;
  if (s.disturbances.wind) wind.emplace(s.disturbances.wind_params, s.seed);
  const double hover_throttle = plant.throttleForSteadySpeed(n0);
  std::array<double, 4> throttle{hover_throttle, hover_throttle, hover_throttle, hover_throttle};

  sim::SensorSuite sensors(s.sensors, s.seed);
  // The controller side: built from the nominal vehicle and sensor data only.
  const auto eskf = std::make_unique<estimation::Eskf>(s.eskf);  // ≈ 125 kB: on the heap
  const estimation::LatticeHeightEstimator lattice(
      s.lattice.value_or(estimation::LatticeHeightParams::forVehicle(s.vehicle)));
  std::optional<control::Controller> controller;
  if (closed) controller.emplace(vehicle, s.controller, s.residual);
  const bool perturbed_start = !s.estimator_start.position_error_m.isZero(0.0) ||
                               !s.estimator_start.velocity_error_mps.isZero(0.0) ||
                               !s.estimator_start.attitude_error_rad.isZero(0.0);

  // Metrics.
  TrackingAccumulator tracking;
  const auto bins = static_cast<std::size_t>(
      std::ceil(s.hover_bins.max_height_m / s.hover_bins.bin_width_m - 1e-9));
  std::vector<BinAccumulator> bin_acc(bins);
  Rms est_p;
  Rms est_v;
  Rms est_q;
  Rms est_h;
  FlightResult result;

  // Latest sensor-derived values the controller flies on.
  Eigen::Vector4d telemetry_rpm = Eigen::Vector4d::Constant(n0);  // replaced by the first sample
  bool have_telemetry = false;
  double height_m = 0.0;
  double height_t_s = -1.0;
  bool have_height = false;
  double last_imu_t_s = 0.0;

  const double t_end = s.start_hover_s + duration + s.settle_s;
  const auto last_step = static_cast<long>(std::ceil(t_end * s.plant_rate_hz - 1e-9));
  const double tick_tolerance_s = 0.5 * dt;
  FlightTick tick;

  // ---- The loop ------------------------------------------------------------------------------
  const auto wall_start = std::chrono::steady_clock::now();
  for (long k = 0;; ++k) {
    const sim::PlantState& x = plant.state();
    const double t = static_cast<double>(k) * dt;

    // 1. Sensors at the true state.
    const sim::SensorReadings r = sensors.step(x, terrain.get());
    if (closed) {
      // 2. Estimator: the IMU sample first, then the pose delivered now.
      if (r.imu) {
        (void)eskf->addImu(*r.imu);
        last_imu_t_s = r.imu->t_s;
      }
      if (r.mocap) {
        if (!eskf->initialised() && perturbed_start) {
          estimation::EskfState e0;
          e0.p_W = r.mocap->p_W + s.estimator_start.position_error_m;
          e0.v_W = s.estimator_start.velocity_error_mps;
          e0.q_WB =
              (r.mocap->q_WB * model::expMap(s.estimator_start.attitude_error_rad))
                  .normalized();
          eskf->initialise(e0, last_imu_t_s);
        } else {
          (void)eskf->addMocap(*r.mocap);
        }
      }
      if (r.rotors) {
        telemetry_rpm = r.rotors->n_rpm;
        have_telemetry = true;
      }
      // 3. Height from the ranger, with the attitude estimate.
      if (r.ranger && eskf->initialised()) {
        ++result.estimation.ranger_frames;
        const estimation::LatticeHeight lh = lattice.estimate(*r.ranger, eskf->state().q_WB);
        if (lh.valid) {
          ++result.estimation.height_valid_frames;
          height_m = lh.height_m;
          height_t_s = r.ranger->t_s;
          have_height = true;
          const double t_traj = t - s.start_hover_s;
          if (t_traj >= -tick_tolerance_s && t_traj <= duration + tick_tolerance_s) {
            est_h.add(lh.height_m - heightAbove(*terrain, x.p_W));
          }
        }
      }
    }

    // 4. Control tick.
    if (k % decimation == 0) {
      const double t_traj = t - s.start_hover_s;
      tick.t_s = x.t_s;
      tick.t_traj_s = t_traj;
      tick.in_trajectory = t_traj >= -tick_tolerance_s && t_traj <= duration + tick_tolerance_s;
      tick.truth = x;
      tick.true_height_m = heightAbove(*terrain, x.p_W);
      control::ControllerInput& in = tick.input;
      in.t_s = x.t_s;
      in.reference = trajectory.sample(t_traj);
      tick.controller_active = closed && eskf->initialised() && have_telemetry;
      if (tick.controller_active) {
        const estimation::EskfOutput eo = eskf->output();
        in.estimate = eo.estimate;
        in.gyro_B = eo.gyro_B;
        in.accel_B = eo.accel_B;
        in.height_valid = have_height && t - height_t_s <= s.max_height_age_s + tick_tolerance_s;
        in.height_m = height_m;
        in.rotor_speeds_rpm = telemetry_rpm;
        tick.output = controller->update(in);
        throttle = tick.output.throttle;
        ++result.controller_updates;
        for (int b = 0; b < kControllerFlagBits; ++b) {
          if ((tick.output.flags >> b) & 1u) ++result.flag_counts[static_cast<std::size_t>(b)];
        }
        tick.attitude_error_rad = model::angleBetween(x.q_WB, tick.output.q_des_WB);
      } else {
        tick.output = control::ControllerOutput{};
        tick.output.throttle = throttle;
        tick.attitude_error_rad = 0.0;
      }
      tick.throttle = throttle;
      ++result.control_ticks;

      if (tick.in_trajectory) {
        tracking.add(in.reference.p_W - x.p_W);
        if (tick.controller_active) {
          est_p.add((in.estimate.p_W - x.p_W).norm());
          est_v.add((in.estimate.v_W - x.v_W).norm());
          est_q.add(model::angleBetween(in.estimate.q_WB, x.q_WB) * kRadToDeg);
          const double h = tick.true_height_m;
          if (h >= 0.0 && h < s.hover_bins.max_height_m) {
            const auto i =
                std::min(static_cast<std::size_t>(h / s.hover_bins.bin_width_m), bins - 1);
            BinAccumulator& b = bin_acc[i];
            const double deg = tick.attitude_error_rad * kRadToDeg;
            ++b.n;
            b.sum += deg;
            b.sum_sq += deg * deg;
            b.max = std::max(b.max, deg);
          }
        }
      }
      if (observer != nullptr) observer->onTick(tick);
    }

    if (k >= last_step) break;
    // 5. Plant step with the held throttles.
    if (wind) plant.setWind_W(wind->advance(dt));
    const sim::StepResult step = plant.step(throttle);
    if (step.crash) {
      result.crash = step.crash;
      break;
    }
  }
  const auto wall_end = std::chrono::steady_clock::now();

  // ---- Results ---------------------------------------------------------------------------------
  result.tracking = tracking.result();
  result.angle_error_by_height.resize(bins);
  for (std::size_t i = 0; i < bins; ++i) {
    AngleErrorBin& b = result.angle_error_by_height[i];
    const BinAccumulator& a = bin_acc[i];
    b.h_low_m = static_cast<double>(i) * s.hover_bins.bin_width_m;
    b.h_high_m =
        std::min(static_cast<double>(i + 1) * s.hover_bins.bin_width_m, s.hover_bins.max_height_m);
    b.samples = a.n;
    if (a.n > 0) {
      const auto n = static_cast<double>(a.n);
      b.mean_deg = a.sum / n;
      b.rms_deg = std::sqrt(a.sum_sq / n);
      b.max_deg = a.max;
    }
  }
  if (result.crash) result.crash_description = sim::describe(*result.crash);
  result.completed = !result.crash.has_value();
  result.throttle_faults = plant.throttleFaults();
  result.estimation.eskf = eskf->counters();
  result.estimation.position_rmse_m = est_p.value();
  result.estimation.velocity_rmse_mps = est_v.value();
  result.estimation.attitude_rmse_deg = est_q.value();
  result.estimation.height_rmse_m = est_h.value();
  result.simulated_s = plant.state().t_s;
  result.wall_s = std::chrono::duration<double>(wall_end - wall_start).count();
  result.real_time_factor = result.wall_s > 0.0 ? result.simulated_s / result.wall_s : 0.0;
  if (observer != nullptr) observer->finish(result);
  return result;
}

}  // namespace geaware::experiments
