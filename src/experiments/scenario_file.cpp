// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/scenario_file.hpp"

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <utility>

#include <Eigen/Geometry>

#include "geaware/io/input_file.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "geaware/io/format_version.hpp"
#include "geaware/experiments/flight_setup.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/height_map_file.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/io/yaml_reader.hpp"
#include "geaware/model/units.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware/traj/hover_descent.hpp"
#include "geaware/traj/touchdown.hpp"
#include "geaware/traj/lemniscate.hpp"
#include "geaware/traj/min_snap.hpp"

namespace geaware::experiments {
namespace {

/// `p` as written, or relative to the scenario file's folder.
std::filesystem::path resolve(const std::filesystem::path& base, const std::string& p) {
  const std::filesystem::path path(p);
  return path.is_absolute() ? path : base / path;
}

Eigen::Vector2d vec2(const std::vector<double>& v) { return {v[0], v[1]}; }
Eigen::Vector3d vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

/// `n` finite numbers at `key` (no value of a scenario may be NaN or infinite: a NaN wind flew
/// like no wind); a missing, short or non-finite list is a problem there, NaN-padded to `n`.
std::vector<double> fixedFinite(io::MapReader& m, const std::string& key, std::size_t n) {
  const auto before = m.problemCount();
  std::vector<double> v = m.finiteNumbers(key);
  if (m.problemCount() == before && v.size() != n) {
    m.problem(key, "expected a list of " + std::to_string(n) + " numbers, got " + std::to_string(v.size()));
  }
  v.resize(n, std::nan(""));
  return v;
}

/// Runs a constructor that validates and throws std::invalid_argument; its message becomes a
/// problem at the section's key. Skipped when the file already has problems (a missing or
/// malformed value would only be reported a second time, less clearly).
template <typename Make>
auto buildOrReport(io::MapReader& section, const std::string& key, Make make) -> decltype(make()) {
  if (section.problemCount() > 0) return nullptr;
  try {
    return make();
  } catch (const std::exception& e) {
    section.problem(key, e.what());
    return nullptr;
  }
}

/// The minimum-snap segments take max(length / average_speed_mps, 0.5 s) (the floor of
/// traj::MinSnapTrajectory::fromAverageSpeed): a speed that would make a segment shorter than
/// the floor was flown slower than asked, silently (issue 16). It is a problem at the key.
void checkSegmentTimes(io::MapReader& t, const std::vector<traj::Waypoint>& wps, double speed_mps) {
  constexpr double kMinSegmentS = 0.5;
  if (!(std::isfinite(speed_mps) && speed_mps > 0.0)) return;  // the trajectory reports it
  for (std::size_t i = 0; i + 1 < wps.size(); ++i) {
    const double length_m = (wps[i + 1].p_W - wps[i].p_W).norm();
    if (length_m > 0.0 && length_m / speed_mps < kMinSegmentS) {
      std::ostringstream os;
      os << "got " << speed_mps << " m/s, expected at most " << length_m / kMinSegmentS << " m/s: segment "
         << i + 1 << " (" << length_m << " m) would take less than the trajectory's minimum segment time of "
         << kMinSegmentS << " s and be flown slower than asked";
      t.problem("average_speed_mps", os.str());
      return;
    }
  }
}

std::shared_ptr<const traj::Trajectory> readTrajectory(io::MapReader& t) {
  const std::string type =
      t.choice("type", {"lemniscate", "hover_descent", "waypoints", "landing", "takeoff"});
  if (type == "lemniscate") {
    traj::LemniscateParams p;
    p.centre_xy_m = vec2(fixedFinite(t, "centre_xy_m", 2));
    p.half_extent_x_m = t.finiteNumber("half_extent_x_m");
    p.half_extent_y_m = t.finiteNumber("half_extent_y_m");
    p.height_m = t.finiteNumber("height_m");
    p.peak_speed_mps = t.finiteNumber("peak_speed_mps");
    p.laps = static_cast<int>(t.integer("laps", 1, 1000));
    p.ramp_time_s = t.finiteNumber("ramp_time_s");
    p.yaw_rad = t.finiteNumber("yaw_deg") * model::kDegToRad;
    if (t.has("height_swing_m")) p.height_swing_m = t.finiteNumber("height_swing_m");  // optional
    t.rejectUnknownKeys();
    return buildOrReport(t, "type", [&] { return std::make_shared<const traj::Lemniscate>(p); });
  }
  if (type == "hover_descent") {
    traj::HoverDescentParams p;
    p.position_xy_m = vec2(fixedFinite(t, "position_xy_m", 2));
    p.from_height_m = t.finiteNumber("from_height_m");
    p.to_height_m = t.finiteNumber("to_height_m");
    p.descent_rate_mps = t.finiteNumber("descent_rate_mps");
    p.ramp_time_s = t.finiteNumber("ramp_time_s");
    p.hold_start_s = t.finiteNumber("hold_start_s");
    p.hold_end_s = t.finiteNumber("hold_end_s");
    p.yaw_rad = t.finiteNumber("yaw_deg") * model::kDegToRad;
    t.rejectUnknownKeys();
    return buildOrReport(t, "type", [&] { return std::make_shared<const traj::HoverDescent>(p); });
  }
  if (type == "landing") {
    traj::LandingParams p;
    p.position_xy_m = vec2(fixedFinite(t, "position_xy_m", 2));
    p.from_height_m = t.finiteNumber("from_height_m");
    p.touchdown_height_m = t.finiteNumber("touchdown_height_m");
    p.descent_rate_mps = t.finiteNumber("descent_rate_mps");
    p.flare_height_m = t.finiteNumber("flare_height_m");
    p.touchdown_speed_mps = t.finiteNumber("touchdown_speed_mps");
    p.press_depth_m = t.finiteNumber("press_depth_m");
    p.ramp_time_s = t.finiteNumber("ramp_time_s");
    p.hold_start_s = t.finiteNumber("hold_start_s");
    p.hold_end_s = t.finiteNumber("hold_end_s");
    p.yaw_rad = t.finiteNumber("yaw_deg") * model::kDegToRad;
    t.rejectUnknownKeys();
    return buildOrReport(t, "type", [&] { return std::make_shared<const traj::Landing>(p); });
  }
  if (type == "takeoff") {
    traj::TakeOffParams p;
    p.position_xy_m = vec2(fixedFinite(t, "position_xy_m", 2));
    p.touchdown_height_m = t.finiteNumber("touchdown_height_m");
    p.to_height_m = t.finiteNumber("to_height_m");
    p.climb_rate_mps = t.finiteNumber("climb_rate_mps");
    p.ramp_time_s = t.finiteNumber("ramp_time_s");
    p.hold_start_s = t.finiteNumber("hold_start_s");
    p.hold_end_s = t.finiteNumber("hold_end_s");
    p.yaw_rad = t.finiteNumber("yaw_deg") * model::kDegToRad;
    t.rejectUnknownKeys();
    return buildOrReport(t, "type", [&] { return std::make_shared<const traj::TakeOff>(p); });
  }
  if (type == "waypoints") {
    std::vector<traj::Waypoint> wps;
    for (const auto& r : t.finiteRows("points_m", 3)) {
      if (r.size() == 3) wps.push_back({vec3(r), 0.0});  // another length is a problem already
    }
    const double yaw = t.finiteNumber("yaw_deg") * model::kDegToRad;
    for (auto& w : wps) w.yaw_rad = yaw;
    const double speed = t.finiteNumber("average_speed_mps");
    checkSegmentTimes(t, wps, speed);
    t.rejectUnknownKeys();
    return buildOrReport(t, "type", [&] {
      return std::make_shared<const traj::MinSnapTrajectory>(
          traj::MinSnapTrajectory::fromAverageSpeed(wps, speed));
    });
  }
  t.rejectUnknownKeys();
  return nullptr;
}

std::shared_ptr<const sim::Terrain> readTerrain(io::MapReader& t, const std::filesystem::path& base) {
  const std::string type = t.choice("type", {"flat", "tilted", "step", "height_map"});
  std::shared_ptr<const sim::Terrain> out;
  if (type == "flat") {
    const double z = t.finiteNumber("height_m");
    out = std::make_shared<const sim::FlatGround>(z);
  } else if (type == "tilted") {
    const Eigen::Vector3d point = vec3(fixedFinite(t, "point_m", 3));
    const double roll = t.finiteNumber("roll_deg") * model::kDegToRad;
    const double pitch = t.finiteNumber("pitch_deg") * model::kDegToRad;
    out = buildOrReport(t, "type", [&] {
      return std::make_shared<const sim::TiltedPlane>(sim::TiltedPlane::fromTilt(point, roll, pitch));
    });
  } else if (type == "step") {
    const Eigen::Vector2d edge = vec2(fixedFinite(t, "edge_point_xy_m", 2));
    const Eigen::Vector2d towards = vec2(fixedFinite(t, "towards_high_xy", 2));
    const double low = t.finiteNumber("low_m");
    const double high = t.finiteNumber("high_m");
    out = buildOrReport(t, "type", [&] { return std::make_shared<const sim::StepTerrain>(edge, towards, low, high); });
  } else if (type == "height_map") {
    const std::string file = t.text("file");
    if (!file.empty()) {
      const std::filesystem::path path = resolve(base, file);
      // A height-map problem names its own file and line (io::HeightMapFileError); it is
      // reported here under the key that named the file.
      out = buildOrReport(t, "file", [&] { return std::make_shared<const sim::HeightMap>(io::readHeightMapFile(path.string())); });
    }
  }
  t.rejectUnknownKeys();
  return out;
}

/// `obstacles:` a list of boxes (docs/scenario-file.md): type box, name, min_m, max_m (world
/// corners before the rotation), optional yaw_deg, pitch_deg, roll_deg about the box's centre
/// (R = R_z(yaw)·R_y(pitch)·R_x(roll), as the vehicle's attitude).
std::shared_ptr<const sim::Obstacles> readObstacles(io::MapReader& root) {
  std::vector<sim::Box> boxes;
  for (io::MapReader& o : root.maps("obstacles")) {
    (void)o.choice("type", {"box"});
    const std::string name = o.text("name");
    const Eigen::Vector3d lo = vec3(fixedFinite(o, "min_m", 3));
    const Eigen::Vector3d hi = vec3(fixedFinite(o, "max_m", 3));
    const auto angle = [&o](const char* key) { return o.has(key) ? o.finiteNumber(key) * model::kDegToRad : 0.0; };
    const double yaw = angle("yaw_deg");
    const double pitch = angle("pitch_deg");
    const double roll = angle("roll_deg");
    if (lo.allFinite() && hi.allFinite() && !(hi.array() > lo.array()).all()) {
      o.problem("max_m", "greater than min_m on every axis (a box of positive size)");
    } else if (lo.allFinite() && hi.allFinite() && !(hi - lo).allFinite()) {
      o.problem("max_m", "a box whose size is a finite number of metres");
    }
    o.rejectUnknownKeys();
    if (o.problemCount() == 0) {
      sim::Box b = sim::boxFromCorners(lo, hi, 0.0, name);
      b.R_WO = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
      boxes.push_back(std::move(b));
    }
  }
  if (root.problemCount() > 0 || boxes.empty()) return nullptr;
  return std::make_shared<const sim::Obstacles>(std::move(boxes));
}

/// `beam_rangers:` a list of single-beam rangers: direction_B (unit, body), mount_B_m, and
/// optionally rate_Hz, max_range_m, noise_floor_m, noise_fraction, outlier_probability.
std::vector<sim::BeamRangerParams> readBeamRangers(io::MapReader& root) {
  std::vector<sim::BeamRangerParams> out;
  for (io::MapReader& b : root.maps("beam_rangers")) {
    sim::BeamRangerParams p;
    p.direction_B = vec3(fixedFinite(b, "direction_B", 3));
    if (p.direction_B.allFinite() && p.direction_B.norm() > 0.0) p.direction_B.normalize();
    p.mount_B = vec3(fixedFinite(b, "mount_B_m", 3));
    if (b.has("rate_Hz")) p.rate_Hz = b.finiteNumber("rate_Hz");
    if (b.has("max_range_m")) p.max_range_m = b.finiteNumber("max_range_m");
    if (b.has("noise_floor_m")) p.noise_floor_m = b.finiteNumber("noise_floor_m");
    if (b.has("noise_fraction")) p.noise_fraction = b.finiteNumber("noise_fraction");
    if (b.has("outlier_probability")) p.outlier_probability = b.finiteNumber("outlier_probability");
    b.rejectUnknownKeys();
    out.push_back(p);
  }
  return out;
}

}  // namespace

FlightScenario parseScenarioYaml(std::string_view yaml_text, const std::string& source,
                                 const std::filesystem::path& base_dir,
                                 const sim::World* truth_override, std::optional<double> max_sim_s_override) {
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw io::ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  if (!doc.IsMap()) throw io::ConfigError(source, {{1, "", "expected a map (a flight scenario) at the top level"}});

  io::YamlContext ctx;
  io::MapReader root(doc, "", ctx);
  (void)io::readFormatVersion(root, ctx, source);
  FlightScenario s;

  const std::string vehicle = root.text("vehicle");
  if (vehicle == "builtin") {
    s.vehicle = io::builtinVehicle();
  } else if (!vehicle.empty()) {
    const std::filesystem::path path = resolve(base_dir, vehicle);
    try {
      s.vehicle = io::loadVehicleFile(path);
    } catch (const std::exception& e) {
      root.problem("vehicle", std::string("cannot use the vehicle file: ") + e.what());
    }
  }
  s.seed = static_cast<std::uint64_t>(root.integer("seed", 0, 1'000'000'000));

  auto traj_section = root.map("trajectory");
  s.trajectory = readTrajectory(traj_section);

  if (root.isScalar("controller")) {
    // A configuration by name (docs/controller.md), as --controller takes it, in place of the
    // two switches: "recommended", "model:model_indi+rotors", "recommended+learn0", …
    const std::string name = root.text("controller");
    if (!control::parseConfiguration(name, s.controller)) {
      root.problem("controller", "got '" + name +
                                     "', expected 'recommended' or ACC:TORQUE, optionally followed "
                                     "by +proximity (not after recommended, which has it), +rotors "
                                     "and +learn or +learn0, or a map with acceleration and torque");
    }
  } else {
    auto ctrl = root.map("controller");
    const std::string acc = ctrl.choice("acceleration", {"none", "indi", "neural", "model"});
    const std::string torque = ctrl.choice("torque", {"none", "model", "indi", "model_indi"});
    if (!acc.empty()) (void)control::parse(acc, s.controller.acceleration);
    if (!torque.empty()) (void)control::parse(torque, s.controller.torque);
    ctrl.rejectUnknownKeys();
  }
  if (root.has("controller_params")) {
    // The gains, rate, limits and additions' settings (docs/controller-params.md), applied to
    // the configuration above.
    const std::string file = root.text("controller_params");
    if (!file.empty()) {
      try {
        s.controller = io::withControllerParamsFile(s.controller, resolve(base_dir, file));
      } catch (const std::exception& e) {
        root.problem("controller_params", std::string("cannot use the controller-parameters file: ") + e.what());
      }
    }
  }

  auto terrain = root.map("terrain");
  s.terrain = readTerrain(terrain, base_dir);
  if (root.has("obstacles")) s.obstacles = readObstacles(root);
  if (root.has("beam_rangers")) s.beam_rangers = readBeamRangers(root);

  // The world: the scenario's `truth` (a built-in name or a truth file), unless the caller
  // overrides it (`fly --truth`); none named: the default world (experiments/world_setup.hpp).
  std::optional<sim::World> world;
  if (root.has("truth")) {
    const std::string truth = root.text("truth");
    if (truth_override == nullptr && !truth.empty()) {
      try {
        world = io::resolveTruth(truth, base_dir);
      } catch (const std::exception& e) {
        root.problem("truth", std::string("cannot use the truth: ") + e.what());
      }
    }
  }
  if (truth_override != nullptr) world = *truth_override;
  if (!world && root.problemCount() == 0) {
    world = defaultWorld(s.vehicle, vehicle == "builtin", vehicle);
  }
  if (world) applyWorld(s, *world);

  // This flight's disturbances, replacing the world's (optional).
  if (root.has("disturbances")) {
    auto dist = root.map("disturbances");
    s.disturbances.turbulence = dist.boolean("turbulence");
    s.disturbances.wind_params.mean_W_mps = vec3(fixedFinite(dist, "wind_mps", 3));
    s.disturbances.wind_params.gust_std_mps = vec3(fixedFinite(dist, "gust_std_mps", 3));
    s.disturbances.wind = s.disturbances.wind_params.mean_W_mps.norm() > 0.0 ||
                          s.disturbances.wind_params.gust_std_mps.norm() > 0.0;
    dist.rejectUnknownKeys();
  }

  if (root.has("max_sim_s")) s.max_sim_s = root.finiteNumber("max_sim_s");
  if (max_sim_s_override) s.max_sim_s = *max_sim_s_override;

  // The per-flight variation is the world's now: one way to describe a world.
  if (root.has("truth_mismatch")) {
    (void)root.map("truth_mismatch");
    root.problem("truth_mismatch",
                 "moved into the truth file: give 'truth:' a truth file whose section "
                 "'truth.per_flight_variation' holds these bounds (docs/truth-file.md)");
  }
  root.rejectUnknownKeys();
  if (!ctx.problems.empty()) throw io::ConfigError(source, std::move(ctx.problems));
  applyTouchdown(s);  // a landing or take-off: ground contact, the land detector, no guard

  // Whole-scenario checks (ranges, the wind's and mismatch's own validation), each at its key.
  // The residual network of acceleration "neural" is not part of the file (the caller loads it,
  // e.g. `fly --neural-weights`), so it is not required here; runFlight checks it.
  for (const auto& e : validate(s, ScenarioStage::kFile)) {
    ctx.problem(ctx.lineOf(e.field), e.field, "got " + e.value + ", expected " + e.expected);
  }
  if (!ctx.problems.empty()) throw io::ConfigError(source, std::move(ctx.problems));
  return s;
}

FlightScenario loadScenarioFile(const std::filesystem::path& file, const sim::World* truth_override,
                                std::optional<double> max_sim_s_override) {
  return parseScenarioYaml(io::readInputFile(file, "scenario file", "scenario YAML file"),
                           file.string(), file.parent_path(), truth_override, max_sim_s_override);
}

}  // namespace geaware::experiments
