// SPDX-License-Identifier: BSD-3-Clause
// A flight log from a mapped autopilot log, a_ext by the paper's observer (ident/rig_logs.hpp).

#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "geaware/ident/rig_logs.hpp"
#include "geaware/io/log_map.hpp"

namespace geaware::ident {

MappedFlightLog flightLogFromMapped(const io::MappedFlight& flight, double mass_kg, double k_T_N_per_rpm2) {
  const std::size_t n = flight.size();
  const auto need = [&](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(flight.source + ": the mapped log has no " + std::string(what));
  };
  need(flight.h_m.size() == n, "height");
  need(flight.f_B_mps2[0].size() == n, "specific force");
  need(flight.q_WB[0].size() == n, "attitude");
  need(flight.n_rpm.size() == 4 && flight.n_rpm[0].size() == n, "rotor speeds of 4 rotors");
  if (!(mass_kg > 0.0) || !(k_T_N_per_rpm2 > 0.0)) {
    throw std::invalid_argument("flightLogFromMapped: mass and k_T must be positive");
  }
  const bool with_velocity = flight.v_W_mps[0].size() == n;
  MappedFlightLog out;
  FlightLog& log = out.log;
  log.source = flight.source + " (mapped, time base " + flight.time_base + ")";
  std::size_t resting = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double S = 0.0;
    for (const auto& r : flight.n_rpm) S += r[i] * r[i];
    if (S == 0.0) {
      ++resting;
      continue;
    }
    const Eigen::Quaterniond q(flight.q_WB[0][i], flight.q_WB[1][i], flight.q_WB[2][i], flight.q_WB[3][i]);
    const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
    const Eigen::Vector3d f(flight.f_B_mps2[0][i], flight.f_B_mps2[1][i], flight.f_B_mps2[2][i]);
    const Eigen::Vector3d a_ext = R * f - R.col(2) * (k_T_N_per_rpm2 * S / mass_kg);
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
  if (resting > 0) {
    out.notes.push_back(std::to_string(resting) + " of " + std::to_string(n) +
                        " samples with every rotor at 0 rpm (on the ground or disarmed): dropped");
  }
  return out;
}

}  // namespace geaware::ident
