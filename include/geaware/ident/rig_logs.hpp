// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The logs identification reads (formats in docs/identification.md, "Log formats"): the
// quadrotor force/torque platform, the single-rotor stand, and flight logs. Each reader keeps
// only the columns it needs, as vectors of doubles, read in one pass (io/csv_reader.hpp);
// column names are configurable, with the rigs' names as defaults, and every column's values
// are checked against a plausible range for its unit.

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "geaware/io/column_expression.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::ident {

/// Columns computed from the log's fields (`--column NAME=EXPR`, `--const NAME=VALUE`; each
/// NAME one of the reader's column names, io/column_expression.hpp).
using ColumnDefinitions = std::vector<io::ColumnDefinition>;

// ------------------------------------------------------------------------ quadrotor platform

/// Column names of a quadrotor platform log. Forces and torques are in the body frame, about
/// the vehicle's centre; the vehicle is level and the board below it is tilted by tilt_deg
/// about the body y axis; rotors are numbered as model::Mixer (1 front-right, 2 rear-left,
/// 3 front-left, 4 rear-right).
struct PlatformColumns {
  std::string t = "t_s";
  std::string h = "h_m";             ///< rotor-plane height above the board [m]
  std::string tilt = "tilt_deg";     ///< board tilt about body y [deg]
  std::array<std::string, 4> n = {"n1_rpm", "n2_rpm", "n3_rpm", "n4_rpm"};
  std::array<std::string, 3> f = {"fx_N", "fy_N", "fz_N"};
  std::array<std::string, 3> tau = {"tx_Nm", "ty_Nm", "tz_Nm"};
  /// Rows that are means (a table published as mean ± std per height): the standard deviation
  /// of fz behind each mean [N] and the count of samples behind it. Empty: not read (every row
  /// one sample). With fz_std the level-board thrust fits weight each row by 1/σ²,
  /// σ = std/√count, as known variances; with count alone every fit weights rows by their count.
  /// `identify platform --std-column NAME --count-column NAME`.
  std::string fz_std;
  std::string count;
};

struct PlatformLog {
  std::string source;                 ///< file it was read from
  std::size_t first_data_line = 0;    ///< line of sample 0
  std::vector<double> t_s;
  std::vector<double> h_m;
  std::vector<double> tilt_deg;
  std::array<std::vector<double>, 4> n_rpm;
  std::array<std::vector<double>, 3> f_N;     ///< body-frame force [N]
  std::array<std::vector<double>, 3> tau_Nm;  ///< body-frame torque [N·m]
  std::vector<double> fz_std_N;  ///< std of f_z behind each row's mean (> 0); empty: not given [N]
  std::vector<double> count;     ///< samples behind each row (≥ 1); empty: one per row

  [[nodiscard]] std::size_t size() const noexcept { return t_s.size(); }
  /// Samples behind row i (1 without a count column).
  [[nodiscard]] double samples(std::size_t i) const noexcept { return count.empty() ? 1.0 : count[i]; }
  /// The weight of row i's f_z: 1/σ² with σ = std/√count when the stds are given (known
  /// variances), else the row's count.
  [[nodiscard]] double fzWeight(std::size_t i) const noexcept {
    return fz_std_N.empty() ? samples(i) : samples(i) / (fz_std_N[i] * fz_std_N[i]);
  }
  [[nodiscard]] bool fzVariancesKnown() const noexcept { return !fz_std_N.empty(); }
};

/// Throws IdentError naming the file and line when a std is not > 0 or a count is below 1.
[[nodiscard]] PlatformLog readPlatformLog(const std::filesystem::path& file,
                                          const PlatformColumns& columns = {},
                                          const ColumnDefinitions& definitions = {});

// ------------------------------------------------------------------------ single-rotor stand

struct RotorStandColumns {
  std::string t = "t_s";
  std::string throttle = "throttle";   ///< ESC command in [0, 1]
  std::string rpm = "rpm";
  std::string thrust = "thrust_N";
  std::string torque = "torque_Nm";    ///< reaction torque about the rotor axis [N·m]
  /// Battery (supply) voltage [V]; empty: not read (the throttle curve without its voltage
  /// dependence). `identify rotor --voltage-column voltage_V`.
  std::string voltage;
};

struct RotorStandLog {
  std::string source;
  std::size_t first_data_line = 0;
  std::vector<double> t_s;
  std::vector<double> throttle;
  std::vector<double> rpm;
  std::vector<double> thrust_N;
  std::vector<double> torque_Nm;
  std::vector<double> voltage_V;  ///< empty when not read [V]

  [[nodiscard]] std::size_t size() const noexcept { return t_s.size(); }
};

[[nodiscard]] RotorStandLog readRotorStandLog(const std::filesystem::path& file,
                                              const RotorStandColumns& columns = {},
                                              const ColumnDefinitions& definitions = {});

// ----------------------------------------------------------------------------- flight logs

/// Column names of a flight log. Velocity and the external acceleration are in the world
/// frame (z up); the attitude is the Hamilton quaternion of R_WB. The external acceleration is
/// the paper's disturbance observer (eq. 3): ã_ext = (a − g)_f^imu − z_B·T_f/m, i.e. the
/// force not explained by gravity and the rotor thrust k_T·Σn², per unit mass.
struct FlightColumns {
  std::string t = "t_s";
  std::string h = "h_m";
  std::array<std::string, 3> v = {"vx_mps", "vy_mps", "vz_mps"};
  std::array<std::string, 4> q = {"qw", "qx", "qy", "qz"};
  std::array<std::string, 3> a_ext = {"ax_ext_mps2", "ay_ext_mps2", "az_ext_mps2"};
  std::array<std::string, 4> n = {"n1_rpm", "n2_rpm", "n3_rpm", "n4_rpm"};
};

struct FlightLog {
  std::string source;
  std::size_t first_data_line = 0;
  std::vector<double> t_s;
  std::vector<double> h_m;
  std::array<std::vector<double>, 3> v_W;        ///< empty in a hover log [m/s]
  std::array<std::vector<double>, 4> q_WB;       ///< w, x, y, z; empty in a hover log
  std::array<std::vector<double>, 3> a_ext_W;    ///< x, y empty in a hover log [m/s²]
  std::array<std::vector<double>, 4> n_rpm;

  [[nodiscard]] std::size_t size() const noexcept { return t_s.size(); }
};

/// A full flight log (for the drag table): every column of FlightColumns.
[[nodiscard]] FlightLog readFlightLog(const std::filesystem::path& file,
                                      const FlightColumns& columns = {},
                                      const ColumnDefinitions& definitions = {});

/// A hover-descent log (for F_G in flight, paper eq. 10): only t, h, the world-z external
/// acceleration and the rotor speeds are read.
[[nodiscard]] FlightLog readHoverLog(const std::filesystem::path& file,
                                     const FlightColumns& columns = {},
                                     const ColumnDefinitions& definitions = {});

}  // namespace geaware::ident

namespace geaware::io {
struct MappedFlight;
}

namespace geaware::ident {

/// A flight log made from a mapped autopilot log (io::mapFlight: ENU/FLU, SI, one time axis),
/// with the external acceleration computed as the paper's observer does (eq. 3, unfiltered):
/// a_ext = R_WB·f_IMU − z_B·k_T·Σn²/m, with the mass and k_T given. Rows where every rotor reads
/// 0 rpm (on the ground, disarmed) are dropped and counted in `notes`. So are the rows where the
/// ground holds the vehicle up: those where m·(R_WB·f_IMU)_z/Σn² is over twice its lower
/// quartile over the rows with rotors turning (its value in flight, k_T·(1 + F_G)) — too little
/// thrust to fly — and, when those and the stopped rows last kMinRestingS, their median height
/// being the height the vehicle rests at, the rows with rotors turning within
/// kGroundContactMarginM of it (spinning up before a take-off or down after a landing). The ground's support would otherwise be read as
/// a ground effect of tens of percent or more. (A log less than a quarter airborne defeats the
/// quartile; so does one that flies lower than it rests.)
struct MappedFlightLog {
  FlightLog log;
  std::vector<std::string> notes;
};
/// `flight` must hold height, specific force, attitude and 4 rotor speeds (velocity optional).
/// Throws std::invalid_argument naming what is missing.
[[nodiscard]] MappedFlightLog flightLogFromMapped(const io::MappedFlight& flight, double mass_kg,
                                                  double k_T_N_per_rpm2);

/// Height above the resting height within which a vehicle with turning rotors is taken to stand
/// on the ground [m] (a range finder's noise is about 1 cm; airborne, the vehicle leaves it within
/// a fraction of a second).
inline constexpr double kGroundContactMarginM = 0.02;
/// Rows held up by the ground make a resting height only when they last this long in all [s].
inline constexpr double kMinRestingS = 1.0;

/// Rotor speeds of a vehicle that logs no rotor speed, from its throttles (flight.throttle, 0…1
/// each) through the vehicle's ESC throttle curve and, when the curve has a voltage dependence
/// (reference_voltage_V > 0), the logged battery voltage: n_i = model::ThrottleCurve::speedRpm(
/// t_i, V) (docs/identification.md, "Vehicles without rotor-speed telemetry"). A stopped motor
/// (io::kStoppedThrottle, any negative throttle) turns at 0 rpm, and so does every motor where the
/// flight is disarmed (flight.armed below 0.5, when mapped); a throttle above 1 is taken as 1 and
/// counted; a gap in the voltage (NaN) takes the curve at its reference voltage, counted. The curve gives
/// steady speeds: a motor's lag (tens of ms) is not modelled, so fast throttle changes add noise.
/// Fills flight.n_rpm and flight.rotor_fields. Throws std::invalid_argument when the flight has
/// no throttles or the curve is not a curve (c2, c1, c0 all 0).
struct ThrottleConversion {
  std::vector<std::string> notes;
  std::vector<std::string> warnings;
};
[[nodiscard]] ThrottleConversion rotorSpeedsFromThrottle(io::MappedFlight& flight,
                                                         const model::ThrottleCurveParams& curve);

}  // namespace geaware::ident
