// SPDX-License-Identifier: BSD-3-Clause
// The campaign's calibration as a real team would do it (experiments/calibration.hpp; issue 10
// item 2): the belief's mass is the scale's seeded reading of the truth's, its inertia the CAD's,
// its k_T the hover flight's, its drag table the drag flights'; the truth reaches the belief only
// through what a measurement sees.

#include "geaware/experiments/calibration.hpp"

#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include "geaware/io/truth_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/rotor_drag.hpp"
#include "geaware/sim/imu.hpp"
#include "geaware/sim/sampling.hpp"
#include "geaware/sim/world.hpp"

namespace geaware::experiments {
namespace {

sim::World asBuilt() { return io::builtinTruth("as_built"); }

CalibrationSweeps rigsAndScaleOnly() {
  CalibrationSweeps s = CalibrationSweeps::defaults();
  s.flights = false;
  return s;
}

const ControllerCalibration& asBuiltCalibration() {
  static const ControllerCalibration c =
      calibrateController(io::builtinVehicle(), calibrationWorld(asBuilt()));
  return c;
}

TEST(CalibrationScale, TheBeliefsMassIsTheTruthsPlusTheSeededScaleDraw) {
  const sim::World world = asBuilt();
  ASSERT_GT(world.team_scale_error_std_kg, 0.0);
  CalibrationSweeps s = rigsAndScaleOnly();
  const ControllerCalibration a = calibrateController(io::builtinVehicle(), calibrationWorld(world), s);
  sim::NoiseSource scale(s.seed, salt::kScaleReading);
  const double expected = world.truth.mass_kg + world.team_scale_error_std_kg * scale.normal();
  EXPECT_EQ(a.vehicle.mass_kg, expected);
  EXPECT_NE(a.vehicle.mass_kg, world.truth.mass_kg);
  EXPECT_LT(std::abs(a.vehicle.mass_kg - world.truth.mass_kg), 5.0 * world.team_scale_error_std_kg);
  // Reproducible from the seed; another seed reads the scale again.
  const ControllerCalibration b = calibrateController(io::builtinVehicle(), calibrationWorld(world), s);
  EXPECT_EQ(b.vehicle.mass_kg, a.vehicle.mass_kg);
  s.seed = 2;
  const ControllerCalibration c = calibrateController(io::builtinVehicle(), calibrationWorld(world), s);
  EXPECT_NE(c.vehicle.mass_kg, a.vehicle.mass_kg);
  // The scale follows the truth, not the file: a heavier truth weighs more.
  sim::World heavy = world;
  heavy.truth.mass_kg += 0.2;
  s.seed = 1;
  const ControllerCalibration h = calibrateController(io::builtinVehicle(), calibrationWorld(heavy), s);
  EXPECT_NEAR(h.vehicle.mass_kg - a.vehicle.mass_kg, 0.2, 1e-12);
}

TEST(CalibrationScale, TheInertiaStaysTheCadValueWhateverTheTruth) {
  sim::World world = asBuilt();
  world.truth.inertia_kgm2 *= 1.2;
  const model::VehicleParams file = io::builtinVehicle();
  const ControllerCalibration c = calibrateController(file, calibrationWorld(world), rigsAndScaleOnly());
  EXPECT_EQ(c.vehicle.inertia_kgm2, file.inertia_kgm2);
}

TEST(CalibrationFlights, TheHoverKtIsTheTruthsInFlightKtNotTheFiles) {
  const ControllerCalibration& c = asBuiltCalibration();
  const sim::World world = asBuilt();
  // The truth's k_T in a hover out of ground effect: its nominal k_T times the mean motor scale
  // (near-equal hover speeds), seen through the scale's mass (the fit's thrust is m·f_z).
  double mean_scale = 0.0;
  for (double m : world.truth.thrust_multiplier) mean_scale += m / 4.0;
  const double effective =
      world.truth.k_T_N_per_rpm2 * mean_scale * c.vehicle.mass_kg / world.truth.mass_kg;
  EXPECT_NEAR(c.k_T_hover_N_per_rpm2 / effective, 1.0, 0.02);
  EXPECT_EQ(c.vehicle.rotor.k_T_N_per_rpm2, c.k_T_hover_N_per_rpm2);
  ASSERT_EQ(c.flights.size(), 3u);
  EXPECT_FALSE(c.flights[0].struck);
  EXPECT_GE(c.flights[0].mean_height_m, 1.0);

  // A truth whose rotors give 8 % more thrust than the file says: the hover k_T follows it.
  sim::World strong = world;
  strong.truth.k_T_N_per_rpm2 *= 1.08;
  const ControllerCalibration s = calibrateController(io::builtinVehicle(), calibrationWorld(strong));
  const double file_k_T = io::builtinVehicle().rotor.k_T_N_per_rpm2;
  EXPECT_NEAR(s.k_T_hover_N_per_rpm2 / (1.08 * effective), 1.0, 0.02);
  EXPECT_GT(s.vehicle.rotor.k_T_N_per_rpm2 / file_k_T, 1.05);
}

/// The low-frequency density of the IMU the world gives, per sensor: the vibration's raw white
/// noise behind the flight controller's filter (DC gain 1) and the sensor's own white noise.
double lowFrequencyDensity(const sim::ImuParams& imu, double vibration_std, double sensor_density) {
  double vib = 0.0;
  if (vibration_std > 0.0) {
    const sim::LowPass2 lp(imu.filter_rate_Hz, imu.lowpass_cutoff_Hz);
    vib = vibration_std / std::sqrt(lp.noiseGain()) / std::sqrt(imu.filter_rate_Hz);
  }
  return std::hypot(vib, sensor_density);
}

TEST(CalibrationFlights, TheEstimatorsNoiseIsWhatTheHoverFlightsImuDelivers) {
  // As built the gyro's broadband vibration behind the 20 Hz filter dominates it; the
  // accelerometer's vibration is at the rotor harmonics (170 Hz in x/y), of which the filter
  // leaves σ_res = σ_raw·|H(f_hover)| ≈ 0.28 m/s², aliased by the 200 Hz output. The hover's own
  // motion (turbulence, unsteadiness) and that residue add to the Allan deviation, so the fit may
  // read above the sensor's density, never far below; and never above the residue spread white
  // over the output band, σ_res/√(rate/2), the most it could put at any frequency.
  const ControllerCalibration& c = asBuiltCalibration();
  const sim::ImuParams& imu = asBuilt().sensors.imu;
  const double accel = lowFrequencyDensity(imu, imu.vibration_accel_std_m_per_s2, imu.accel_noise_density_m_per_s2_sqrtHz);
  const double gyro = lowFrequencyDensity(imu, imu.vibration_gyro_std_rad_per_s, imu.gyro_noise_density_rad_per_s_sqrtHz);
  const sim::LowPass2 lp(imu.filter_rate_Hz, imu.lowpass_cutoff_Hz);
  const double hover_Hz = imu.rotor_vibration.reference_rpm / 60.0;
  const double residue = imu.rotor_vibration.accel_std_m_per_s2 * lp.gainAt(hover_Hz);
  ASSERT_GT(residue, 0.1);
  EXPECT_GT(c.estimator.accel_noise_density / accel, 0.9);
  EXPECT_LT(c.estimator.accel_noise_density, std::hypot(accel, residue / std::sqrt(imu.rate_Hz / 2.0)));
  EXPECT_GT(c.estimator.gyro_noise_density / gyro, 0.9);
  bool listed = false;
  for (const IdentifiedParameter& p : c.parameters) listed |= p.key == "estimator.accel_noise_density";
  EXPECT_TRUE(listed);

  // The ideal world has no vibration: the fit reads the sensor's own accelerometer noise.
  const sim::World ideal = sim::idealWorld(io::builtinVehicle());
  const ControllerCalibration i = calibrateController(io::builtinVehicle(), calibrationWorld(ideal));
  const double sensor = ideal.sensors.imu.accel_noise_density_m_per_s2_sqrtHz;
  EXPECT_NEAR(i.estimator.accel_noise_density / sensor, 1.0, 0.15);
  // Without flights nothing is measured: the estimator keeps the world's settings.
  const ControllerCalibration r = calibrateController(io::builtinVehicle(), calibrationWorld(asBuilt()), rigsAndScaleOnly());
  EXPECT_EQ(r.estimator.accel_noise_density, calibrationWorld(asBuilt()).flights.eskf.accel_noise_density);
}

TEST(CalibrationFlights, TheDragTableComesFromTheFlights) {
  const ControllerCalibration& c = asBuiltCalibration();
  const model::VehicleParams file = io::builtinVehicle();
  const auto& d = c.vehicle.drag;
  ASSERT_EQ(d.heights_m.size(), 2u);
  EXPECT_NEAR(d.heights_m[0], 0.12, 0.01);
  EXPECT_NEAR(d.heights_m[1], 2.0, 0.05);
  EXPECT_NE(d.d_x_N_per_mps, file.drag.d_x_N_per_mps);
  // Less drag near the ground, as the truth's rotor drag q(z) and the paper's flights say — on
  // average over calibration seeds: one drag flight's d_x scatters by ±0.03–0.1 N/(m/s) from
  // seed to seed (as built, seeds 1–4: 0.325/0.366, 0.218/0.480, 0.324/0.330, 0.210/0.236 at
  // 0.12 m / 2 m), so a single seed's ratio (0.89 for seed 1 since the per-rotor near-ground
  // turbulence of docs/world.md §7; 0.77 before it) says little.
  double near = 0.0, high = 0.0;
  for (std::uint64_t seed : {1, 2, 3, 4}) {
    CalibrationSweeps sw = CalibrationSweeps::defaults();
    sw.seed = seed;
    const auto& q = calibrateController(file, calibrationWorld(asBuilt()), sw).vehicle.drag;
    near += q.d_x_N_per_mps[0] / 4.0;
    high += q.d_x_N_per_mps[1] / 4.0;
  }
  EXPECT_LT(near, 0.85 * high);
  // The truth's rotor drag 30 % stronger: the identified table moves with it.
  sim::World draggy = asBuilt();
  draggy.truth.aero.drag_x_N_per_mps_per_rpm *= 1.3;
  draggy.truth.aero.drag_y_N_per_mps_per_rpm *= 1.3;
  const ControllerCalibration s = calibrateController(file, calibrationWorld(draggy));
  EXPECT_GT(s.vehicle.drag.d_x_N_per_mps[1], 1.15 * d.d_x_N_per_mps[1]);
  EXPECT_GT(s.vehicle.drag.d_y_N_per_mps[1], 1.15 * d.d_y_N_per_mps[1]);
  EXPECT_GT(s.vehicle.drag.d_x_N_per_mps[0], 1.1 * d.d_x_N_per_mps[0]);
}

TEST(CalibrationFlights, WhatNoMeasurementSeesDoesNotReachTheBelief) {
  const ControllerCalibration& a = asBuiltCalibration();
  // The landing feet 5 mm higher (they touch nothing in any calibration flight), and the
  // scenario's vehicle (the calibration flies its own belief): nothing of the belief moves.
  sim::World world = asBuilt();
  for (auto& f : world.truth.landing_feet_B) f.z() += 0.005;
  CalibrationWorld cw = calibrationWorld(world);
  cw.flights.vehicle.mass_kg = 9.0;
  cw.flights.vehicle.drag.d_x_N_per_mps.assign(cw.flights.vehicle.drag.d_x_N_per_mps.size(), 5.0);
  const ControllerCalibration b = calibrateController(io::builtinVehicle(), cw);
  EXPECT_EQ(b.vehicle.mass_kg, a.vehicle.mass_kg);
  EXPECT_EQ(b.vehicle.rotor.k_T_N_per_rpm2, a.vehicle.rotor.k_T_N_per_rpm2);
  EXPECT_EQ(b.vehicle.drag.d_x_N_per_mps, a.vehicle.drag.d_x_N_per_mps);
  EXPECT_EQ(b.vehicle.drag.d_y_N_per_mps, a.vehicle.drag.d_y_N_per_mps);
  EXPECT_EQ(b.vehicle.drag.heights_m, a.vehicle.drag.heights_m);
}

TEST(CalibrationFlights, EveryBeliefParameterNamesItsSource) {
  const ControllerCalibration& c = asBuiltCalibration();
  auto sourceOf = [&](const std::string& key) -> std::string {
    for (const auto& p : c.parameters) {
      if (p.key == key) return p.source;
    }
    return "";
  };
  EXPECT_EQ(sourceOf("mass_kg").rfind("scale", 0), 0u);
  EXPECT_EQ(sourceOf("inertia_kgm2.xx").rfind("CAD", 0), 0u);
  EXPECT_EQ(sourceOf("rotor.k_T_N_per_rpm2 (stand, not used)"), "single-rotor stand");
  EXPECT_EQ(sourceOf("rotor.k_T_N_per_rpm2 (platform, not flown)"), "platform, level board");
  EXPECT_EQ(sourceOf("rotor.k_T_N_per_rpm2").rfind("hover flight", 0), 0u);
  int drag_rows = 0;
  for (const auto& p : c.parameters) {
    if (p.source.rfind("drag flight", 0) == 0) ++drag_rows;
  }
  EXPECT_EQ(drag_rows, 4);
  EXPECT_GT(c.k_T_stand_N_per_rpm2, 0.0);
  EXPECT_GT(c.k_T_platform_N_per_rpm2, 0.0);
}

}  // namespace
}  // namespace geaware::experiments
