// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/flight_series.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geaware/model/units.hpp"

namespace geaware::experiments {

SeriesCollector::SeriesCollector(std::size_t ticks, int stride) : stride_(std::max(stride, 1)) {
  const std::size_t n = ticks / static_cast<std::size_t>(stride_) + 2;
  auto reserve = [n](std::vector<double>& v) { v.reserve(n); };
  reserve(s_.t_s);
  for (auto& v : s_.ref_m) reserve(v);
  for (auto& v : s_.true_m) reserve(v);
  reserve(s_.err_cm);
  reserve(s_.err_z_cm);
  reserve(s_.h_true_m);
  reserve(s_.h_meas_m);
  reserve(s_.att_err_deg);
  for (auto& v : s_.n_rpm) reserve(v);
  for (auto& v : s_.tau_des_Nm) reserve(v);
  for (auto& v : s_.tau_hat_Nm) reserve(v);
}

void SeriesCollector::onTick(const FlightTick& k) noexcept {
  if (ticks_++ % static_cast<std::size_t>(stride_) != 0) return;
  if (s_.t_s.size() == s_.t_s.capacity()) return;  // never reallocate inside the loop
  const Eigen::Vector3d& ref = k.input.reference.p_W;
  const Eigen::Vector3d& p = k.truth.p_W;
  s_.t_s.push_back(k.t_traj_s);
  for (std::size_t a = 0; a < 3; ++a) {
    const auto i = static_cast<Eigen::Index>(a);
    s_.ref_m[a].push_back(ref(i));
    s_.true_m[a].push_back(p(i));
    s_.tau_des_Nm[a].push_back(k.controller_active ? k.output.tau_des_B(i)
                                                   : std::numeric_limits<double>::quiet_NaN());
    s_.tau_hat_Nm[a].push_back(k.controller_active ? k.output.tau_hat_B(i)
                                                   : std::numeric_limits<double>::quiet_NaN());
  }
  s_.err_cm.push_back((ref - p).norm() * 100.0);
  s_.err_z_cm.push_back((ref.z() - p.z()) * 100.0);
  s_.h_true_m.push_back(k.true_height_m);
  s_.h_meas_m.push_back(k.controller_active && k.input.height_valid
                            ? k.input.height_m
                            : std::numeric_limits<double>::quiet_NaN());
  s_.att_err_deg.push_back(k.controller_active ? k.attitude_error_rad / model::kDegToRad
                                               : std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < 4; ++i) s_.n_rpm[i].push_back(k.truth.n_rpm[i]);
}

std::size_t expectedTicks(const FlightScenario& s) {
  const double seconds = s.start_hover_s + s.trajectory->duration() + s.settle_s;
  return static_cast<std::size_t>(std::ceil(seconds * s.controller.rate_hz)) + 8;
}

}  // namespace geaware::experiments
