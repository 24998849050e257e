// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Synthetic rig and flight logs for the identification tests, generated exactly from the
// controller-side model (model::Mixer, model::GroundEffectModel, model::ThrottleCurve,
// model::RotorDragModel) with the paper's parameters plus seeded Gaussian noise. A fit of such
// data must return the parameters within a few of its reported standard errors.

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/motor.hpp"
#include "geaware/model/rotor_drag.hpp"
#include "geaware/model/units.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace ident_test {

using geaware::ident::Estimate;
namespace model = geaware::model;

/// |estimate − truth| ≤ k·σ, printing the z-score on failure.
inline ::testing::AssertionResult withinSigmas(const Estimate& e, double truth, double k = 4.0) {
  const double z = (e.value - truth) / e.std_error;
  if (std::abs(z) <= k && e.std_error > 0.0) return ::testing::AssertionSuccess() << "z = " << z;
  return ::testing::AssertionFailure() << "estimate " << e.value << " ± " << e.std_error
                                       << " vs truth " << truth << ": z = " << z;
}

/// A fresh, empty directory for one test's files (the process id keeps two test runs at the
/// same time, e.g. from two build trees, apart).
inline std::filesystem::path tempDir(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) /
                   ("geaware_ident_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void writeText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream os(file, std::ios::binary);
  os << text;
}

struct PlatformSpec {
  std::size_t level_samples = 20000;
  std::size_t tilted_samples = 20000;
  std::vector<double> level_heights_m = {0.075, 0.09, 0.11, 0.13, 0.16, 0.2, 0.25,
                                         0.3,   0.4,  0.5,  0.7,  1.0,  1.5, 2.0};
  std::vector<double> tilted_heights_m = {0.08, 0.1, 0.12, 0.14, 0.16, 0.18, 0.2,
                                          0.22, 0.25, 0.28, 0.31, 0.35, 0.4};
  std::vector<double> tilts_deg = {2.0, 4.0, 6.0, 8.0, 10.0};
  double mixing_rpm = 1500.0;    ///< per-rotor speed differences on the level board
  double sigma_force_N = 0.05;   ///< force-sensor noise
  double sigma_torque_Nm = 0.002;
  double outlier_fraction = 0.0; ///< gross errors of 100–400 σ on f_z and τ_y
};

/// A platform log from the controller-side model: f_z = T·(1 + F_G(h)), τ = τ_B + τ_G with
/// τ_G,y = −M_G(h)·T·sin δ (the platform's leveling sign), T = k_T·Σn².
inline geaware::ident::PlatformLog syntheticPlatform(const PlatformSpec& spec, std::uint64_t seed,
                                                     const model::VehicleParams& p =
                                                         geaware_test::paperParams()) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const model::Mixer mixer(p);
  const model::GroundEffectModel ge(p);
  geaware::ident::PlatformLog log;
  log.source = "synthetic_platform_" + std::to_string(seed);
  log.first_data_line = 2;
  const std::size_t n = spec.level_samples + spec.tilted_samples;
  auto pick = [&](const std::vector<double>& v) {
    return v[static_cast<std::size_t>(unit(rng) * static_cast<double>(v.size())) % v.size()];
  };
  for (std::size_t i = 0; i < n; ++i) {
    const bool level = i < spec.level_samples;
    const double h = level ? pick(spec.level_heights_m) : pick(spec.tilted_heights_m);
    const double tilt = level ? 0.0 : pick(spec.tilts_deg);
    const double base = level ? 8000.0 + 8000.0 * unit(rng) : 10000.0 + 6000.0 * unit(rng);
    const double spread = level ? spec.mixing_rpm : 300.0;
    Eigen::Vector4d speeds;
    for (int k = 0; k < 4; ++k) speeds(k) = base + spread * (2.0 * unit(rng) - 1.0);
    const Eigen::Vector4d n2 = speeds.cwiseAbs2();
    const Eigen::Vector4d w = mixer.wrench(n2);  // [T, τ_B]
    const double T = w(0);
    double fz = T * (1.0 + ge.thrustRatio(h)) + spec.sigma_force_N * noise(rng);
    double ty = w(2) - ge.levelingCoefficient(h) * T * std::sin(tilt * model::kDegToRad) +
                spec.sigma_torque_Nm * noise(rng);
    if (unit(rng) < spec.outlier_fraction) {
      const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
      fz += sign * spec.sigma_force_N * (100.0 + 300.0 * unit(rng));
      ty += sign * spec.sigma_torque_Nm * (100.0 + 300.0 * unit(rng));
    }
    log.t_s.push_back(0.005 * static_cast<double>(i));
    log.h_m.push_back(h);
    log.tilt_deg.push_back(tilt);
    for (std::size_t k = 0; k < 4; ++k) log.n_rpm[k].push_back(speeds(static_cast<Eigen::Index>(k)));
    log.f_N[0].push_back(spec.sigma_force_N * noise(rng));
    log.f_N[1].push_back(spec.sigma_force_N * noise(rng));
    log.f_N[2].push_back(fz);
    log.tau_Nm[0].push_back(w(1) + spec.sigma_torque_Nm * noise(rng));
    log.tau_Nm[1].push_back(ty);
    log.tau_Nm[2].push_back(w(3) + spec.sigma_torque_Nm * noise(rng));
  }
  return log;
}

/// Writes a hover log in `identify flight --hover`'s CSV format (t, h, az_ext, n1..n4).
inline void writeHoverCsv(const std::filesystem::path& file, const geaware::ident::FlightLog& log) {
  std::ofstream os(file);
  os.precision(12);
  os << "t_s,h_m,az_ext_mps2,n1_rpm,n2_rpm,n3_rpm,n4_rpm\n";
  for (std::size_t i = 0; i < log.size(); ++i) {
    os << log.t_s[i] << ',' << log.h_m[i] << ',' << log.a_ext_W[2][i];
    for (const auto& c : log.n_rpm) os << ',' << c[i];
    os << '\n';
  }
}

/// Writes a platform log in the rig's CSV format.
inline void writePlatformCsv(const std::filesystem::path& file,
                             const geaware::ident::PlatformLog& log) {
  std::ofstream os(file);
  os.precision(12);
  os << "t_s,h_m,tilt_deg,n1_rpm,n2_rpm,n3_rpm,n4_rpm,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm\n";
  for (std::size_t i = 0; i < log.size(); ++i) {
    os << log.t_s[i] << ',' << log.h_m[i] << ',' << log.tilt_deg[i];
    for (const auto& c : log.n_rpm) os << ',' << c[i];
    for (const auto& c : log.f_N) os << ',' << c[i];
    for (const auto& c : log.tau_Nm) os << ',' << c[i];
    os << '\n';
  }
}

struct StandSpec {
  double duration_s = 20.0;
  double dt_s = 0.001;
  double sigma_rpm = 2.0;
  double sigma_thrust_N = 0.02;
  double sigma_torque_Nm = 0.003;
};

/// A single-rotor stand log: a speed sweep n(t) = 11,500 + 8,000·sin(2π·0.25·t) rpm, the
/// throttle from the inverse throttle curve, thrust k_T·n², torque k_I·n² + J_R·ṅ.
inline geaware::ident::RotorStandLog syntheticStand(const StandSpec& spec, std::uint64_t seed) {
  const auto& p = geaware_test::paperParams();
  const model::ThrottleCurve curve(p.throttle);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  geaware::ident::RotorStandLog log;
  log.source = "synthetic_stand_" + std::to_string(seed);
  const double w = 2.0 * std::numbers::pi * 0.25;
  const auto n = static_cast<std::size_t>(spec.duration_s / spec.dt_s);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = spec.dt_s * static_cast<double>(i);
    const double rpm = 11500.0 + 8000.0 * std::sin(w * t);
    const double rate = 8000.0 * w * std::cos(w * t);
    log.t_s.push_back(t);
    log.throttle.push_back(curve.throttle(rpm));
    log.rpm.push_back(rpm + spec.sigma_rpm * noise(rng));
    log.thrust_N.push_back(model::rotorThrust(p.rotor, rpm) + spec.sigma_thrust_N * noise(rng));
    log.torque_Nm.push_back(model::rotorReactionTorque(p.rotor, rpm, rate) +
                            spec.sigma_torque_Nm * noise(rng));
  }
  return log;
}

/// Hover descent from 1.5 m to 0.075 m: speeds hold m·g = T·(1 + F_G(h)); the observer's
/// external acceleration is F_G·T/m plus noise.
/// `observer_k_T_scale`: the observer's k_T relative to the truth's (1: right).
inline geaware::ident::FlightLog hoverDescent(std::uint64_t seed, double observer_k_T_scale = 1.0) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::GroundEffectModel ge(p);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  geaware::ident::FlightLog log;
  log.source = "hover_" + std::to_string(seed);
  const int n = 12000;  // 60 s at 200 Hz
  for (int i = 0; i < n; ++i) {
    const double h = 1.5 - (1.5 - 0.075) * i / (n - 1.0);
    const double T = p.mass_kg * geaware::model::kGravity / (1.0 + ge.thrustRatio(h));
    const double rpm = std::sqrt(T / (4.0 * p.rotor.k_T_N_per_rpm2));
    log.t_s.push_back(0.005 * i);
    log.h_m.push_back(h);
    // The observer explains k_T,obs·Σn² = observer_k_T_scale·T of the total T·(1 + F_G).
    log.a_ext_W[2].push_back((T * (1.0 + ge.thrustRatio(h)) - observer_k_T_scale * T) / p.mass_kg +
                             0.05 * noise(rng));
    for (auto& c : log.n_rpm) c.push_back(rpm);
  }
  return log;
}

/// Hover between h_lo_m and h_hi_m (slow up and down) in a world WITHOUT ground effect: speeds
/// hold m·g = k_T·Σn² with ±5 % speed changes; the observer's external acceleration is
/// (m·g − observer_k_T_scale·k_T·Σn²)/m plus noise.
inline geaware::ident::FlightLog hoverNoGroundEffect(std::uint64_t seed, double h_lo_m, double h_hi_m,
                                                     double observer_k_T_scale = 1.0) {
  const auto& p = geaware_test::paperParams();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  geaware::ident::FlightLog log;
  log.source = "hover_no_ge_" + std::to_string(seed);
  const int n = 6000;  // 30 s at 200 Hz
  for (int i = 0; i < n; ++i) {
    const double s = 0.5 - 0.5 * std::cos(6.283185307 * i / (n - 1.0) * 3.0);
    const double h = h_lo_m + (h_hi_m - h_lo_m) * s;
    const double rpm = std::sqrt(p.mass_kg * geaware::model::kGravity / (4.0 * p.rotor.k_T_N_per_rpm2)) *
                       (1.0 + 0.05 * std::sin(0.37 * i));
    const double T = 4.0 * p.rotor.k_T_N_per_rpm2 * rpm * rpm;
    log.t_s.push_back(0.005 * i);
    log.h_m.push_back(h);
    log.a_ext_W[2].push_back((T - observer_k_T_scale * T) / p.mass_kg + 0.05 * noise(rng));
    for (auto& c : log.n_rpm) c.push_back(rpm);
  }
  return log;
}

/// Flights at four heights with random velocities and attitudes; the external acceleration is
/// (f_D + f_G)/m plus noise, f_D from the vehicle's drag table.
inline geaware::ident::FlightLog dragFlights(std::uint64_t seed) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::RotorDragModel drag(p.drag);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  geaware::ident::FlightLog log;
  log.source = "flight_" + std::to_string(seed);
  const std::vector<double> heights = {0.1, 0.2, 0.5, 2.0};
  for (int i = 0; i < 8000; ++i) {
    const double h = heights[static_cast<std::size_t>(i / 2000)];
    const Eigen::Quaterniond q =
        Eigen::AngleAxisd(6.283 * unit(rng), Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(0.3 * (unit(rng) - 0.5), Eigen::Vector3d::UnitY()) *
        Eigen::AngleAxisd(0.3 * (unit(rng) - 0.5), Eigen::Vector3d::UnitX());
    const Eigen::Matrix3d R = q.toRotationMatrix();
    const Eigen::Vector3d v(4.0 * (unit(rng) - 0.5), 4.0 * (unit(rng) - 0.5), 0.5 * (unit(rng) - 0.5));
    const Eigen::Vector3d f = geaware::model::RotorDragModel::force_W(R, v, drag.coefficients(h)) +
                              2.0 * R.col(2);  // an additional thrust along z_B: must not matter
    log.t_s.push_back(0.005 * i);
    log.h_m.push_back(h);
    for (int k = 0; k < 3; ++k) {
      log.v_W[static_cast<std::size_t>(k)].push_back(v(k));
      log.a_ext_W[static_cast<std::size_t>(k)].push_back(f(k) / p.mass_kg + 0.05 * noise(rng));
    }
    log.q_WB[0].push_back(q.w());
    log.q_WB[1].push_back(q.x());
    log.q_WB[2].push_back(q.y());
    log.q_WB[3].push_back(q.z());
    for (auto& c : log.n_rpm) c.push_back(10000.0);
  }
  return log;
}

}  // namespace ident_test
