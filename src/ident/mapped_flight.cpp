// SPDX-License-Identifier: BSD-3-Clause
// A flight log from a mapped autopilot log, a_ext by the paper's observer (ident/rig_logs.hpp).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "geaware/ident/rig_logs.hpp"
#include "geaware/io/log_map.hpp"
#include "geaware/model/motor.hpp"

namespace geaware::ident {

MappedFlightLog flightLogFromMapped(const io::MappedFlight& flight, double mass_kg, double k_T_N_per_rpm2) {
  const std::size_t n = flight.size();
  const auto need = [&](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(flight.source + ": the mapped log has no " + std::string(what));
  };
  need(flight.h_m.size() == n, "height");
  need(flight.f_B_mps2[0].size() == n, "specific force");
  need(flight.q_WB[0].size() == n, "attitude");
  if (!flight.n_rpm.empty() && flight.n_rpm.size() != 4) {
    throw std::invalid_argument(flight.source + ": the map gives " + std::to_string(flight.n_rpm.size()) +
                                " rotors; the flight fits are for a quadrotor's 4");
  }
  need(flight.n_rpm.size() == 4 && flight.n_rpm[0].size() == n, "rotor speeds of 4 rotors");
  if (!(mass_kg > 0.0) || !(k_T_N_per_rpm2 > 0.0)) {
    throw std::invalid_argument("flightLogFromMapped: mass and k_T must be positive");
  }
  const bool with_velocity = flight.v_W_mps[0].size() == n;
  MappedFlightLog out;
  FlightLog& log = out.log;
  log.source = flight.source + " (mapped, time base " + flight.time_base + ")";
  // Per row: Σn², and whether the ground holds the vehicle up: every rotor stopped, or m·f_z/Σn²
  // (the IMU's vertical specific force per unit of Σn²: k_T·(1 + F_G) in a hover) more than twice
  // its value in flight, the lower quartile over the rows with rotors turning (those of a log
  // that is at least a quarter airborne). No ground effect a vehicle can fly in doubles its
  // thrust (the paper's platform measures F_G = 0.32 at its lowest height), and the ratio needs
  // no k_T: a vehicle file's may be off.
  std::vector<double> S(n, 0.0);
  std::vector<double> ratio(n, 0.0);
  std::vector<Eigen::Matrix3d> R(n);
  std::vector<double> turning;
  std::size_t stopped = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto& r : flight.n_rpm) S[i] += r[i] * r[i];
    const Eigen::Quaterniond q(flight.q_WB[0][i], flight.q_WB[1][i], flight.q_WB[2][i], flight.q_WB[3][i]);
    R[i] = q.normalized().toRotationMatrix();
    const Eigen::Vector3d f(flight.f_B_mps2[0][i], flight.f_B_mps2[1][i], flight.f_B_mps2[2][i]);
    if (S[i] == 0.0) {
      ++stopped;
      continue;
    }
    ratio[i] = mass_kg * (R[i] * f).z() / S[i];
    turning.push_back(ratio[i]);
  }
  double in_flight = std::numeric_limits<double>::infinity();
  if (!turning.empty()) {
    const auto q1 = turning.begin() + static_cast<std::ptrdiff_t>(turning.size() / 4);
    std::nth_element(turning.begin(), q1, turning.end());
    in_flight = *q1;
  }
  std::vector<char> supported(n, 0);
  std::vector<double> resting_heights;
  for (std::size_t i = 0; i < n; ++i) {
    if (S[i] == 0.0 || (in_flight > 0.0 && ratio[i] > 2.0 * in_flight)) {
      supported[i] = 1;
      resting_heights.push_back(flight.h_m[i]);
    }
  }
  // The height the vehicle rests at: the median over those rows, when they last kMinRestingS in
  // all (a few rows before the first rotor-speed sample of a log that starts in the air do not
  // make a resting height); within kGroundContactMarginM of it, rotors turning fast enough to fly
  // still stand on the ground (spinning up to take off).
  double h_rest_m = -std::numeric_limits<double>::infinity();
  const double dt_s = n > 1 ? (flight.t_s.back() - flight.t_s.front()) / static_cast<double>(n - 1) : 0.0;
  if (static_cast<double>(resting_heights.size()) * dt_s >= kMinRestingS) {
    const auto mid = resting_heights.begin() + static_cast<std::ptrdiff_t>(resting_heights.size() / 2);
    std::nth_element(resting_heights.begin(), mid, resting_heights.end());
    h_rest_m = *mid;
  }
  std::size_t standing = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (S[i] == 0.0) continue;
    if (supported[i] != 0 || flight.h_m[i] <= h_rest_m + kGroundContactMarginM) {
      ++standing;
      continue;
    }
    const Eigen::Vector3d f(flight.f_B_mps2[0][i], flight.f_B_mps2[1][i], flight.f_B_mps2[2][i]);
    const Eigen::Vector3d a_ext = R[i] * f - R[i].col(2) * (k_T_N_per_rpm2 * S[i] / mass_kg);
    log.t_s.push_back(flight.t_s[i]);
    log.h_m.push_back(flight.h_m[i]);
    for (std::size_t k = 0; k < 3; ++k) {
      log.a_ext_W[k].push_back(a_ext[static_cast<Eigen::Index>(k)]);
      if (with_velocity) log.v_W[k].push_back(flight.v_W_mps[k][i]);
    }
    for (std::size_t k = 0; k < 4; ++k) {
      log.q_WB[k].push_back(flight.q_WB[k][i]);
      log.n_rpm[k].push_back(flight.n_rpm[k][i]);
    }
  }
  if (stopped > 0) {
    out.notes.push_back(std::to_string(stopped) + " of " + std::to_string(n) +
                        " samples with every rotor at 0 rpm (on the ground or disarmed): dropped");
  }
  if (standing > 0) {
    char text[320];
    if (std::isfinite(h_rest_m)) {
      std::snprintf(text, sizeof text,
                    " samples standing on the ground (rotors turning at or within %.0f cm of the resting height "
                    "%.3f m, or the IMU's vertical specific force per sum(n^2) over twice its value in flight): "
                    "dropped",
                    kGroundContactMarginM * 100.0, h_rest_m);
    } else {
      std::snprintf(text, sizeof text,
                    " samples held up by the ground (the IMU's vertical specific force per sum(n^2) over twice its "
                    "value in flight; less than %.0f s of them, so no resting height): dropped",
                    kMinRestingS);
    }
    out.notes.push_back(std::to_string(standing) + " of " + std::to_string(n) + text);
  }
  return out;
}

ThrottleConversion rotorSpeedsFromThrottle(io::MappedFlight& flight, const model::ThrottleCurveParams& curve) {
  const std::size_t n = flight.size();
  if (flight.throttle.empty() || flight.throttle[0].size() != n) {
    throw std::invalid_argument(flight.source + ": the mapped log has no throttles");
  }
  if (!(curve.c2_rpm2 != 0.0 || curve.c1_rpm2 != 0.0 || curve.c0_rpm2 != 0.0)) {
    throw std::invalid_argument(flight.source + ": the vehicle has no throttle curve (c2, c1 and c0 are 0)");
  }
  const model::ThrottleCurve speed(curve);
  const bool with_voltage = curve.reference_voltage_V > 0.0 && flight.vbat_V.size() == n;
  ThrottleConversion out;
  std::size_t above = 0, stopped = 0, gaps = 0, disarmed = 0;
  const bool with_armed = flight.armed.size() == n;
  for (std::size_t i = 0; i < n && with_voltage; ++i) gaps += std::isnan(flight.vbat_V[i]) ? 1 : 0;
  for (std::size_t i = 0; i < n && with_armed; ++i) disarmed += flight.armed[i] < 0.5 ? 1 : 0;
  flight.n_rpm.assign(flight.throttle.size(), std::vector<double>(n, 0.0));
  for (std::size_t r = 0; r < flight.throttle.size(); ++r) {
    for (std::size_t i = 0; i < n; ++i) {
      const double t = with_armed && flight.armed[i] < 0.5 ? io::kStoppedThrottle : flight.throttle[r][i];
      if (!(t >= 0.0)) {  // io::kStoppedThrottle
        ++stopped;
        continue;
      }
      above += t > 1.0 ? 1 : 0;
      flight.n_rpm[r][i] = speed.speedRpm(std::min(t, 1.0), with_voltage ? flight.vbat_V[i] : kNaN);
    }
  }
  flight.rotor_fields.clear();
  for (const auto& f : flight.throttle_fields) flight.rotor_fields.push_back("throttle " + f);
  char text[200];
  std::snprintf(text, sizeof text,
                "rotor speeds from the throttles through the vehicle's throttle curve n^2 = %g t^2 + %g t + %g rpm^2",
                curve.c2_rpm2, curve.c1_rpm2, curve.c0_rpm2);
  std::string note = text;
  if (with_voltage) {
    std::snprintf(text, sizeof text, ", times (V/%g V)^%g with the logged battery voltage", curve.reference_voltage_V,
                  curve.voltage_exponent);
    note += text;
  }
  out.notes.push_back(note + "; " + std::to_string(stopped) + " of " +
                      std::to_string(n * flight.throttle.size()) + " values are a stopped motor");
  if (curve.reference_voltage_V > 0.0 && !with_voltage) {
    out.warnings.push_back("the vehicle's throttle curve depends on the battery voltage, but the log has none: the "
                           "curve is taken at its reference voltage, so a sagging battery reads as lost lift");
  } else if (!(curve.reference_voltage_V > 0.0) && flight.vbat_V.size() == n) {
    out.warnings.push_back("the log has the battery voltage but the vehicle's throttle curve has no voltage "
                           "dependence (throttle_curve.reference_voltage_V = 0; `identify rotor` with a voltage column "
                           "fits it): a sagging battery reads as lost lift");
  }
  if (with_voltage && gaps > 0) {
    out.notes.push_back(std::to_string(gaps) + " samples without a battery voltage (a gap in its log): the curve at "
                        "its reference voltage there");
  }
  if (disarmed > 0) {
    out.notes.push_back(std::to_string(disarmed) + " of " + std::to_string(n) +
                        " samples disarmed (the map's armed channel below 0.5): every motor stopped");
  }
  if (above > 0) {
    out.warnings.push_back(std::to_string(above) + " throttle values above 1 taken as 1 (the map's range may be wrong)");
  }
  return out;
}

}  // namespace geaware::ident
