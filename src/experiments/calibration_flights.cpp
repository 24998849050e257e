// SPDX-License-Identifier: BSD-3-Clause
#include "calibration_flights.hpp"

#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <Eigen/Geometry>

#include "geaware/ident/identify.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments::detail {
namespace {

/// A constant reference: hold a point (the hover flight).
class HoldPoint final : public traj::Trajectory {
 public:
  HoldPoint(const Eigen::Vector3d& p_W, double duration_s) : duration_s_(duration_s) {
    out_.p_W = p_W;
  }
  [[nodiscard]] traj::FlatOutput sample(double /*t_s*/) const noexcept override { return out_; }
  [[nodiscard]] double duration() const noexcept override { return duration_s_; }

 private:
  traj::FlatOutput out_;
  double duration_s_;
};

/// What a team logs for `geaware identify flight`, from the controller's own inputs on every
/// control tick of the trajectory with a valid ranger height: the columns CsvFlightLog writes
/// (ã_ext = R·f_B − z_B·k_T·Σn²/m with the belief's k_T and mass). Reads nothing of the truth.
/// The IMU samples of a calibration flight (body axes), beside its ident::FlightLog.
struct ImuLog {
  std::array<std::vector<double>, 3> gyro_B;   ///< [rad/s]
  std::array<std::vector<double>, 3> accel_B;  ///< [m/s²]
};

class IdentLogCollector final : public FlightObserver {
 public:
  IdentLogCollector(const model::VehicleParams& belief, std::string source, std::size_t reserve)
      : k_T_(belief.rotor.k_T_N_per_rpm2), mass_kg_(belief.mass_kg) {
    log_.source = std::move(source);
    log_.t_s.reserve(reserve);
    log_.h_m.reserve(reserve);
    for (auto& c : log_.v_W) c.reserve(reserve);
    for (auto& c : log_.q_WB) c.reserve(reserve);
    for (auto& c : log_.a_ext_W) c.reserve(reserve);
    for (auto& c : log_.n_rpm) c.reserve(reserve);
    for (auto& c : imu_.gyro_B) c.reserve(reserve);
    for (auto& c : imu_.accel_B) c.reserve(reserve);
  }

  void onTick(const FlightTick& k) noexcept override {
    const control::ControllerInput& in = k.input;
    if (!k.controller_active || !k.in_trajectory || !in.height_valid) return;
    if (log_.t_s.size() == log_.t_s.capacity()) return;  // no allocation inside the loop
    const Eigen::Matrix3d R = in.estimate.q_WB.toRotationMatrix();
    const double thrust_N = k_T_ * in.rotor_speeds_rpm.squaredNorm();
    const Eigen::Vector3d a_ext = R * in.accel_B - R.col(2) * (thrust_N / mass_kg_);
    log_.t_s.push_back(k.t_s);
    log_.h_m.push_back(in.height_m);
    const Eigen::Quaterniond& q = in.estimate.q_WB;
    const double qc[4] = {q.w(), q.x(), q.y(), q.z()};
    for (std::size_t a = 0; a < 3; ++a) {
      const auto i = static_cast<Eigen::Index>(a);
      log_.v_W[a].push_back(in.estimate.v_W(i));
      log_.a_ext_W[a].push_back(a_ext(i));
      imu_.gyro_B[a].push_back(in.gyro_B(i));
      imu_.accel_B[a].push_back(in.accel_B(i));
    }
    for (std::size_t a = 0; a < 4; ++a) {
      log_.q_WB[a].push_back(qc[a]);
      log_.n_rpm[a].push_back(in.rotor_speeds_rpm(static_cast<Eigen::Index>(a)));
    }
  }

  [[nodiscard]] const ident::FlightLog& log() const noexcept { return log_; }
  [[nodiscard]] const ImuLog& imu() const noexcept { return imu_; }

 private:
  double k_T_;
  double mass_kg_;
  ident::FlightLog log_;
  ImuLog imu_;  // the IMU samples the controller was given, at the log's times
};

/// Flies `trajectory` with `belief` in the world and returns the flight's record and its log.
/// Throws std::runtime_error when the flight strikes the ground: a team would not use it.
std::tuple<CalibrationFlight, ident::FlightLog, ImuLog> fly(
    const model::VehicleParams& belief, const CalibrationWorld& world,
    const CalibrationSweeps& sweeps, std::shared_ptr<const traj::Trajectory> trajectory,
    std::uint64_t seed, std::string purpose) {
  FlightScenario f = world.flights;
  f.vehicle = belief;
  f.lattice.reset();  // the ranger's estimator for the belief's geometry
  f.trajectory = std::move(trajectory);
  f.controller = sweeps.flight_controller;
  f.residual.reset();
  f.seed = seed;
  f.start_hover_s = sweeps.flight_start_hover_s;
  f.settle_s = 0.0;
  f.loop = LoopMode::kClosed;
  const double rate_hz = f.controller.rate_hz;
  const auto ticks = static_cast<std::size_t>(f.trajectory->duration() * rate_hz) + 2;
  IdentLogCollector collector(belief, "calibration flight: " + purpose, ticks);
  const FlightResult r = runFlight(f, &collector);
  CalibrationFlight c;
  c.purpose = std::move(purpose);
  c.reference_height_m = f.trajectory->sample(0.0).p_W.z();
  c.samples = collector.log().size();
  double h_sum = 0.0;
  for (double h : collector.log().h_m) h_sum += h;
  c.mean_height_m = c.samples > 0 ? h_sum / static_cast<double>(c.samples) : 0.0;
  c.struck = r.crash.has_value();
  c.crash = r.crash_description;
  c.guard_active_s = r.guard_active_s.value_or(0.0);
  if (c.struck) {
    throw std::runtime_error(fmt::format("calibration: the {} flight ({}) struck the ground: {}",
                                         c.purpose, control::configurationName(f.controller),
                                         c.crash));
  }
  return {c, collector.log(), collector.imu()};
}

}  // namespace

HoverCalibration calibrateHover(const model::VehicleParams& belief, const CalibrationWorld& world,
                                const CalibrationSweeps& sweeps) {
  auto hold = std::make_shared<HoldPoint>(Eigen::Vector3d(0.0, 0.0, sweeps.hover_height_m),
                                          sweeps.hover_s);
  auto [flight, log, imu] = fly(belief, world, sweeps, std::move(hold), 50 + sweeps.seed,
                                fmt::format("hover k_T at {:g} m", sweeps.hover_height_m));
  HoverCalibration h;
  h.fit = ident::fitHoverThrust(log, belief);
  h.imu_noise = ident::fitImuNoise(log.t_s, imu.gyro_B, imu.accel_B);
  h.flight = std::move(flight);
  return h;
}

DragCalibration calibrateDrag(const model::VehicleParams& belief, const CalibrationWorld& world,
                              const CalibrationSweeps& sweeps) {
  DragCalibration d;
  ident::IdentifyOptions options;
  options.height_bands = 1;  // one flight, one height
  std::uint64_t k = 0;
  for (double h : sweeps.drag_heights_m) {
    traj::LemniscateParams p;
    p.half_extent_x_m = sweeps.drag_half_extent_x_m;
    p.half_extent_y_m = sweeps.drag_half_extent_y_m;
    p.height_m = h;
    p.peak_speed_mps = sweeps.drag_speed_mps;
    p.laps = 1;
    [[maybe_unused]] auto [flight, log, imu] = fly(belief, world, sweeps, std::make_shared<traj::Lemniscate>(p),
                             60 + sweeps.seed + k++, fmt::format("drag at {:g} m", h));
    const ident::IdentifyResult id = ident::identifyFlight(log, belief, options);
    const ident::DragFit& fit = *id.fits.drag;
    d.warnings.insert(d.warnings.end(), fit.warnings.begin(), fit.warnings.end());
    d.bands.push_back(fit.bands.front());
    d.flights.push_back(std::move(flight));
  }
  return d;
}

}  // namespace geaware::experiments::detail
