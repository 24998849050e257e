// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/min_snap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <Eigen/LU>

namespace geaware::traj {
namespace {

// k!/(k − r)!: the factor dʳ/dxʳ brings to x^k (0 when r > k).
double fallingFactorial(int k, int r) noexcept {
  if (r > k) return 0.0;
  double f = 1.0;
  for (int i = 0; i < r; ++i) f *= static_cast<double>(k - i);
  return f;
}

Eigen::RowVector4d asRow(const Waypoint& w) { return {w.p_W.x(), w.p_W.y(), w.p_W.z(), w.yaw_rad}; }

void waypointProblems(const std::vector<Waypoint>& waypoints, std::vector<std::string>& out) {
  std::ostringstream os;
  os.precision(10);
  if (waypoints.size() < 2) {
    os << "waypoints: size = " << waypoints.size() << " (expected >= 2)";
    out.push_back(os.str());
    return;
  }
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const Waypoint& w = waypoints[i];
    if (w.p_W.allFinite() && std::isfinite(w.yaw_rad)) continue;
    os.str("");
    os << "waypoints[" << i << "] = (p_W = (" << w.p_W.x() << ", " << w.p_W.y() << ", " << w.p_W.z()
       << "), yaw_rad = " << w.yaw_rad << ") (expected finite)";
    out.push_back(os.str());
  }
}

[[noreturn]] void throwProblems(const std::vector<std::string>& problems) {
  std::string msg = "MinSnapTrajectory: invalid input: ";
  for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
  throw std::invalid_argument(msg);
}

}  // namespace

std::vector<std::string> MinSnapTrajectory::validate(
    const std::vector<Waypoint>& waypoints, const std::vector<double>& segment_durations_s) {
  std::vector<std::string> out;
  waypointProblems(waypoints, out);
  std::ostringstream os;
  os.precision(10);
  if (waypoints.size() >= 2 && segment_durations_s.size() != waypoints.size() - 1) {
    os << "segment_durations_s: size = " << segment_durations_s.size()
       << " (expected waypoints.size() - 1 = " << waypoints.size() - 1 << ")";
    out.push_back(os.str());
  }
  for (std::size_t i = 0; i < segment_durations_s.size(); ++i) {
    const double d = segment_durations_s[i];
    if (std::isfinite(d) && d > 0.0) continue;
    os.str("");
    os << "segment_durations_s[" << i << "] = " << d << " (expected finite > 0)";
    out.push_back(os.str());
  }
  return out;
}

MinSnapTrajectory MinSnapTrajectory::fromAverageSpeed(std::vector<Waypoint> waypoints,
                                                      double average_speed_mps,
                                                      double min_segment_duration_s) {
  std::vector<std::string> problems;
  waypointProblems(waypoints, problems);
  std::ostringstream os;
  os.precision(10);
  if (!(std::isfinite(average_speed_mps) && average_speed_mps > 0.0)) {
    os << "average_speed_mps = " << average_speed_mps << " (expected finite > 0)";
    problems.push_back(os.str());
  }
  if (!(std::isfinite(min_segment_duration_s) && min_segment_duration_s > 0.0)) {
    os.str("");
    os << "min_segment_duration_s = " << min_segment_duration_s << " (expected finite > 0)";
    problems.push_back(os.str());
  }
  if (!problems.empty()) throwProblems(problems);

  std::vector<double> durations(waypoints.size() - 1);
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    const double length_m = (waypoints[i + 1].p_W - waypoints[i].p_W).norm();
    durations[i] = std::max(length_m / average_speed_mps, min_segment_duration_s);
  }
  return {std::move(waypoints), std::move(durations)};
}

MinSnapTrajectory::MinSnapTrajectory(std::vector<Waypoint> waypoints,
                                     std::vector<double> segment_durations_s)
    : waypoints_(std::move(waypoints)), durations_s_(std::move(segment_durations_s)) {
  const std::vector<std::string> problems = validate(waypoints_, durations_s_);
  if (!problems.empty()) throwProblems(problems);

  const int m = static_cast<int>(durations_s_.size());
  start_times_s_.resize(durations_s_.size() + 1);
  start_times_s_[0] = 0.0;
  for (std::size_t i = 0; i < durations_s_.size(); ++i) {
    start_times_s_[i + 1] = start_times_s_[i] + durations_s_[i];
  }

  // 1. Unknowns: segment i's normalised coefficients a_{i,k}, p_i(τ) = Σ_k a_{i,k}·(τ/T_i)^k,
  //    at rows 8i + k; one column per dimension. A derivative of order r in τ is T_i^{-r}
  //    times the one in x; every equation below is multiplied by the segment's T^r so that
  //    its coefficients are the pure numbers k!/(k − r)!, whatever the durations.
  const int n = kOrder * m;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n, kDims);
  int row = 0;

  // 2. Start at rest on waypoint 0: dʳp_0/dxʳ(0) = r!·a_{0,r}; position, then v = a = j = 0.
  for (int r = 0; r < 4; ++r, ++row) {
    a(row, r) = fallingFactorial(r, r);
    if (r == 0) b.row(row) = asRow(waypoints_.front());
  }
  // 3. Interior waypoint j + 1, between segments j and j + 1: position, then continuity of
  //    derivatives 0…6. Scaled by T_j^r, the continuity row reads
  //    Σ_k k!/(k − r)!·a_{j,k} − (T_j/T_{j+1})^r·r!·a_{j+1,r} = 0.
  for (int j = 0; j + 1 < m; ++j) {
    const int c0 = kOrder * j;
    const int c1 = kOrder * (j + 1);
    for (int k = 0; k < kOrder; ++k) a(row, c0 + k) = 1.0;
    b.row(row) = asRow(waypoints_[static_cast<std::size_t>(j + 1)]);
    ++row;
    const double ratio =
        durations_s_[static_cast<std::size_t>(j)] / durations_s_[static_cast<std::size_t>(j + 1)];
    for (int r = 0; r <= 6; ++r, ++row) {
      for (int k = r; k < kOrder; ++k) a(row, c0 + k) = fallingFactorial(k, r);
      a(row, c1 + r) = -std::pow(ratio, r) * fallingFactorial(r, r);
    }
  }
  // 4. End at rest on the last waypoint: dʳp/dxʳ(1) = Σ_k k!/(k − r)!·a_{M−1,k}.
  for (int r = 0; r < 4; ++r, ++row) {
    for (int k = r; k < kOrder; ++k) a(row, kOrder * (m - 1) + k) = fallingFactorial(k, r);
    if (r == 0) b.row(row) = asRow(waypoints_.back());
  }

  // 5. Solve for all dimensions at once. The system is non-singular for positive durations
  //    (the strictly convex problem has a unique minimiser); the residual check catches a
  //    numerically hopeless case such as durations spanning many orders of magnitude.
  const Eigen::MatrixXd x = a.partialPivLu().solve(b);
  const double residual = (a * x - b).lpNorm<Eigen::Infinity>();
  const double scale =
      a.lpNorm<Eigen::Infinity>() * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>();
  if (!x.allFinite() || !(residual <= 1e-9 * scale)) {
    std::ostringstream os;
    os << "MinSnapTrajectory: the linear solve failed (relative residual " << residual / scale
       << "); are the segment durations of very different magnitudes?";
    throw std::runtime_error(os.str());
  }

  // 6. Tabulate the coefficients of dʳp/dxʳ, r = 0…4, for Horner evaluation in sample().
  derivative_coeffs_.resize(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) {
    const Coeffs c = x.block<kOrder, kDims>(kOrder * i, 0);
    auto& d = derivative_coeffs_[static_cast<std::size_t>(i)];
    for (int r = 0; r < kDerivs; ++r) {
      d[static_cast<std::size_t>(r)].setZero();
      for (int k = 0; k + r < kOrder; ++k) {
        d[static_cast<std::size_t>(r)].row(k) = fallingFactorial(k + r, r) * c.row(k + r);
      }
    }
  }
}

FlatOutput MinSnapTrajectory::sample(double t_s) const noexcept {
  FlatOutput out;
  if (std::isnan(t_s)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out.p_W.setConstant(nan);
    out.yaw_rad = nan;
    return out;
  }
  // Strictly outside [0, duration]: the end state at rest, exactly on the waypoint.
  if (t_s < 0.0 || t_s > duration()) {
    const Waypoint& w = t_s < 0.0 ? waypoints_.front() : waypoints_.back();
    out.p_W = w.p_W;
    out.yaw_rad = w.yaw_rad;
    return out;
  }
  // Segment i holds t ∈ [t_i, t_{i+1}); the last one also holds t = duration.
  const auto first_interior = start_times_s_.begin() + 1;
  const auto last = start_times_s_.end() - 1;
  const auto i =
      static_cast<std::size_t>(std::upper_bound(first_interior, last, t_s) - first_interior);
  const double t_seg = durations_s_[i];
  const double x = std::clamp((t_s - start_times_s_[i]) / t_seg, 0.0, 1.0);

  // Horner per derivative, then d/dτ = (1/T)·d/dx once per order.
  std::array<Eigen::RowVector4d, kDerivs> value;
  double inv_t_pow = 1.0;
  for (int r = 0; r < kDerivs; ++r) {
    const Coeffs& d = derivative_coeffs_[i][static_cast<std::size_t>(r)];
    Eigen::RowVector4d v = d.row(kOrder - 1 - r);
    for (int k = kOrder - 2 - r; k >= 0; --k) v = v * x + d.row(k);
    value[static_cast<std::size_t>(r)] = v * inv_t_pow;
    inv_t_pow /= t_seg;
  }
  out.p_W = value[0].head<3>().transpose();
  out.v_W = value[1].head<3>().transpose();
  out.a_W = value[2].head<3>().transpose();
  out.j_W = value[3].head<3>().transpose();
  out.s_W = value[4].head<3>().transpose();
  out.yaw_rad = value[0](3);
  out.yaw_rate_radps = value[1](3);
  out.yaw_acc_radps2 = value[2](3);
  return out;
}

}  // namespace geaware::traj
