// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/calibration.hpp"

#include <array>
#include <optional>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "calibration_flights.hpp"
#include "geaware/experiments/rig_runs.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/ident/identify.hpp"
#include "geaware/model/field_check.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/vehicle_schema.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/model/rotor_drag.hpp"
#include "geaware/model/units.hpp"
#include "geaware/sim/sampling.hpp"

namespace geaware::experiments {
namespace {

std::vector<double> grid(double from, double to, double step) {
  std::vector<double> v;
  for (int k = 0; from + k * step <= to + 1e-9; ++k) v.push_back(from + k * step);
  return v;
}

/// Appends the rows of one platform sweep to `log`, with the time running on from the last
/// row (each sweep starts at t = 0; the readers require increasing time, the fits ignore it).
std::size_t appendSweep(const sim::ForceTorquePlatform& rig, const sim::PlatformSweep& sweep,
                        std::uint64_t seed, ident::PlatformLog& log) {
  const double t0 = log.t_s.empty() ? 0.0 : log.t_s.back() + 1.0;
  return rig.sweep(sweep, seed, [&](const sim::PlatformRow& r) {
    log.t_s.push_back(t0 + r.t_s);
    log.h_m.push_back(r.h_m);
    log.tilt_deg.push_back(r.tilt_deg);
    for (std::size_t i = 0; i < 4; ++i) log.n_rpm[i].push_back(r.n_rpm[i]);
    for (int a = 0; a < 3; ++a) {
      log.f_N[static_cast<std::size_t>(a)].push_back(r.force_B[a]);
      log.tau_Nm[static_cast<std::size_t>(a)].push_back(r.torque_B[a]);
    }
  });
}

}  // namespace

CalibrationSweeps CalibrationSweeps::defaults() {
  CalibrationSweeps s;
  // 1. Level board: the round trip's sweep (docs/identification.md), so that its documented
  //    F_G tolerances apply to the campaign's calibration.
  s.level.heights_m = grid(0.07, 1.0, 0.01);
  s.level.tilts_deg = {0.0};
  s.level.rpm = {9000.0, 12000.0, 15000.0};
  // 2. Tilted board at SMALL tilts, 2–10°: J'(h) (eq. 24–26) is the slope of the leveling
  //    torque in sin δ at small tilts, which is where a flying vehicle is; the truth, like the
  //    paper's measurement, stops growing above ≈ 10°, so a 15° board would fit a smaller
  //    slope. Heights from just above the lowest flight height to past the wake-merge collapse.
  s.tilted.heights_m = grid(0.08, 0.40, 0.02);
  s.tilted.tilts_deg = {2.0, 4.0, 6.0, 8.0, 10.0};
  s.tilted.rpm = {9000.0, 12000.0, 15000.0};
  // 3. Mixing: rpm differences on the roll, pitch and yaw rows, out of ground effect.
  s.mixing.heights_m = {1.0, 1.5, 2.0};
  s.mixing.tilts_deg = {0.0};
  s.mixing.rpm = {9000.0, 12000.0, 15000.0};
  s.mixing.rpm_diffs = {-1500.0, -750.0, 0.0, 750.0, 1500.0};
  // 4. Stand: throttle steps over the whole range (speed steps also determine J_R).
  s.stand_throttles = grid(0.0, 1.0, 0.1);
  return s;
}

namespace {

/// The rigs' logs, in memory in the readers' format (no CSV round trip: the readers' checks
/// are for files from the outside; these rows come straight from the simulator).
struct RigLogs {
  ident::PlatformLog platform;
  ident::RotorStandLog stand;
};

/// Step 1: the platform's three sweeps and the stand's throttle steps on the truth.
RigLogs runRigs(const model::VehicleParams& file_vehicle, const sim::TruthParams& truth,
                const CalibrationSweeps& sweeps, ControllerCalibration& c) {
  RigLogs logs;
  const sim::ForceTorquePlatform rig(platformGeometry(truth), truth.aero, sweeps.platform);
  logs.platform.source = "virtual quadrotor platform (campaign calibration)";
  c.platform_rows += appendSweep(rig, sweeps.level, 10 + sweeps.seed, logs.platform);
  c.platform_rows += appendSweep(rig, sweeps.tilted, 20 + sweeps.seed, logs.platform);
  c.platform_rows += appendSweep(rig, sweeps.mixing, 30 + sweeps.seed, logs.platform);

  ident::RotorStandLog& stand_log = logs.stand;
  stand_log.source = "virtual single-rotor stand (campaign calibration)";
  sim::RotorStandParams stand_params = sweeps.stand;
  stand_params.motor_time_constant_s = truth.motor.time_constant_s;  // the world's motor on the stand
  const sim::RotorStand stand(rotorStandVehicle(file_vehicle, truth), stand_params);
  c.stand_rows = stand.sweep(sweeps.stand_throttles, 40 + sweeps.seed,
                             [&](const sim::RotorStandRow& r) {
                               stand_log.t_s.push_back(r.t_s);
                               stand_log.throttle.push_back(r.throttle);
                               stand_log.rpm.push_back(r.rpm);
                               stand_log.thrust_N.push_back(r.thrust_N);
                               stand_log.torque_Nm.push_back(r.torque_Nm);
                             });
  return logs;
}

/// Step 2: the identification of both logs, with the default options (the tilt limit and the
/// curve form aside, see the sweeps), as `geaware identify rotor|platform` does it.
struct Identified {
  ident::IdentifyResult rotor;
  ident::IdentifyResult platform;
};

Identified identifyOnRigs(const RigLogs& logs, const model::VehicleParams& file_vehicle,
                          const CalibrationSweeps& sweeps, ControllerCalibration& c) {
  ident::IdentifyOptions options;
  options.tilt_limit_deg = sweeps.tilt_limit_deg;
  if (sweeps.tables) options.ground_effect = ident::CurveForm::kTable;
  Identified id{ident::identifyRotorStand(logs.stand, options),
                ident::identifyPlatform(logs.platform, file_vehicle, options)};
  const ident::Fits& f = id.platform.fits;
  // The fits' warnings in the order the calibration has always listed them.
  using Warnings = const std::vector<std::string>*;
  const std::initializer_list<Warnings> warnings{
      f.additional_thrust ? &f.additional_thrust->warnings : nullptr,
      f.additional_thrust_table ? &f.additional_thrust_table->warnings : nullptr,
      f.leveling ? &f.leveling->warnings : nullptr,
      f.leveling_table ? &f.leveling_table->warnings : nullptr,
      &id.rotor.fits.rotor->warnings, &f.mixing->warnings};
  for (const Warnings w : warnings) {
    if (w != nullptr) c.warnings.insert(c.warnings.end(), w->begin(), w->end());
  }
  return id;
}

/// Step 3: the merge into the vehicle file's parameters, stand first, then the platform
/// (docs/identification.md, "Commands"), through the parameter schema: every identified key is
/// listed in c.parameters beside the file's value, then model::mergeParameters takes them.
model::VehicleParams mergeIdentified(const model::VehicleParams& file_vehicle, const Identified& id,
                                     ControllerCalibration& c) {
  const auto& schema = model::vehicleSchema();
  model::VehicleParams identified = file_vehicle;
  std::vector<std::string> keys;
  auto take = [&](const std::string& key, const std::string& source, const ident::Estimate& e) {
    const auto* spec = schema.find(key);
    c.parameters.push_back({key, std::string(spec->unit), source, spec->numberOf(file_vehicle), e.value,
                            e.std_error});
    spec->number(identified) = e.value;
    keys.push_back(key);
  };
  // A curve: its formula keys as the platform result gives them, or its table (one row per
  // knot, the file's value being the file's curve at that height).
  const model::GroundEffectModel file_ge(file_vehicle);
  const ident::IdentifyResult& platform = id.platform;
  auto takeCurve = [&](const std::string& section, const std::string& name, const std::string& source) {
    const std::string curve = "ground_effect." + section;
    for (const auto& t : platform.tables) {
      if (t.section != section) continue;
      const auto columns = schema.columns(curve + ".table");  // heights, values
      columns[0]->list(identified) = t.curve.heights_m;
      columns[1]->list(identified).clear();
      for (std::size_t j = 0; j < t.curve.values.size(); ++j) {
        const double h = t.curve.heights_m[j];
        c.parameters.push_back({fmt::format("{}(h = {:.3g} m)", name, h), columns[1]->unit.empty() ? "-" : std::string(columns[1]->unit), source,
                                section == "additional_thrust" ? file_ge.thrustRatio(h) : file_ge.levelingCoefficient(h),
                                t.curve.values[j].value, t.curve.values[j].std_error});
        columns[1]->list(identified).push_back(t.curve.values[j].value);
      }
      keys.push_back(curve + ".table");
      return;
    }
    for (const auto& p : platform.parameters) {
      if (const auto* spec = schema.find(p.name); spec != nullptr && spec->curve == curve) take(p.name, source, p.estimate);
    }
  };
  const ident::RotorFit& rotor = *id.rotor.fits.rotor;
  const std::string kStand = "single-rotor stand";
  // k_T and k_I of the stand are shown but superseded by the platform's (the scale of M_G and
  // F_G belong to the platform's k_T).
  c.parameters.push_back({"rotor.k_T_N_per_rpm2 (stand, not used)", "N/rpm²", kStand,
                          file_vehicle.rotor.k_T_N_per_rpm2, rotor.k_T_N_per_rpm2.value,
                          rotor.k_T_N_per_rpm2.std_error});
  c.k_T_stand_N_per_rpm2 = rotor.k_T_N_per_rpm2.value;
  // The stand's own keys (J_R, the throttle curve); J_R stays the file's when the speed steps
  // did not determine it.
  if (!rotor.J_R_kgm2) take("rotor.J_R_kgm2", kStand, {file_vehicle.rotor.J_R_kgm2, 0.0});
  for (const auto& p : id.rotor.parameters) {
    if (p.name != "rotor.k_T_N_per_rpm2" && p.name != "rotor.k_I_Nm_per_rpm2") take(p.name, kStand, p.estimate);
  }
  const auto& f = platform.fits;
  const ident::Estimate& k_T_platform =
      f.additional_thrust ? f.additional_thrust->k_T_N_per_rpm2 : f.additional_thrust_table->k_T_N_per_rpm2;
  take("rotor.k_T_N_per_rpm2", "platform, level board", k_T_platform);
  c.k_T_platform_N_per_rpm2 = k_T_platform.value;
  takeCurve("additional_thrust", "F_G", "platform, level board");
  // The mixing coefficients: the platform's keys outside the curves, k_T aside.
  for (const auto& p : platform.parameters) {
    const auto* spec = schema.find(p.name);
    if (spec != nullptr && spec->curve.empty() && p.name != "rotor.k_T_N_per_rpm2") {
      take(p.name, "platform, rpm differences", p.estimate);
    }
  }
  takeCurve("leveling_torque", "M_G", "platform, tilted board");
  model::VehicleParams v = model::mergeParameters(file_vehicle, identified, keys);
  v.name = file_vehicle.name + " (identified on the virtual rigs)";
  return v;
}

/// Step 4: the identified and the file's curves against the noise-free truth (as `geaware rig
/// calibrate` and the round-trip test compute it).
void compareCurves(const model::VehicleParams& file_vehicle, const sim::TruthParams& truth,
                   const CalibrationSweeps& sweeps, ControllerCalibration& c) {
  const model::VehicleParams& v = c.vehicle;
  const sim::RotorGeometry geometry = platformGeometry(truth);
  sim::PlatformParams quiet = sweeps.platform;
  quiet.force_noise_N = 0.0;
  quiet.torque_noise_Nm = 0.0;
  const sim::ForceTorquePlatform clean(geometry, truth.aero, quiet);
  double k_sum = 0.0;
  for (double k : geometry.k_T_N_per_rpm2) k_sum += k;
  const double n = c.torque_rpm;
  const std::array<double, 4> speeds{n, n, n, n};
  const double sin_d = std::sin(c.torque_tilt_deg * model::kDegToRad);
  // The curves as the controller's model evaluates them, without its clamp at the landing
  // gear (the rigs go lower than the vehicle flies).
  auto unclamped = [](model::VehicleParams p) {
    p.min_rotor_plane_height_m = 0.0;
    return model::GroundEffectModel(p);
  };
  const model::GroundEffectModel ge_fit = unclamped(v);
  const model::GroundEffectModel ge_file = unclamped(file_vehicle);
  auto torque = [&](const model::GroundEffectModel& ge, const model::VehicleParams& p, double h) {
    const double T = 4.0 * p.rotor.k_T_N_per_rpm2 * n * n;
    return -ge.levelingCoefficient(h) * T * sin_d;
  };
  for (double h : grid(0.07, 1.0, 0.01)) {
    const double truth_fg = clean.wrench(h, 0.0, speeds).wrench.force_B.z() / (k_sum * n * n) - 1.0;
    c.thrust_ratio.push_back({h, truth_fg, ge_fit.thrustRatio(h), ge_file.thrustRatio(h)});
  }
  for (double h : grid(0.08, 0.5, 0.01)) {
    const double truth_tau = clean.wrench(h, c.torque_tilt_deg, speeds).wrench.torque_B.y();
    c.leveling_torque.push_back(
        {h, truth_tau, torque(ge_fit, v, h), torque(ge_file, file_vehicle, h)});
  }
}

/// Steps 5 and 6: the scale's reading of the truth's mass, the CAD inertia kept.
void weigh(const model::VehicleParams& file_vehicle, const CalibrationWorld& world,
           const CalibrationSweeps& sweeps, ControllerCalibration& c) {
  sim::NoiseSource scale(sweeps.seed, salt::kScaleReading);
  c.scale_error_std_kg = world.scale_error_std_kg;
  c.scale_reading_kg = world.flights.truth->mass_kg + world.scale_error_std_kg * scale.normal();
  c.vehicle.mass_kg = c.scale_reading_kg;
  c.parameters.push_back({"mass_kg", "kg", fmt::format("scale (σ = {:g} g)", 1e3 * world.scale_error_std_kg),
                          file_vehicle.mass_kg, c.scale_reading_kg, world.scale_error_std_kg});
  const char* axes[3] = {"xx", "yy", "zz"};
  for (int a = 0; a < 3; ++a) {
    const double J = file_vehicle.inertia_kgm2(a);
    c.parameters.push_back({fmt::format("inertia_kgm2.{}", axes[a]), "kg·m²",
                            "CAD (vehicle file): not measured", J, c.vehicle.inertia_kgm2(a), 0.0});
  }
}

/// Steps 7 and 8: the hover flight's k_T, then the drag flights' D(h), each flown with the
/// belief as it stands.
void fly(const model::VehicleParams& file_vehicle, const CalibrationWorld& world,
         const CalibrationSweeps& sweeps, ControllerCalibration& c) {
  const detail::HoverCalibration hover = detail::calibrateHover(c.vehicle, world, sweeps);
  c.k_T_hover_N_per_rpm2 = hover.fit.k_T_N_per_rpm2.value;
  c.vehicle.rotor.k_T_N_per_rpm2 = c.k_T_hover_N_per_rpm2;
  // The platform's k_T stays listed (F_G's and M_G's fit scale) but is not what the controller
  // flies with: docs/results.md, "How the campaign is set up".
  for (auto& p : c.parameters) {
    if (p.key == "rotor.k_T_N_per_rpm2") p.key += " (platform, not flown)";
  }
  c.parameters.push_back({"rotor.k_T_N_per_rpm2", "N/rpm²",
                          fmt::format("hover flight at {:g} m ({:g} s)", sweeps.hover_height_m, sweeps.hover_s),
                          file_vehicle.rotor.k_T_N_per_rpm2, c.k_T_hover_N_per_rpm2,
                          hover.fit.k_T_N_per_rpm2.std_error});
  c.warnings.insert(c.warnings.end(), hover.fit.warnings.begin(), hover.fit.warnings.end());
  c.flights.push_back(hover.flight);
  // The estimator's process noise from the same hover: what the IMU delivers at the time scales
  // the filter integrates over, the flight controller's vibration included (docs/results.md).
  const ident::ImuNoiseFit& noise = hover.imu_noise;
  const std::string noise_source = fmt::format("hover flight, Allan deviation ({} samples)", noise.samples);
  c.parameters.push_back({"estimator.accel_noise_density", "m/s²/√Hz", noise_source,
                          c.estimator.accel_noise_density, noise.accel_noise_density_m_per_s2_sqrtHz, 0.0});
  c.parameters.push_back({"estimator.gyro_noise_density", "rad/s/√Hz", noise_source,
                          c.estimator.gyro_noise_density, noise.gyro_noise_density_rad_per_s_sqrtHz, 0.0});
  // A density of zero (an IMU that read a constant) would make the filter trust it absolutely.
  if (noise.accel_noise_density_m_per_s2_sqrtHz > 0.0 && noise.gyro_noise_density_rad_per_s_sqrtHz > 0.0) {
    c.estimator.accel_noise_density = noise.accel_noise_density_m_per_s2_sqrtHz;
    c.estimator.gyro_noise_density = noise.gyro_noise_density_rad_per_s_sqrtHz;
  } else {
    c.warnings.push_back("IMU noise: the hover flight's IMU read a constant; the estimator keeps its defaults");
  }
  c.warnings.insert(c.warnings.end(), noise.warnings.begin(), noise.warnings.end());

  CalibrationWorld drag_world = world;
  drag_world.flights.eskf = c.estimator;
  const detail::DragCalibration drag = detail::calibrateDrag(c.vehicle, drag_world, sweeps);
  model::DragTableParams table;
  for (std::size_t k = 0; k < drag.bands.size(); ++k) {
    const ident::DragBand& b = drag.bands[k];
    table.heights_m.push_back(b.h_mean_m);
    table.d_x_N_per_mps.push_back(b.d_x_N_per_mps.value);
    table.d_y_N_per_mps.push_back(b.d_y_N_per_mps.value);
    const std::string source = fmt::format("drag flight at {:g} m", sweeps.drag_heights_m[k]);
    const Eigen::Vector2d file_d = model::RotorDragModel(file_vehicle.drag).coefficients(b.h_mean_m);
    c.parameters.push_back({fmt::format("drag d_x(h = {:.3f} m)", b.h_mean_m), "N/(m/s)", source,
                            file_d.x(), b.d_x_N_per_mps.value, b.d_x_N_per_mps.std_error});
    c.parameters.push_back({fmt::format("drag d_y(h = {:.3f} m)", b.h_mean_m), "N/(m/s)", source,
                            file_d.y(), b.d_y_N_per_mps.value, b.d_y_N_per_mps.std_error});
  }
  c.vehicle.drag = table;
  c.warnings.insert(c.warnings.end(), drag.warnings.begin(), drag.warnings.end());
  c.flights.insert(c.flights.end(), drag.flights.begin(), drag.flights.end());
}

void weighAndFly(const model::VehicleParams& file_vehicle, const CalibrationWorld& world,
                 const CalibrationSweeps& sweeps, ControllerCalibration& c) {
  weigh(file_vehicle, world, sweeps, c);
  c.estimator = world.flights.eskf;
  if (sweeps.flights) {
    fly(file_vehicle, world, sweeps, c);
    c.vehicle.name = file_vehicle.name + " (calibrated: rigs, scale, hover and drag flights)";
  } else {
    c.vehicle.name = file_vehicle.name + " (calibrated: rigs and scale)";
  }
}

}  // namespace

CalibrationWorld calibrationWorld(const sim::World& world) {
  CalibrationWorld w;
  applyWorld(w.flights, world);
  w.scale_error_std_kg = world.team_scale_error_std_kg;
  return w;
}

ControllerCalibration calibrateController(const model::VehicleParams& file_vehicle,
                                          const CalibrationWorld& world,
                                          const CalibrationSweeps& sweeps) {
  if (!world.flights.truth) throw std::invalid_argument("calibration: the world has no truth");
  const sim::TruthParams& truth = *world.flights.truth;
  ControllerCalibration c;
  const RigLogs logs = runRigs(file_vehicle, truth, sweeps, c);
  const Identified identified = identifyOnRigs(logs, file_vehicle, sweeps, c);
  c.vehicle = mergeIdentified(file_vehicle, identified, c);
  weighAndFly(file_vehicle, world, sweeps, c);
  if (const auto errors = c.vehicle.validate(); !errors.empty()) {
    throw std::invalid_argument(model::describeErrors(
        "calibration: the identified parameters are not a valid vehicle:", errors));
  }
  compareCurves(file_vehicle, truth, sweeps, c);
  return c;
}

}  // namespace geaware::experiments
