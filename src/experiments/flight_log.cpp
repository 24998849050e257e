// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/flight_log.hpp"

#include <Eigen/Geometry>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "geaware/model/units.hpp"

namespace geaware::experiments {
namespace {

/// Appends the cells of one row to the CSV writer: values as float32 text, times exactly.
class RowWriter {
 public:
  explicit RowWriter(io::CsvWriter& csv) noexcept : csv_(csv) {}
  void num(double v) noexcept { csv_.single(v); }
  void exact(double v) noexcept { csv_.exact(v); }
  void integer(std::uint64_t v) noexcept { csv_.integer(v); }
  void vec3(const Eigen::Vector3d& v) noexcept {
    num(v.x());
    num(v.y());
    num(v.z());
  }
  void quat(const Eigen::Quaterniond& q) noexcept {
    num(q.w());
    num(q.x());
    num(q.y());
    num(q.z());
  }
  void end() noexcept { csv_.endRow(); }

 private:
  io::CsvWriter& csv_;
};

}  // namespace

const std::vector<std::string_view>& flightLogColumns() {
  static const std::vector<std::string_view> columns = {
      // time and phase
      "t_s", "t_traj_s", "controller_active", "in_trajectory",
      // reference (flat outputs)
      "ref_x_m", "ref_y_m", "ref_z_m", "ref_vx_mps", "ref_vy_mps", "ref_vz_mps", "ref_ax_mps2",
      "ref_ay_mps2", "ref_az_mps2", "ref_yaw_rad",
      // estimate (ESKF), what the controller flies on
      "est_x_m", "est_y_m", "est_z_m", "est_vx_mps", "est_vy_mps", "est_vz_mps", "est_qw", "est_qx",
      "est_qy", "est_qz", "gyro_x_radps", "gyro_y_radps", "gyro_z_radps", "accel_x_mps2",
      "accel_y_mps2", "accel_z_mps2",
      // truth (simulator), never seen by the controller
      "true_x_m", "true_y_m", "true_z_m", "true_vx_mps", "true_vy_mps", "true_vz_mps", "true_qw",
      "true_qx", "true_qy", "true_qz", "true_wx_radps", "true_wy_radps", "true_wz_radps",
      // tracking error, reference − truth
      "err_x_m", "err_y_m", "err_z_m", "err_norm_m",
      // heights
      "h_true_m", "h_meas_m", "h_meas_valid", "h_used_m",
      // commands
      "a_des_x_mps2", "a_des_y_mps2", "a_des_z_mps2", "thrust_des_N", "q_des_w", "q_des_x",
      "q_des_y", "q_des_z", "att_err_deg", "w_des_x_radps", "w_des_y_radps", "w_des_z_radps",
      "tau_des_x_Nm", "tau_des_y_Nm", "tau_des_z_Nm", "tau_hat_x_Nm", "tau_hat_y_Nm",
      "tau_hat_z_Nm",
      // rotors
      "n_des_1_rpm", "n_des_2_rpm", "n_des_3_rpm", "n_des_4_rpm", "n_meas_1_rpm", "n_meas_2_rpm",
      "n_meas_3_rpm", "n_meas_4_rpm", "n_true_1_rpm", "n_true_2_rpm", "n_true_3_rpm",
      "n_true_4_rpm", "throttle_1", "throttle_2", "throttle_3", "throttle_4", "battery_V",
      // control::ControllerFlag bits
      "flags",
      // the disturbance observer (paper eq. 6), filtered: ã_ext (world), τ̃_ext (body), F̃_G
      "dob_valid", "dob_ax_mps2", "dob_ay_mps2", "dob_az_mps2", "dob_tau_x_Nm", "dob_tau_y_Nm",
      "dob_tau_z_Nm", "dob_f_g",
      // geaware's additions (docs/controller.md): the residual fed forward, the integral term,
      // the height aimed at, the guard's bound on the vertical command and whether it acted
      "dob_ff_x_mps2", "dob_ff_y_mps2", "dob_ff_z_mps2", "int_x_mps2", "int_y_mps2", "int_z_mps2",
      "z_cmd_m", "guard_az_min_mps2", "guard_active",
      // what `geaware identify flight` reads (docs/identification.md, "Flight log"): the
      // controller-side height, velocity, attitude and rotor telemetry, and the external
      // acceleration ã_ext = R_WB·f_B − z_B·k_T·Σn²/m of the nominal vehicle (unfiltered)
      "h_m", "vx_mps", "vy_mps", "vz_mps", "qw", "qx", "qy", "qz", "ax_ext_mps2", "ay_ext_mps2",
      "az_ext_mps2", "n1_rpm", "n2_rpm", "n3_rpm", "n4_rpm",
      // estimation::EskfFlag bits (1 pose stale, 2 IMU clipped, 4 pose rejected) and the
      // injected faults active (bit i: the scenario's fault i; experiments/faults.hpp)
      "eskf_flags", "fault_bits"};
  return columns;
}

namespace {

/// The comment lines that precede the header, each line ended.
std::string commentLines(std::string_view comment) {
  std::string text(comment);
  if (!text.empty() && text.back() != '\n') text += '\n';
  return text;
}

}  // namespace

CsvFlightLog::CsvFlightLog(const std::filesystem::path& file, const model::VehicleParams& vehicle,
                           std::string_view header_comment)
    : path_(file),
      file_(file.string(), "the flight log"),
      csv_((file_.write(commentLines(header_comment)), file_.stream()), "the flight log '" + file.string() + "'",
           flightLogColumns()),
      k_T_N_per_rpm2_(vehicle.rotor.k_T_N_per_rpm2),
      mass_kg_(vehicle.mass_kg) {}

CsvFlightLog::~CsvFlightLog() = default;

void CsvFlightLog::onTick(const FlightTick& k) noexcept {
  RowWriter w(csv_);
  const control::ControllerInput& in = k.input;
  const control::ControllerOutput& out = k.output;
  const traj::FlatOutput& ref = in.reference;
  const sim::PlantState& x = k.truth;
  w.exact(k.t_s);
  w.exact(k.t_traj_s);
  w.integer(k.controller_active ? 1 : 0);
  w.integer(k.in_trajectory ? 1 : 0);
  w.vec3(ref.p_W);
  w.vec3(ref.v_W);
  w.vec3(ref.a_W);
  w.num(ref.yaw_rad);
  w.vec3(in.estimate.p_W);
  w.vec3(in.estimate.v_W);
  w.quat(in.estimate.q_WB);
  w.vec3(in.gyro_B);
  w.vec3(in.accel_B);
  w.vec3(x.p_W);
  w.vec3(x.v_W);
  w.quat(x.q_WB);
  w.vec3(x.w_B);
  const Eigen::Vector3d err = ref.p_W - x.p_W;
  w.vec3(err);
  w.num(err.norm());
  w.num(k.true_height_m);
  w.num(in.height_m);
  w.integer(in.height_valid ? 1 : 0);
  w.num(out.height_used_m);
  w.vec3(out.a_des_W);
  w.num(out.thrust_des_N);
  w.quat(out.q_des_WB);
  w.num(k.attitude_error_rad / model::kDegToRad);
  w.vec3(out.w_des_B);
  w.vec3(out.tau_des_B);
  w.vec3(out.tau_hat_B);
  for (int i = 0; i < 4; ++i) w.num(out.n_des_rpm(i));
  for (int i = 0; i < 4; ++i) w.num(in.rotor_speeds_rpm(i));
  for (double n : x.n_rpm) w.num(n);
  for (double t : k.throttle) w.num(t);
  w.num(in.battery_voltage_V);
  w.integer(out.flags);
  const estimation::DisturbanceEstimate& d = k.disturbance;
  w.integer(d.valid ? 1 : 0);
  w.vec3(d.a_ext_W);
  w.vec3(d.tau_ext_B);
  w.num(d.f_g_valid ? d.f_g_ratio : 0.0);
  w.vec3(out.a_dob_W);
  w.vec3(out.a_int_W);
  w.num(out.z_cmd_m);
  w.num(out.guard_min_accel_z_mps2);
  w.integer((out.flags & control::kFlagClearanceGuard) != 0 ? 1 : 0);
  // The identification columns.
  w.num(in.height_m);
  w.vec3(in.estimate.v_W);
  w.quat(in.estimate.q_WB);
  const Eigen::Matrix3d R = in.estimate.q_WB.toRotationMatrix();
  const double thrust_N = k_T_N_per_rpm2_ * in.rotor_speeds_rpm.squaredNorm();
  w.vec3(R * in.accel_B - R.col(2) * (thrust_N / mass_kg_));
  for (int i = 0; i < 4; ++i) w.num(in.rotor_speeds_rpm(i));
  w.integer(k.eskf_flags);
  w.integer(k.fault_bits);
  w.end();
}

void CsvFlightLog::finish(const FlightResult& /*result*/) { close(); }

void CsvFlightLog::close() {
  csv_.close();
  file_.commit();
}

}  // namespace geaware::experiments
