// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Which topic and field of a log is what (issue 11 item 2, the basis): a small YAML file per log
// family (config/log-maps/NAME.yaml, built in by name: `--map px4`; or any file) naming the
// topic, fields, unit and frame of the height, specific force, gyro, attitude, velocity, rotor
// speed and battery voltage; and mapFlight, which takes those channels from a log into SI units,
// geaware's frames (ENU world, FLU body; PX4 and ArduPilot log NED/FRD) and one time axis.
// docs/identification.md "Mapping a log".

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "geaware/io/column_expression.hpp"
#include "geaware/io/log_channels.hpp"

namespace geaware::io {

/// One mapped quantity: `fields` of one topic (each an expression, io/column_expression.hpp:
/// `esc[2].esc_rpm`, `z[mm]`, `delta(vz[m/s]) / delta(t[s])`), scaled by `scale` into SI (rpm
/// for rotor speeds, rad for Euler angles) from `unit` — a field that writes its own units is
/// converted by them instead — in `frame` ("scalar", "world", "body", "quaternion" w x y z world
/// from body, "euler": roll, pitch, yaw of the body in the world (z-y-x), "world_z": a world z
/// coordinate, read as a height).
struct MappedChannel {
  std::string topic;
  unsigned instance = 0;
  std::vector<std::string> fields;
  /// The topic instance of each field (same length as fields): `instance` for all, or, with
  /// `instances: [0, 1, 2, 3]` and one field, that field of each instance (ArduPilot's ESC).
  std::vector<unsigned> field_instances;
  std::vector<ColumnExpression> expressions;  ///< fields, parsed
  /// Per field: whether it comes from --column/--const (then in the column's unit, the log's
  /// units used) rather than from the map file.
  std::vector<bool> from_option;
  std::string unit;
  double scale = 1.0;
  std::string frame = "scalar";
  /// A log without this channel is read without it (a note says so); a required channel
  /// missing is an error naming the map, the channel and the fields the log has.
  bool optional = false;
  // Rotor speeds only (docs/identification.md, "Motor order and pole pairs"):
  /// The log's motor number of each field (1-based), as numbers, or read from the log: a field
  /// of the topic or `param:NAME` (a logged parameter) holding motor_base for motor 1 (PX4's
  /// esc[i].actuator_function, 101 = Motor1; ArduPilot's SERVOn_FUNCTION, 33 = Motor1). Empty:
  /// field k is motor k + 1.
  std::vector<std::string> motor_of_field;
  double motor_base = 1.0;
  /// geaware's rotor number (model::Mixer: 1 front-right, 2 rear-left, 3 front-left, 4
  /// rear-right) of each of the log's motors 1…N. Empty: the same numbers.
  std::vector<unsigned> rotor_of_motor;
  /// Magnet pole pairs of the motors: a logged electrical speed divided by it is the rotor's
  /// (1: the log gives mechanical rpm).
  double pole_pairs = 1.0;
  // Throttles only (docs/identification.md, "Vehicles without rotor-speed telemetry"); the motor
  // order above applies to them as to rotor speeds:
  /// The raw values that are throttle 0 and 1 (PWM 1000 and 2000 µs, a Crazyflie's 0 and 65535,
  /// PX4's actuator_motors 0 and 1): throttle = (raw − range[0]) / (range[1] − range[0]).
  std::array<double, 2> range{0.0, 1.0};
  /// Logged parameters that hold the range (ArduPilot's MOT_PWM_MIN and MOT_PWM_MAX); used when
  /// the log has both and they make a range, else `range` (a note says which).
  std::vector<std::string> range_params;
  /// A NaN throttle is a stopped motor (PX4 logs NaN for a disarmed motor), not a missing value,
  /// and throttle 0 an armed motor at idle; otherwise throttle 0 and below are a stopped motor.
  bool nan_is_stopped = false;
  int line = 0;  ///< line in the map file
};

struct LogMap {
  std::string name;    ///< "px4", or the file's stem
  std::string source;  ///< the file (or "built-in map px4 (config/log-maps/px4.yaml)")
  std::string family;
  std::string frames;  ///< "ned_frd" or "enu_flu"
  /// A field (name matched without case) that is the time of every mapped topic, and its scale
  /// to seconds (`time: {field: timestamp, unit: ms}`); empty: the reader's time axes.
  std::string time_field;
  double time_scale = 1.0;
  /// height, specific_force, gyro, attitude, velocity, rotor_speed, throttle, armed,
  /// battery_voltage (any subset).
  std::map<std::string, MappedChannel> channels;
};

/// The names of the built-in maps ("px4").
[[nodiscard]] std::vector<std::string> builtinLogMapNames();
/// A built-in map by name, or a map file. Throws ConfigError naming the file, the line and the
/// key (unknown channel, wrong field count, unknown unit or frame), or std::runtime_error for a
/// name that is neither.
[[nodiscard]] LogMap loadLogMap(const std::string& name_or_file);
[[nodiscard]] LogMap parseLogMap(const std::string& text, const std::string& source, const std::string& name);

/// The flight columns `--column` and `--const` may define with a map, each with its channel and
/// component: h_m (height), a_x_mps2 … (specific_force), gyro_x_radps …, qw … qz (attitude as a
/// quaternion), vx_mps … (velocity), n1_rpm … n8_rpm (rotor_speed), throttle1 … throttle8 (throttle,
/// each a fraction 0…1; geaware's rotor order applies to the map's fields, not to these), vbat_V
/// (battery_voltage).
[[nodiscard]] std::vector<std::string> mappedColumnNames();
/// Puts each definition into `map` in place of the map's field (the channel is created when the
/// map has none: then every component of it must be defined). Values of a definition are in
/// the map's frames. Throws ExpressionError naming the option.
void applyColumnDefinitions(LogMap& map, const std::vector<ColumnDefinition>& definitions);

/// The values of `e` on `log`: its fields resolved in `topic`/`instance` (a field may name its
/// own: `sensor_combined.gyro_rad[0]`, `IMU[1].GyrX`; with no topic, the one topic that has
/// it), on that topic's time axis; a constant has no topic and one value. `target` is the unit
/// of the result (io/column_expression.hpp). Throws MissingFieldError (a field or topic the log
/// lacks, naming the fields it has) or LogError.
struct EvaluatedField {
  const Topic* topic = nullptr;
  std::vector<double> values;
};
class MissingFieldError : public LogError {
 public:
  using LogError::LogError;
};
[[nodiscard]] EvaluatedField evaluateOnLog(const ColumnExpression& e, const LogData& log, const std::string& topic,
                                           unsigned instance, const Unit* target, const std::string& target_name,
                                           bool log_units);

/// The mapped channels of one log on one time axis, in SI units and geaware's frames.
struct MappedFlight {
  std::string source;
  std::string time_base;                 ///< "esc_status[0]": the slowest channel asked for
  std::vector<double> t_s;
  std::vector<double> h_m;
  std::array<std::vector<double>, 3> f_B_mps2;      ///< specific force, FLU body
  std::array<std::vector<double>, 3> gyro_B_radps;  ///< FLU body
  std::array<std::vector<double>, 4> q_WB;          ///< w, x, y, z: ENU world from FLU body
  std::array<std::vector<double>, 3> v_W_mps;       ///< ENU
  std::vector<std::vector<double>> n_rpm;           ///< one vector per rotor, geaware's order
  std::vector<std::string> rotor_fields;            ///< the log field of each rotor (n_rpm's order)
  /// Throttle of each rotor, 0…1, or kStoppedThrottle for a stopped motor (geaware's order),
  /// when asked for.
  std::vector<std::vector<double>> throttle;
  std::vector<std::string> throttle_fields;         ///< the log field of each rotor (throttle's order)
  /// Arming state, 1 armed and 0 disarmed (interpolated: below 0.5 is disarmed), when asked for.
  std::vector<double> armed;
  std::vector<double> vbat_V;             ///< NaN where the battery's log has a gap (the row is kept)
  std::vector<std::string> notes;        ///< rates, time base, rows dropped
  /// Channels logged slower than kMinFitRateHz (each named with its rate).
  std::vector<std::string> warnings;
  [[nodiscard]] std::size_t size() const noexcept { return t_s.size(); }
};

/// MappedFlight::throttle of a stopped motor: a NaN where the map's nan_is_stopped says so (PX4
/// logs NaN for a disarmed motor and 0 for one armed at idle), else a raw value at or below the
/// range's throttle 0 (a disarmed ArduPilot output, a Crazyflie motor at 0).
inline constexpr double kStoppedThrottle = -1.0;

/// A mapped channel logged slower than this [Hz] is named in MappedFlight::warnings: a quadrotor's
/// thrust and attitude change within tenths of a second, so a fit sampled slower sees them aliased.
inline constexpr double kMinFitRateHz = 20.0;

/// The channels `wanted` (names of LogMap::channels) of `log`: every one sampled at the times of
/// the slowest of them (linear interpolation, the quaternion normalised; rows outside any
/// channel's time span or with a NaN are dropped and counted in the notes); rotor speeds in
/// geaware's rotor order, mechanical. An optional channel the log lacks is left out (a note).
/// Throws LogError naming the log, the map and the missing channel, topic or field (with the
/// fields the log has).
[[nodiscard]] MappedFlight mapFlight(const LogData& log, const LogMap& map, const std::vector<std::string>& wanted);

/// Whether `log` has channel `name` of `map`: the map names it and the log has the fields of its
/// first component (a constant counts).
[[nodiscard]] bool logHasChannel(const LogData& log, const LogMap& map, const std::string& name);

}  // namespace geaware::io
