// SPDX-License-Identifier: BSD-3-Clause
// The `truth:` section's keys (io/truth_file.hpp): one row per key, with its unit, range,
// meaning and place in sim::World. docs/truth-file.md lists this table (checked by a test);
// the reader, the writer and the range checks all work from it.

#include <numbers>
#include <string>
#include <vector>

#include "geaware/io/truth_file.hpp"
#include "geaware/model/field_check.hpp"

namespace geaware::io {
namespace {

using K = TruthKey;
using W = sim::World;
using enum TruthValueKind;

/// The accessor of one number of the world: `expr` is a field path of W (named w).
#define GW_NUMBER(expr) [](W& w, std::size_t) -> double& { return expr; }
/// The accessor of number i of an Eigen vector or std::array field.
#define GW_ELEMENT(expr) [](W& w, std::size_t i) -> double& { return (expr)[static_cast<Eigen::Index>(i)]; }
#define GW_ARRAY(expr) [](W& w, std::size_t i) -> double& { return (expr)[i]; }

K number(std::string_view key, std::string_view unit, double lo, double hi, bool lo_exclusive,
         double& (*get)(W&, std::size_t), std::string_view meaning) {
  K k;
  k.key = key;
  k.unit = unit;
  k.lo = lo;
  k.hi = hi;
  k.lo_exclusive = lo_exclusive;
  k.number = get;
  k.meaning = meaning;
  return k;
}

K vector(std::string_view key, std::string_view unit, std::size_t n, double lo, double hi,
         double& (*get)(W&, std::size_t), std::string_view meaning) {
  K k = number(key, unit, lo, hi, false, get, meaning);
  k.kind = kVector;
  k.cols = n;
  return k;
}

K flag(std::string_view key, bool& (*get)(W&), std::string_view meaning) {
  K k;
  k.key = key;
  k.kind = kBoolean;
  k.flag = get;
  k.meaning = meaning;
  return k;
}

K integer(std::string_view key, std::string_view unit, long lo, long hi,
          long (*get)(const W&), void (*set)(W&, long), std::string_view meaning) {
  K k;
  k.key = key;
  k.unit = unit;
  k.kind = kInteger;
  k.lo = static_cast<double>(lo);
  k.hi = static_cast<double>(hi);
  k.get_integer = get;
  k.set_integer = set;
  k.meaning = meaning;
  return k;
}

constexpr bool kOpen = true;    // lower bound excluded
constexpr bool kClosed = false; // lower bound included

/// The vehicle as built beside its file, its motors and battery.
void bodyKeys(std::vector<K>& t) {
  t.push_back(vector("motor_k_T_scale", "", 4, 0.5, 1.5, GW_ARRAY(w.truth.thrust_multiplier),
                     "each motor's k_T relative to the vehicle part's, mixer order"));
  t.push_back(vector("motor_k_I_scale", "", 4, 0.5, 1.5, GW_ARRAY(w.truth.torque_multiplier),
                     "each motor's k_I relative to the vehicle part's, mixer order"));
  K tilt = vector("thrust_axis_tilt_deg", "deg", 2, -10.0, 10.0,
                  [](W& w, std::size_t i) -> double& {
                    return w.truth.thrust_axis_tilt_rad[i / 2][static_cast<Eigen::Index>(i % 2)];
                  },
                  "each rotor's thrust axis tilted about body x, then body y, mixer order");
  tilt.kind = kRows;
  tilt.rows = 4;
  tilt.to_si = std::numbers::pi / 180.0;
  t.push_back(tilt);
  t.push_back(vector("cog_offset_m", "m", 3, -1.0, 1.0, GW_ELEMENT(w.truth.cog_offset_B),
                     "centre of mass relative to the geometric centre, body x, y, z"));
  t.push_back(number("motor.time_constant_s", "s", 0.0, 10.0, kOpen,
                     GW_NUMBER(w.truth.motor.time_constant_s), "first-order rotor-speed lag τ"));
  t.push_back(number("motor.min_speed_rpm", "rpm", 0.0, 1e6, kClosed,
                     GW_NUMBER(w.truth.motor.min_speed_rpm), "hard rotor-speed floor"));
  t.push_back(number("motor.max_speed_rpm", "rpm", 0.0, 1e6, kOpen,
                     GW_NUMBER(w.truth.motor.max_speed_rpm), "hard rotor-speed ceiling"));
  t.push_back(number("motor.dead_time_s", "s", 0.0, 1.0, kClosed, GW_NUMBER(w.truth.motor.dead_time_s),
                     "ESC/link dead time: a motor acts on the command of this long ago"));
  t.push_back(flag("battery.enabled", [](W& w) -> bool& { return w.truth.battery.enabled; },
                   "false: the ESC curve holds at its nominal voltage always"));
  t.push_back(number("battery.full_voltage_V", "V", 0.0, 1000.0, kOpen,
                     GW_NUMBER(w.truth.battery.full_voltage_V), "open-circuit voltage when full"));
  t.push_back(number("battery.empty_voltage_V", "V", 0.0, 1000.0, kOpen,
                     GW_NUMBER(w.truth.battery.empty_voltage_V), "open-circuit voltage at rated capacity"));
  t.push_back(number("battery.nominal_voltage_V", "V", 0.0, 1000.0, kOpen,
                     GW_NUMBER(w.truth.battery.nominal_voltage_V), "voltage at which the ESC curve holds"));
  t.push_back(number("battery.internal_resistance_ohm", "Ω", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.truth.battery.internal_resistance_ohm), "pack and wiring resistance"));
  t.push_back(number("battery.capacity_Ah", "A·h", 0.0, 1000.0, kOpen,
                     GW_NUMBER(w.truth.battery.capacity_Ah), "rated capacity"));
  t.push_back(number("battery.initial_charge_used_Ah", "A·h", 0.0, 1000.0, kClosed,
                     GW_NUMBER(w.truth.battery.initial_charge_used_Ah), "charge drawn before take-off"));
  t.push_back(number("battery.efficiency", "", 0.0, 1.0, kOpen,
                     GW_NUMBER(w.truth.battery.efficiency), "motor and ESC efficiency, mechanical/electrical"));
  t.push_back(number("battery.idle_current_A", "A", 0.0, 1000.0, kClosed,
                     GW_NUMBER(w.truth.battery.idle_current_A), "current of everything but the motors"));
  t.push_back(number("landing_gear.stiffness_N_per_m", "N/m", 0.0, 1e8, kClosed,
                     GW_NUMBER(w.truth.landing_gear.stiffness_N_per_m),
                     "each leg's stiffness along the surface normal, for flights with ground contact (0: none)"));
  t.push_back(number("landing_gear.damping_ratio", "", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.truth.landing_gear.damping_ratio),
                     "each leg's damping ratio with its share of the mass"));
  t.push_back(number("landing_gear.friction_coefficient", "", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.truth.landing_gear.friction_coefficient),
                     "Coulomb friction between a foot and the surface"));
  t.push_back(number("landing_gear.slip_speed_mps", "m/s", 0.0, 1.0, kOpen,
                     GW_NUMBER(w.truth.landing_gear.slip_speed_mps),
                     "sliding speed below which the friction is regularised"));
  t.push_back(number("landing_gear.max_compression_m", "m", 0.0, 1.0, kOpen,
                     GW_NUMBER(w.truth.landing_gear.max_compression_m),
                     "a leg compressed further breaks or bottoms out: a strike"));
}

/// The truth aerodynamics (sim/rotor_aerodynamics.hpp, docs/sim-aerodynamics.md).
void aeroKeys(std::vector<K>& t) {
  const auto a = [&t](std::string_view key, std::string_view unit, double lo, double hi,
                      double& (*get)(W&, std::size_t), std::string_view meaning) {
    t.push_back(number(key, unit, lo, hi, kClosed, get, meaning));
  };
  a("aero.body_coefficient", "", 0.0, 20.0, GW_NUMBER(w.truth.aero.body_coefficient),
    "K_b of the collective cushion (Sanchez-Cuevas et al. 2017)");
  a("aero.image_core_fraction", "", 1e-3, 10.0, GW_NUMBER(w.truth.aero.image_core_fraction),
    "core radius of the image term, fraction of the propeller radius");
  a("aero.impingement_slope_per_m", "1/m", 0.0, 100.0,
    GW_NUMBER(w.truth.aero.impingement_slope_per_m), "slope of the slipstream-impingement term");
  a("aero.wake_merge_height_m", "m", 0.0, 10.0, GW_NUMBER(w.truth.aero.wake_merge_height_m),
    "height below which each slipstream reaches the surface alone");
  a("aero.wake_merge_softness_m", "m", 1e-6, 1.0, GW_NUMBER(w.truth.aero.wake_merge_softness_m),
    "rounding of the impingement ramp");
  a("aero.recirculation_height_m", "m", 0.0, 1.0, GW_NUMBER(w.truth.aero.recirculation_height_m),
    "recirculation height z_r of the rotor-resolved term");
  a("aero.suckdown_gain", "", 0.0, 100.0, GW_NUMBER(w.truth.aero.suckdown_gain),
    "suck-down amplification μ of the rotor-resolved differences");
  a("aero.redistribution_cap_per_m", "1/m", 1e-6, 100.0,
    GW_NUMBER(w.truth.aero.redistribution_cap_per_m), "bound on each rotor's redistributed share");
  a("aero.own_thrust_fraction", "", 0.0, 1.0, GW_NUMBER(w.truth.aero.own_thrust_fraction),
    "share β of a rotor's increment scaling with its own n²");
  a("aero.reaction_torque_reduction", "", 0.0, 1.0, GW_NUMBER(w.truth.aero.reaction_torque_reduction),
    "reaction-torque reduction κ_Q per unit additional thrust");
  a("aero.ground_effect_range_m", "m", 0.1, 1000.0, GW_NUMBER(w.truth.aero.ground_effect_range_m),
    "distance beyond which a rotor sees no surface");
  a("aero.min_ground_distance_m", "m", 1e-4, 0.1, GW_NUMBER(w.truth.aero.min_ground_distance_m),
    "distances below are clamped to it");
  a("aero.induced_velocity_mps", "m/s", 0.1, 100.0, GW_NUMBER(w.truth.aero.induced_velocity_mps),
    "induced velocity at the reference speed (forward-flight fade)");
  a("aero.induced_velocity_ref_rpm", "rpm", 1.0, 1e6, GW_NUMBER(w.truth.aero.induced_velocity_ref_rpm),
    "rotor speed of induced_velocity_mps");
  a("aero.drag_x_N_per_mps_per_rpm", "N/(m/s)/rpm", 0.0, 1e-2,
    GW_NUMBER(w.truth.aero.drag_x_N_per_mps_per_rpm), "per-rotor drag along body x per rpm");
  a("aero.drag_y_N_per_mps_per_rpm", "N/(m/s)/rpm", 0.0, 1e-2,
    GW_NUMBER(w.truth.aero.drag_y_N_per_mps_per_rpm), "per-rotor drag along body y per rpm");
  a("aero.drag_ground_reduction_x", "", 0.0, 0.99, GW_NUMBER(w.truth.aero.drag_ground_reduction_x),
    "near-ground drag reduction a_x");
  a("aero.drag_ground_reduction_y", "", 0.0, 0.99, GW_NUMBER(w.truth.aero.drag_ground_reduction_y),
    "near-ground drag reduction a_y");
  a("aero.drag_ground_height_m", "m", 1e-3, 10.0, GW_NUMBER(w.truth.aero.drag_ground_height_m),
    "range z_q of the near-ground drag reduction");
  a("aero.in_flight_cushion_scale", "", 0.0, 2.0, GW_NUMBER(w.truth.aero.in_flight_cushion_scale),
    "the additional-thrust fraction in flight relative to the rigs' (the rigs never apply it)");
  a("aero.translational_lift_per_mps2", "1/(m/s)²", 0.0, 1.0,
    GW_NUMBER(w.truth.aero.translational_lift_per_mps2),
    "c of the free-air thrust gain 1 + min(c·v_h², max), v_h the rotor's in-plane airspeed");
  a("aero.translational_lift_max", "", 0.0, 0.5, GW_NUMBER(w.truth.aero.translational_lift_max),
    "cap of the translational-lift gain");
  a("aero.airframe_drag_area_m2", "m²", 0.0, 1.0, GW_NUMBER(w.truth.aero.airframe_drag_area_m2),
    "C_d·A of the quadratic airframe drag at the CoM (0: none)");
  a("aero.air_density_kg_per_m3", "kg/m³", 0.5, 1.5, GW_NUMBER(w.truth.aero.air_density_kg_per_m3),
    "air density of the airframe drag");
}

void imuMocapKeys(std::vector<K>& t) {
  t.push_back(number("sensors.imu.rate_Hz", "Hz", 0.0, 1e5, kOpen, GW_NUMBER(w.sensors.imu.rate_Hz),
                     "IMU sample rate"));
  t.push_back(number("sensors.imu.gyro_noise_density_rad_per_s_sqrtHz", "rad/s/√Hz", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.sensors.imu.gyro_noise_density_rad_per_s_sqrtHz), "gyro white noise"));
  t.push_back(number("sensors.imu.gyro_bias_walk_rad_per_s2_sqrtHz", "rad/s²/√Hz", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.sensors.imu.gyro_bias_walk_rad_per_s2_sqrtHz), "gyro bias random walk"));
  t.push_back(number("sensors.imu.gyro_initial_bias_std_rad_per_s", "rad/s", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.sensors.imu.gyro_initial_bias_std_rad_per_s), "turn-on gyro bias, 1σ per axis"));
  t.push_back(number("sensors.imu.accel_noise_density_m_per_s2_sqrtHz", "m/s²/√Hz", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.sensors.imu.accel_noise_density_m_per_s2_sqrtHz), "accelerometer white noise"));
  t.push_back(number("sensors.imu.accel_bias_walk_m_per_s3_sqrtHz", "m/s³/√Hz", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.sensors.imu.accel_bias_walk_m_per_s3_sqrtHz), "accelerometer bias random walk"));
  t.push_back(number("sensors.imu.accel_initial_bias_std_m_per_s2", "m/s²", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.sensors.imu.accel_initial_bias_std_m_per_s2), "turn-on accelerometer bias, 1σ per axis"));
  t.push_back(number("sensors.imu.gyro_range_rad_per_s", "rad/s", 0.0, 1e4, kOpen,
                     GW_NUMBER(w.sensors.imu.gyro_range_rad_per_s), "gyro saturation"));
  t.push_back(number("sensors.imu.accel_range_m_per_s2", "m/s²", 0.0, 1e5, kOpen,
                     GW_NUMBER(w.sensors.imu.accel_range_m_per_s2), "accelerometer saturation"));
  t.push_back(vector("sensors.imu.lever_arm_B_m", "m", 3, -10.0, 10.0, GW_ELEMENT(w.sensors.imu.lever_arm_B_m),
                     "IMU position relative to the geometric centre, body"));
  t.push_back(number("sensors.imu.vibration_gyro_std_rad_per_s", "rad/s", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.sensors.imu.vibration_gyro_std_rad_per_s),
                     "vibration noise left in the gyro output, 1σ per axis"));
  t.push_back(number("sensors.imu.vibration_accel_std_m_per_s2", "m/s²", 0.0, 100.0, kClosed,
                     GW_NUMBER(w.sensors.imu.vibration_accel_std_m_per_s2),
                     "vibration noise left in the accelerometer output, 1σ per axis"));
  t.push_back(number("sensors.imu.rotor_vibration_accel_std_m_per_s2", "m/s²", 0.0, 1e3, kClosed,
                     GW_NUMBER(w.sensors.imu.rotor_vibration.accel_std_m_per_s2),
                     "raw accelerometer vibration at the rotor harmonics (before any filter) at the reference speed, 1σ per axis (0: off)"));
  t.push_back(number("sensors.imu.rotor_vibration_gyro_std_rad_per_s", "rad/s", 0.0, 100.0, kClosed,
                     GW_NUMBER(w.sensors.imu.rotor_vibration.gyro_std_rad_per_s),
                     "raw gyro vibration at the rotor harmonics (before any filter) at the reference speed, 1σ per axis (0: off)"));
  t.push_back(number("sensors.imu.rotor_vibration_reference_rpm", "rpm", 0.0, 1e6, kOpen,
                     GW_NUMBER(w.sensors.imu.rotor_vibration.reference_rpm),
                     "rotor speed at which the rotor-harmonic σ hold (they scale with speed²)"));
  t.push_back(integer(
      "sensors.imu.rotor_vibration_blade_count", "", 1, 12,
      [](const W& w) -> long { return w.sensors.imu.rotor_vibration.blade_count; },
      [](W& w, long v) { w.sensors.imu.rotor_vibration.blade_count = static_cast<int>(v); },
      "blades per propeller (the blade-passage harmonic)"));
  t.push_back(number("sensors.imu.lowpass_cutoff_Hz", "Hz", 0.0, 1e4, kClosed,
                     GW_NUMBER(w.sensors.imu.lowpass_cutoff_Hz),
                     "the flight controller's second-order low-pass (0: off)"));
  t.push_back(number("sensors.imu.filter_rate_Hz", "Hz", 0.0, 1e5, kOpen,
                     GW_NUMBER(w.sensors.imu.filter_rate_Hz), "raw sample rate the low-pass runs at"));
  t.push_back(number("sensors.mocap.rate_Hz", "Hz", 0.0, 1e4, kOpen, GW_NUMBER(w.sensors.mocap.rate_Hz),
                     "motion-capture rate"));
  t.push_back(number("sensors.mocap.latency_s", "s", 0.0, 1.0, kClosed, GW_NUMBER(w.sensors.mocap.latency_s),
                     "capture-to-delivery delay"));
  t.push_back(number("sensors.mocap.reported_latency_s", "s", -1.0, 1.0, kClosed,
                     GW_NUMBER(w.sensors.mocap.reported_latency_s),
                     "the latency the driver stamps, all the estimator knows (negative: the true one)"));
  t.push_back(number("sensors.mocap.latency_jitter_std_s", "s", 0.0, 0.1, kClosed,
                     GW_NUMBER(w.sensors.mocap.latency_jitter_std_s), "1σ of each capture's latency"));
  t.push_back(number("sensors.mocap.position_noise_std_m", "m", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.sensors.mocap.position_noise_std_m), "position noise, 1σ per axis"));
  t.push_back(number("sensors.mocap.attitude_noise_std_rad", "rad", 0.0, 0.5, kClosed,
                     GW_NUMBER(w.sensors.mocap.attitude_noise_std_rad), "attitude noise, 1σ per body axis"));
  t.push_back(number("sensors.mocap.dropout_probability", "", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.sensors.mocap.dropout_probability), "independent loss of one capture"));
  t.push_back(number("sensors.mocap.burst_probability", "", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.sensors.mocap.burst_probability), "a capture starts a burst of losses"));
  t.push_back(integer(
      "sensors.mocap.burst_length_samples", "", 1, 100000,
      [](const W& w) -> long { return w.sensors.mocap.burst_length_samples; },
      [](W& w, long v) { w.sensors.mocap.burst_length_samples = static_cast<int>(v); },
      "captures lost per burst"));
}

void telemetryRangerKeys(std::vector<K>& t) {
  t.push_back(number("sensors.rotor_telemetry.rate_Hz", "Hz", 0.0, 1e5, kOpen,
                     GW_NUMBER(w.sensors.rotor_telemetry.rate_Hz), "rotor-speed telemetry rate"));
  t.push_back(number("sensors.rotor_telemetry.noise_std_rpm", "rpm", 0.0, 1e4, kClosed,
                     GW_NUMBER(w.sensors.rotor_telemetry.noise_std_rpm), "white noise, 1σ per rotor"));
  t.push_back(number("sensors.rotor_telemetry.resolution_rpm", "rpm", 0.0, 1e4, kClosed,
                     GW_NUMBER(w.sensors.rotor_telemetry.resolution_rpm), "quantisation step (0: none)"));
  t.push_back(number("sensors.ranger.rate_Hz", "Hz", 0.0, 1e4, kOpen, GW_NUMBER(w.sensors.ranger.rate_Hz),
                     "lattice ranger frame rate"));
  t.push_back(integer(
      "sensors.ranger.side", "", 1, 16, [](const W& w) -> long { return w.sensors.ranger.side; },
      [](W& w, long v) { w.sensors.ranger.side = static_cast<int>(v); }, "zones per side"));
  t.push_back(number("sensors.ranger.fov_rad", "rad", 0.0, 0.9 * std::numbers::pi, kOpen, GW_NUMBER(w.sensors.ranger.fov_rad),
                     "full field of view per axis"));
  t.push_back(vector("sensors.ranger.mount_B", "m", 3, -10.0, 10.0, GW_ELEMENT(w.sensors.ranger.mount_B),
                     "sensor origin relative to the geometric centre, body"));
  t.push_back(number("sensors.ranger.min_range_m", "m", 0.0, 1e3, kClosed,
                     GW_NUMBER(w.sensors.ranger.min_range_m), "nearer returns are lost"));
  t.push_back(number("sensors.ranger.max_range_m", "m", 0.0, 1e3, kOpen,
                     GW_NUMBER(w.sensors.ranger.max_range_m), "farther surfaces give no return"));
  t.push_back(number("sensors.ranger.max_incidence_rad", "rad", 0.0, 0.5 * std::numbers::pi, kClosed,
                     GW_NUMBER(w.sensors.ranger.max_incidence_rad), "ray-to-normal angle beyond which nothing returns"));
  t.push_back(number("sensors.ranger.noise_floor_m", "m", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.sensors.ranger.noise_floor_m), "range-independent noise, 1σ"));
  t.push_back(number("sensors.ranger.noise_fraction", "", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.sensors.ranger.noise_fraction), "noise growth with range, 1σ per metre"));
  t.push_back(number("sensors.ranger.outlier_probability", "", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.sensors.ranger.outlier_probability), "per zone and frame"));
}

void disturbanceKeys(std::vector<K>& t) {
  t.push_back(flag("disturbances.ground_turbulence.enabled",
                   [](W& w) -> bool& { return w.ground_turbulence; },
                   "near-ground recirculation buffeting on or off"));
  t.push_back(vector("disturbances.ground_turbulence.force_std_N", "N", 3, 0.0, 1e3,
                     GW_ELEMENT(w.ground_turbulence_params.force_std_N), "σ_F at the surface, body axes"));
  t.push_back(vector("disturbances.ground_turbulence.torque_std_Nm", "N·m", 3, 0.0, 1e3,
                     GW_ELEMENT(w.ground_turbulence_params.torque_std_Nm), "σ_τ at the surface, body axes"));
  t.push_back(number("disturbances.ground_turbulence.correlation_time_s", "s", 0.0, 1e3, kOpen,
                     GW_NUMBER(w.ground_turbulence_params.correlation_time_s), "τ_c of the Gauss–Markov processes"));
  t.push_back(number("disturbances.ground_turbulence.scale_height_m", "m", 0.0, 1e2, kOpen,
                     GW_NUMBER(w.ground_turbulence_params.scale_height_m), "h_s: the intensity halves about here"));
  t.push_back(number("disturbances.ground_turbulence.cutoff_height_m", "m", 0.0, 1e3, kOpen,
                     GW_NUMBER(w.ground_turbulence_params.cutoff_height_m), "h_max: none from here up"));
  t.push_back(flag("disturbances.ground_turbulence.per_rotor",
                   [](W& w) -> bool& { return w.ground_turbulence_params.per_rotor; },
                   "the per-rotor law (docs/world.md §7) instead of σ_F, σ_τ, h_s, h_max"));
  t.push_back(number("disturbances.ground_turbulence.fluctuation_per_increment", "", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.ground_turbulence_params.fluctuation_per_increment),
                     "κ: each rotor's σ_T/T per unit of its in-flight additional-thrust fraction"));
  t.push_back(number("disturbances.ground_turbulence.rotor_correlation", "", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.ground_turbulence_params.rotor_correlation),
                     "ρ: correlation of the four rotors' fluctuations (per-rotor law)"));
  t.push_back(number("disturbances.altitude_unsteadiness.torque_std_Nm", "N·m", 0.0, 10.0, kClosed,
                     GW_NUMBER(w.altitude_unsteadiness_params.torque_std_Nm),
                     "σ_τ about each body axis, at every height (blade imbalance…; 0 and force 0: off)"));
  t.push_back(number("disturbances.altitude_unsteadiness.force_std_N", "N", 0.0, 100.0, kClosed,
                     GW_NUMBER(w.altitude_unsteadiness_params.force_std_N), "σ_F along each body axis"));
  t.push_back(number("disturbances.altitude_unsteadiness.correlation_time_s", "s", 0.0, 1e3, kOpen,
                     GW_NUMBER(w.altitude_unsteadiness_params.correlation_time_s),
                     "τ_c of its Gauss–Markov processes"));
  t.push_back(flag("disturbances.room_air.enabled", [](W& w) -> bool& { return w.room_air; },
                   "air moving in the room on or off"));
  t.push_back(vector("disturbances.room_air.mean_W_mps", "m/s", 3, -100.0, 100.0,
                     GW_ELEMENT(w.room_air_params.mean_W_mps), "steady air velocity, world frame"));
  t.push_back(vector("disturbances.room_air.gust_std_mps", "m/s", 3, 0.0, 100.0,
                     GW_ELEMENT(w.room_air_params.gust_std_mps), "gust 1σ per world axis"));
  t.push_back(number("disturbances.room_air.gust_correlation_time_s", "s", 0.0, 1e4, kOpen,
                     GW_NUMBER(w.room_air_params.gust_correlation_time_s), "correlation time T of the gusts"));
}

void variationKeys(std::vector<K>& t) {
  t.push_back(number("per_flight_variation.mass_rel", "", 0.0, 0.5, kClosed,
                     GW_NUMBER(w.per_flight_variation.mass_rel), "bound of the seeded relative mass error"));
  t.push_back(number("per_flight_variation.inertia_rel", "", 0.0, 0.5, kClosed,
                     GW_NUMBER(w.per_flight_variation.inertia_rel), "bound on each principal moment's relative error"));
  t.push_back(number("per_flight_variation.cog_offset_m", "m", 0.0, 0.1, kClosed,
                     GW_NUMBER(w.per_flight_variation.cog_offset_m), "bound on the CoG offset's x and y"));
  t.push_back(number("per_flight_variation.cog_offset_z_m", "m", 0.0, 0.1, kClosed,
                     GW_NUMBER(w.per_flight_variation.cog_offset_z_m), "bound on the CoG offset's z"));
  t.push_back(number("per_flight_variation.thrust_spread_rel", "", 0.0, 0.5, kClosed,
                     GW_NUMBER(w.per_flight_variation.thrust_spread_rel), "bound on each motor's k_T scale − 1"));
  t.push_back(number("team.scale_error_std_kg", "kg", 0.0, 1.0, kClosed,
                     GW_NUMBER(w.team_scale_error_std_kg), "1σ of the team's scale reading of the mass"));
}

#undef GW_NUMBER
#undef GW_ELEMENT
#undef GW_ARRAY

std::vector<K> buildKeys() {
  std::vector<K> t;
  bodyKeys(t);
  aeroKeys(t);
  imuMocapKeys(t);
  telemetryRangerKeys(t);
  disturbanceKeys(t);
  variationKeys(t);
  return t;
}

std::string bound(double v) {
  std::string s = model::formatValue(v);
  if (const auto e = s.find("e+"); e != std::string::npos) s.erase(e + 1, 1);
  if (s.front() == '-') s = "−" + s.substr(1);
  return s;
}

}  // namespace

std::string TruthKey::validText() const {
  switch (kind) {
    case kBoolean: return "true/false";
    case kInteger: return "whole number in [" + bound(lo) + ", " + bound(hi) + "]";
    default: break;
  }
  std::string r = (lo_exclusive ? "(" : "[") + bound(lo) + ", " + bound(hi) + "]";
  if (kind == kVector) r += ", " + std::to_string(cols) + " numbers";
  if (kind == kRows) r += ", " + std::to_string(rows) + " × [" + std::to_string(cols) + " numbers]";
  return r;
}

const std::vector<TruthKey>& truthFileKeys() {
  static const std::vector<TruthKey> keys = buildKeys();
  return keys;
}

}  // namespace geaware::io
