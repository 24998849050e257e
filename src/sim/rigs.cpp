// SPDX-License-Identifier: BSD-3-Clause
// The paper's virtual test rigs and the calibration of the truth aerodynamics against the
// paper's measurements (docs/paper-facts.md). See docs/sim-aerodynamics.md.

#include "geaware/sim/rigs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "geaware/model/field_check.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/motor.hpp"
#include "geaware/model/units.hpp"

namespace geaware::sim {
namespace {

// The rigs print values with 6 significant digits, in their parameter errors and sweep errors.
constexpr int kDigits = 6;

std::string show(double v) { return model::formatValue(v, kDigits); }

[[noreturn]] void throwErrors(const char* what, const std::vector<model::FieldError>& errors) {
  throw std::invalid_argument(model::describeErrors(std::string(what) + ": invalid parameters:", errors));
}

void requireList(const std::vector<double>& v, const char* name, double lo, double hi,
                 bool lo_open) {
  if (v.empty()) throw std::invalid_argument(std::string("platform sweep: ") + name + " is empty");
  for (double x : v) {
    const bool ok = std::isfinite(x) && (lo_open ? x > lo : x >= lo) && x <= hi;
    if (!ok) {
      throw std::invalid_argument(std::string("platform sweep: ") + name + " value " + show(x) +
                                  " is outside " + (lo_open ? "(" : "[") + show(lo) + ", " +
                                  show(hi) + "]");
    }
  }
}

}  // namespace


RotorGeometry rigGeometry(const model::VehicleParams& vehicle) {
  RotorGeometry g;
  g.position_B = model::Mixer::rotorPositions_B(vehicle.diagonal_rotor_distance_m);
  const Eigen::Vector4d& yaw = model::Mixer::yawSigns();
  for (std::size_t i = 0; i < 4; ++i) {
    g.spin[i] = yaw[static_cast<Eigen::Index>(i)];
    g.k_T_N_per_rpm2[i] = vehicle.rotor.k_T_N_per_rpm2;
    g.k_I_Nm_per_rpm2[i] = vehicle.rotor.k_I_Nm_per_rpm2;
  }
  g.radius_m = vehicle.propeller_radius_m;
  return g;
}

// ---------------------------------------------------------------------------------------------
// Platform

std::vector<model::FieldError> PlatformParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e, kDigits);
  using enum model::LowerBound;
  c.range("platform.force_noise_N", force_noise_N, 0.0, 1e3, kInclusive, "N");
  c.range("platform.torque_noise_Nm", torque_noise_Nm, 0.0, 1e3, kInclusive, "N·m");
  c.integerRange("platform.samples_per_setpoint", samples_per_setpoint, 1, 1'000'000);
  c.range("platform.sample_period_s", sample_period_s, 1e-6, 100.0, kInclusive, "s");
  c.range("platform.settle_time_s", settle_time_s, 0.0, 1e4, kInclusive, "s");
  return e;
}

std::size_t PlatformSweep::setpointCount() const noexcept {
  std::size_t per = 0;
  if (rpm_diffs.empty()) {
    per = 1;
  } else {
    for (double d : rpm_diffs) per += (d == 0.0) ? 1 : diff_axes.size();
  }
  return heights_m.size() * tilts_deg.size() * rpm.size() * per;
}

ForceTorquePlatform::ForceTorquePlatform(const RotorGeometry& geometry, const RotorAeroParams& aero,
                                         const PlatformParams& params)
    : aero_(geometry, aero), params_(params) {
  const auto errors = params.validate();
  if (!errors.empty()) throwErrors("ForceTorquePlatform", errors);
}

RotorSurroundings ForceTorquePlatform::surroundings(double h_m, double tilt_deg) const noexcept {
  RotorSurroundings s;
  const double t = std::tan(tilt_deg * model::kDegToRad);
  const double c = std::cos(tilt_deg * model::kDegToRad);
  const double sn = std::sin(tilt_deg * model::kDegToRad);
  for (std::size_t i = 0; i < 4; ++i) {
    // Vertical distance (the simulator's convention, along −z_W; the vehicle is level here).
    s.ground_distance_m[i] = h_m - aero_.geometry().position_B[i].x() * t;
    // The board rises toward +x: its upward normal leans toward −x.
    s.ground_normal_W[i] = Eigen::Vector3d(-sn, 0.0, c);
  }
  return s;
}

RotorAeroOutput ForceTorquePlatform::wrench(double h_m, double tilt_deg,
                                            const std::array<double, 4>& n_rpm) const noexcept {
  return aero_.compute(n_rpm, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
                       Eigen::Vector3d::Zero(), surroundings(h_m, tilt_deg));
}

std::size_t ForceTorquePlatform::sweep(
    const PlatformSweep& sw, std::uint64_t seed,
    const std::function<void(const PlatformRow&)>& sink,
    const std::function<void(std::size_t, std::size_t)>& progress) const {
  requireList(sw.heights_m, "heights", 0.0, 1e4, true);
  requireList(sw.tilts_deg, "tilts", -44.999, 44.999, false);
  requireList(sw.rpm, "rpm", 0.0, 1e6, false);
  for (double d : sw.rpm_diffs) {
    if (!std::isfinite(d) || std::abs(d) > 1e6)
      throw std::invalid_argument("platform sweep: rpm difference " + show(d) + " is not finite");
  }
  if (!sw.rpm_diffs.empty() && sw.diff_axes.empty())
    throw std::invalid_argument("platform sweep: rpm differences given but no axis");
  if (!sink) throw std::invalid_argument("platform sweep: no row sink");

  NoiseSource noise = NoiseSource::fromEngineSeed(seed);
  const Eigen::Matrix4d& A = model::Mixer::allocationPattern();
  const std::size_t total = sw.setpointCount();
  std::size_t done = 0;
  std::size_t rows = 0;
  // Time from indices (no accumulated rounding): setpoint k starts at k·(samples·Δt + settle).
  const double setpoint_s =
      params_.samples_per_setpoint * params_.sample_period_s + params_.settle_time_s;
  PlatformRow row;

  const auto visit = [&](double h, double tilt, const std::array<double, 4>& n) {
    for (double ni : n) {
      if (!(ni >= 0.0))
        throw std::invalid_argument("platform sweep: rotor speed " + show(ni) +
                                    " rpm is negative (rpm − |difference| < 0)");
    }
    const RotorAeroOutput w = wrench(h, tilt, n);
    row.h_m = h;
    row.tilt_deg = tilt;
    row.n_rpm = n;
    for (int k = 0; k < params_.samples_per_setpoint; ++k) {
      row.t_s = static_cast<double>(done) * setpoint_s + k * params_.sample_period_s;
      for (int a = 0; a < 3; ++a)
        row.force_B[a] = w.wrench.force_B[a] + noise.boxMuller(params_.force_noise_N);
      for (int a = 0; a < 3; ++a)
        row.torque_B[a] = w.wrench.torque_B[a] + noise.boxMuller(params_.torque_noise_Nm);
      sink(row);
      ++rows;
    }
    ++done;
    if (progress) progress(done, total);
  };

  for (double h : sw.heights_m) {
    for (double tilt : sw.tilts_deg) {
      for (double n0 : sw.rpm) {
        if (sw.rpm_diffs.empty()) {
          visit(h, tilt, {n0, n0, n0, n0});
          continue;
        }
        for (double d : sw.rpm_diffs) {
          if (d == 0.0) {
            visit(h, tilt, {n0, n0, n0, n0});
            continue;
          }
          for (DiffAxis axis : sw.diff_axes) {
            const int r = static_cast<int>(axis);
            std::array<double, 4> n{};
            for (int i = 0; i < 4; ++i) n[static_cast<std::size_t>(i)] = n0 + d * A(r, i);
            visit(h, tilt, n);
          }
        }
      }
    }
  }
  return rows;
}

// ---------------------------------------------------------------------------------------------
// Single-rotor stand

std::vector<model::FieldError> RotorStandParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e, kDigits);
  using enum model::LowerBound;
  c.range("stand.thrust_noise_N", thrust_noise_N, 0.0, 1e3, kInclusive, "N");
  c.range("stand.torque_noise_Nm", torque_noise_Nm, 0.0, 1e3, kInclusive, "N·m");
  c.range("stand.rpm_noise", rpm_noise, 0.0, 1e5, kInclusive, "rpm");
  c.range("stand.motor_time_constant_s", motor_time_constant_s, 1e-5, 10.0, kInclusive, "s");
  c.range("stand.sample_period_s", sample_period_s, 1e-6, 100.0, kInclusive, "s");
  c.range("stand.hold_s", hold_s, 1e-6, 1e5, kInclusive, "s");
  if (hold_s < sample_period_s) c.fail("stand.hold_s", show(hold_s), "≥ stand.sample_period_s");
  return e;
}

RotorStand::RotorStand(const model::VehicleParams& vehicle, const RotorStandParams& params)
    : vehicle_(vehicle), params_(params) {
  auto errors = params.validate();
  for (auto& f : vehicle.validate()) errors.push_back(f);
  if (!errors.empty()) throwErrors("RotorStand", errors);
}

std::size_t RotorStand::sweep(const std::vector<double>& throttles, std::uint64_t seed,
                              const std::function<void(const RotorStandRow&)>& sink) const {
  if (throttles.empty()) throw std::invalid_argument("rotor stand: no throttle values");
  for (double th : throttles) {
    if (!(std::isfinite(th) && th >= 0.0 && th <= 1.0)) {
      throw std::invalid_argument("rotor stand: throttle " + show(th) + " is outside [0, 1]");
    }
  }
  if (!sink) throw std::invalid_argument("rotor stand: no row sink");
  const model::ThrottleCurve curve(vehicle_.throttle);
  const double tau = params_.motor_time_constant_s;
  const auto& rp = vehicle_.rotor;
  NoiseSource noise = NoiseSource::fromEngineSeed(seed);
  // Samples per hold: floor(hold/period) + 1 guards against rounding, at least one.
  const auto per_hold =
      static_cast<long>(std::floor(params_.hold_s / params_.sample_period_s + 1e-9));
  double n_start = curve.speedRpm(0.0);  // from rest at zero throttle (the ESC idles)
  double t0 = 0.0;
  std::size_t rows = 0;
  RotorStandRow row;
  for (double th : throttles) {
    const double n_ss = curve.speedRpm(th);
    for (long k = 0; k < per_hold; ++k) {
      const double s = static_cast<double>(k) * params_.sample_period_s;
      // Exact first-order response within the hold: n = n_ss + (n₀ − n_ss)·e^{−s/τ}.
      const double e = std::exp(-s / tau);
      const double n = n_ss + (n_start - n_ss) * e;
      const double n_dot = -(n_start - n_ss) / tau * e;  // [rpm/s]
      row.t_s = t0 + s;
      row.throttle = th;
      row.rpm = n + noise.boxMuller(params_.rpm_noise);
      row.thrust_N = model::rotorThrust(rp, n) + noise.boxMuller(params_.thrust_noise_N);
      row.torque_Nm = model::rotorReactionTorque(rp, n, n_dot) + noise.boxMuller(params_.torque_noise_Nm);
      sink(row);
      ++rows;
    }
    n_start = n_ss + (n_start - n_ss) * std::exp(-params_.hold_s / tau);
    t0 += params_.hold_s;
  }
  return rows;
}

}  // namespace geaware::sim
