#include "geaware/experiments/flight_log.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "geaware/model/units.hpp"

namespace geaware::experiments {
namespace {

// Buffer of the log: rows are formatted into it and it is written out when less than
// kRowReserve bytes are left (a row is at most ~100 numbers of ≤ 25 characters).
constexpr std::size_t kBufferBytes = std::size_t{1} << 18;
constexpr std::size_t kRowReserve = 8192;

/// Appends numbers separated by commas at a raw pointer (the caller guarantees the space).
class RowWriter {
 public:
  explicit RowWriter(char* p) noexcept : p_(p), start_(p) {}
  /// A value as the shortest text that reads back to the same float32: 6–9 significant
  /// digits, far below any sensor's noise, and about half the size and time of a double's.
  void num(double v) noexcept {
    sep();
    p_ = fmt::format_to(p_, FMT_COMPILE("{}"), static_cast<float>(v));
  }
  /// A value as the shortest text that reads back to the same double (times: a float32 would
  /// lose the 1 ms plant step after a few hours).
  void exact(double v) noexcept {
    sep();
    p_ = fmt::format_to(p_, FMT_COMPILE("{}"), v);
  }
  void integer(std::uint64_t v) noexcept {
    sep();
    p_ = fmt::format_to(p_, FMT_COMPILE("{}"), v);
  }
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
  void end() noexcept { *p_++ = '\n'; }
  [[nodiscard]] std::size_t size() const noexcept { return static_cast<std::size_t>(p_ - start_); }
  [[nodiscard]] int fields() const noexcept { return fields_; }

 private:
  void sep() noexcept {
    if (fields_++ > 0) *p_++ = ',';
  }
  char* p_;
  char* start_;
  int fields_ = 0;
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
      "n_true_4_rpm", "throttle_1", "throttle_2", "throttle_3", "throttle_4",
      // control::ControllerFlag bits
      "flags"};
  return columns;
}

CsvFlightLog::CsvFlightLog(const std::filesystem::path& file)
    : path_(file), file_(std::fopen(file.c_str(), "wb")) {
  if (file_ == nullptr) {
    throw std::runtime_error(file.string() + ": cannot open for writing (" + std::strerror(errno) +
                             ")");
  }
  buffer_.resize(kBufferBytes);
  std::string header;
  for (std::string_view c : flightLogColumns()) {
    if (!header.empty()) header += ',';
    header += c;
  }
  header += '\n';
  std::memcpy(buffer_.data(), header.data(), header.size());
  used_ = header.size();
}

CsvFlightLog::~CsvFlightLog() {
  if (file_ != nullptr) std::fclose(file_);
}

void CsvFlightLog::flush() noexcept {
  if (used_ == 0 || file_ == nullptr) return;
  if (std::fwrite(buffer_.data(), 1, used_, file_) != used_) failed_ = true;
  used_ = 0;
}

void CsvFlightLog::onTick(const FlightTick& k) noexcept {
  if (file_ == nullptr) return;
  if (buffer_.size() - used_ < kRowReserve) flush();
  RowWriter w(buffer_.data() + used_);
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
  w.integer(out.flags);
  w.end();
  used_ += w.size();
  ++rows_;
}

void CsvFlightLog::finish(const FlightResult& /*result*/) { close(); }

void CsvFlightLog::close() {
  if (file_ == nullptr) return;
  flush();
  const bool bad = failed_ || std::ferror(file_) != 0;
  const int rc = std::fclose(file_);
  file_ = nullptr;
  if (bad || rc != 0) throw std::runtime_error(path_.string() + ": write failed");
}

}  // namespace geaware::experiments
