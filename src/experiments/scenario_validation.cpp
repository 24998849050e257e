// SPDX-License-Identifier: BSD-3-Clause
// Validation of a flight scenario before it is flown: every stage's parameters, the rates, and
// the trajectory's feasibility for the nominal vehicle (flight.hpp, validate()).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "flight_internal.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/flatness/flat_map.hpp"
#include "geaware/model/field_check.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/vehicle_model.hpp"
#include "geaware/traj/touchdown.hpp"

namespace geaware::experiments {
namespace {

/// The touchdown height of a landing or take-off reference; null for other trajectories.
const double* touchdownHeightOf(const traj::Trajectory* t) {
  if (const auto* l = dynamic_cast<const traj::Landing*>(t)) return &l->params().touchdown_height_m;
  if (const auto* o = dynamic_cast<const traj::TakeOff*>(t)) return &o->params().touchdown_height_m;
  return nullptr;
}

using detail::decimationOf;
using detail::heightAbove;
using detail::terrainOf;

std::string show(double v) { return model::formatValue(v); }

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

}  // namespace

InvalidScenario::InvalidScenario(std::vector<ScenarioProblem> problems)
    : std::invalid_argument(model::describeErrors("invalid flight scenario:", problems)), problems_(std::move(problems)) {}

/// False (with a problem) when the flight would simulate longer than max_sim_s: the feasibility
/// check samples every control tick, so it must not start then.
bool durationBounded(const FlightScenario& s, std::vector<ScenarioProblem>& out) {
  positive(out, "max_sim_s", s.max_sim_s);
  if (s.trajectory == nullptr || !std::isfinite(s.max_sim_s)) return false;
  const double trajectory_s = s.trajectory->duration();
  const double sim_s = s.start_hover_s + trajectory_s + s.settle_s;
  if (sim_s <= s.max_sim_s) return true;
  out.push_back({"trajectory",
                 "a flight of " + show(sim_s) + " s (start hover " + show(s.start_hover_s) + " s + trajectory " +
                     show(trajectory_s) + " s + settling " + show(s.settle_s) + " s)",
                 "at most max_sim_s = " + show(s.max_sim_s) + " s (fly --max-sim-s, scenario or sweep key max_sim_s)"});
  return false;
}

std::vector<ScenarioProblem> validate(const FlightScenario& s, ScenarioStage stage) {
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
  if (stage == ScenarioStage::kFlight &&
      s.controller.acceleration == control::AccelerationCompensation::kNeural && !s.residual) {
    out.push_back({"residual", "none",
                   "a trained residual-force network for acceleration compensation 'neural' "
                   "(load one with neural::loadWeights)"});
  }
  append(out, s.sensors.validate(), "sensors.");
  append(out, s.eskf.validate(), "eskf.");
  append(out, validate(s.faults), "");
  if (s.start_on_ground && !s.plant.ground_contact) {
    out.push_back({"start_on_ground", "true",
                   "plant.ground_contact on (a vehicle standing on its gear needs the contact model)"});
  }
  if (s.plant.ground_contact && (s.start_on_ground || s.land_detector) && vehicle_errors.empty()) {
    const sim::TruthParams truth = s.truth ? *s.truth : sim::fromNominal(s.vehicle);
    if (!truth.landing_gear.enabled() || truth.landing_feet_B.size() < 3) {
      out.push_back({"truth.landing_gear.stiffness_N_per_m", show(truth.landing_gear.stiffness_N_per_m),
                     "a landing gear with stiffness > 0 on at least 3 feet for a landing or take-off (" +
                         std::to_string(truth.landing_feet_B.size()) + " feet)"});
    }
  }
  // A flight that does not stand on its gear starts in the air: level at the reference's first
  // point and yaw, no foot of the world's gear below the surface under it, by the plant's own
  // strike rule (deeper than the leg's compression with ground contact, at all without), or the
  // flight ends in its first millisecond.
  if (!s.start_on_ground && s.trajectory && vehicle_errors.empty()) {
    const traj::FlatOutput first = s.trajectory->sample(0.0);
    const sim::TruthParams truth = s.truth ? *s.truth : sim::fromNominal(s.vehicle);
    if (first.p_W.allFinite() && std::isfinite(first.yaw_rad)) {
      const auto terrain = terrainOf(s);
      const Eigen::Matrix3d R = Eigen::AngleAxisd(first.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const double allowance_m = s.plant.ground_contact ? truth.landing_gear.max_compression_m : 0.0;
      double deepest_m = allowance_m;
      double gear_m = 0.0;  // how far the lowest foot hangs below the rotor plane
      for (const Eigen::Vector3d& f : truth.landing_feet_B) {
        const Eigen::Vector3d p = first.p_W + R * f;
        deepest_m = std::max(deepest_m, terrain->heightAt(p.x(), p.y()) - p.z());
        gear_m = std::max(gear_m, -f.z());
      }
      if (deepest_m > allowance_m) {
        out.push_back({"trajectory",
                       "starts at (" + show(first.p_W.x()) + ", " + show(first.p_W.y()) + ", " +
                           show(first.p_W.z()) + ") m with a landing foot " + show(deepest_m) +
                           " m inside the surface",
                       "a start with every foot of the world's gear (" + show(gear_m) +
                           " m below the rotor plane) on or above the surface: fly higher, or take off"});
      }
    }
  }
  // A landing or take-off reference meets the surface where the vehicle file's gear does.
  if (const double* td = touchdownHeightOf(s.trajectory.get()); td != nullptr && vehicle_errors.empty()) {
    const Eigen::Vector3d last = s.trajectory->sample(s.trajectory->duration()).p_W;
    const auto terrain = detail::terrainOf(s);
    const double surface_m = terrain->heightAt(last.x(), last.y());
    const double expected = surface_m + s.vehicle.min_rotor_plane_height_m;
    if (!(std::abs(*td - expected) <= 0.02)) {
      out.push_back({"trajectory.touchdown_height_m", show(*td),
                     "the surface under the point (" + show(surface_m) + " m) + the vehicle's "
                     "min_rotor_plane_height_m (" + show(s.vehicle.min_rotor_plane_height_m) +
                     " m) = " + show(expected) + " m, within 0.02 m"});
    }
  }
  if (s.land_detector) append(out, s.land_detector->validate(), "land_detector.");
  if (s.beam_rangers.size() > control::ControllerInput::kMaxBeams) {
    out.push_back({"beam_rangers", std::to_string(s.beam_rangers.size()) + " rangers",
                   "at most " + std::to_string(control::ControllerInput::kMaxBeams)});
  }
  for (std::size_t k = 0; k < s.beam_rangers.size(); ++k) {
    append(out, s.beam_rangers[k].validate(), "beam_rangers[" + std::to_string(k) + "].");
  }
  if (!(s.max_beam_age_s > 0.0) || !std::isfinite(s.max_beam_age_s)) {
    out.push_back({"max_beam_age_s", show(s.max_beam_age_s), "a finite age > 0 [s]"});
  }
  if (s.obstacles && s.obstacles->boxes().size() > kMaxObstacles) {
    out.push_back({"obstacles", std::to_string(s.obstacles->boxes().size()) + " boxes",
                   "at most " + std::to_string(kMaxObstacles)});
  } else if (s.obstacles && s.trajectory && finiteNonNegative(s.trajectory->duration()) && vehicle_errors.empty()) {
    // The reference must not lead the vehicle, level at the reference's yaw, into an obstacle:
    // its centre, its rotor centres and 8 points on each rotor's rim, every 10 ms (at most 10⁵
    // samples).
    const double T = s.trajectory->duration();
    const long n = static_cast<long>(std::min(1e5, std::ceil(T * 100.0) + 1.0));
    const auto rotors = model::Mixer::rotorPositions_B(s.vehicle.diagonal_rotor_distance_m);
    const double r_prop = s.vehicle.propeller_radius_m;
    std::vector<Eigen::Vector2d> disc = sim::rimUnitCircle(8);
    disc.emplace_back(0.0, 0.0);  // and the centre
    for (long k = 0; k < n; ++k) {
      const double t = n > 1 ? T * static_cast<double>(k) / static_cast<double>(n - 1) : 0.0;
      const traj::FlatOutput ref = s.trajectory->sample(t);
      const Eigen::Matrix3d yaw = Eigen::AngleAxisd(ref.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      std::optional<std::size_t> box = s.obstacles->containing(ref.p_W);
      for (std::size_t i = 0; i < rotors.size() && !box; ++i) {
        const Eigen::Vector3d c = ref.p_W + yaw * rotors[i];
        for (std::size_t j = 0; j < disc.size() && !box; ++j) {
          box = s.obstacles->containing(c + r_prop * (yaw * Eigen::Vector3d(disc[j].x(), disc[j].y(), 0.0)));
        }
      }
      if (box) {
        const Eigen::Vector3d& p = ref.p_W;
        out.push_back({"trajectory", "at t = " + show(t) + " s, (" + show(p.x()) + ", " + show(p.y()) + ", " +
                                         show(p.z()) + ") m",
                       "a path on which the level vehicle stays outside every obstacle (it enters '" +
                           s.obstacles->boxes()[*box].name + "')"});
        break;
      }
    }
  }
  if (std::abs(s.eskf.imu_rate_hz - s.sensors.imu.rate_Hz) > 1e-9 * s.sensors.imu.rate_Hz) {
    out.push_back({"eskf.imu_rate_hz", show(s.eskf.imu_rate_hz),
                   "the IMU's rate, sensors.imu.rate_Hz = " + show(s.sensors.imu.rate_Hz)});
  }
  if (s.lattice) append(out, s.lattice->validate(), "lattice.");
  if (s.disturbances.turbulence) {
    append(out, s.disturbances.turbulence_params.validate(), "disturbances.turbulence.");
  }
  if (s.disturbances.wind) append(out, s.disturbances.wind_params.validate(), "disturbances.wind.");
  if (s.disturbances.unsteadiness) {
    append(out, s.disturbances.unsteadiness_params.validate(), "disturbances.unsteadiness.");
  }
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
  if (durationBounded(s, out) && out.empty() && s.check_feasibility) checkFeasibility(s, out);
  return out;
}

}  // namespace geaware::experiments
