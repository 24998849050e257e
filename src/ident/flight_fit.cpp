// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/flight_fit.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <utility>
#include <stdexcept>

#include <Eigen/Geometry>

#include "fit_support.hpp"
#include "geaware/model/ground_effect.hpp"

namespace geaware::ident {

using detail::num;

AdditionalThrustFit fitHoverAdditionalThrust(const FlightLog& log, double mass_kg, double k_T,
                                             const RobustOptions& robust) {
  if (!(mass_kg > 0.0) || !(k_T > 0.0)) {
    throw std::invalid_argument("fitHoverAdditionalThrust: mass and k_T must be positive");
  }
  const std::size_t n = log.size();
  if (log.a_ext_W[2].size() != n) throw std::invalid_argument("fitHoverAdditionalThrust: no az_ext");
  // Per sample: S = Σn² and the total z force m·a_ext,z + k_T·S, which the observer split into
  // the thrust it assumed (k_T·S) and the rest. Fitting it as k_T'·S·(1 + F_G(h)) gives the
  // hover's own k_T' along with g1, g2 (paper eq. 10 takes k_T as given: k_T' = k_T).
  std::vector<double> S(n, 0.0);
  std::vector<double> f(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto& c : log.n_rpm) S[i] += c[i] * c[i];
    f[i] = mass_kg * log.a_ext_W[2][i] + k_T * S[i];
  }
  AdditionalThrustFit out = detail::fitThrustWithGroundEffect(
      S, log.h_m, f, {}, robust, log.source, "k_T, g1, g2 of F_G(h) = g2/(h² + g1) from the hover descent");
  detail::warnCurveFit(out.warnings, out.blocking, "hover F_G fit",
                       {{"k_T", &out.k_T_N_per_rpm2}, {"g1", &out.g1_m2}, {"g2", &out.g2_m2}},
                       out.h_min_m, out.h_max_m,
                       "descend from out of ground effect to the lowest height", out.stats);
  return out;
}

namespace {

/// k_T' in m·a_ext,z + k_T·S = k_T'·S·(1 + F_G(h)), S = Σn², for a known F_G (`thrust_ratio`):
/// the observer's split undone, as in the hover descent's fit.
HoverThrustFit fitKTOnly(const FlightLog& log, double m, double k_T,
                         const std::function<double(double)>& thrust_ratio, const RobustOptions& robust) {
  const std::size_t n = log.size();
  if (log.a_ext_W[2].size() != n || log.h_m.size() != n) {
    throw std::invalid_argument("fitHoverThrust: the log lacks h or az_ext");
  }
  HoverThrustFit out;
  if (n > 0) {
    out.h_min_m = *std::min_element(log.h_m.begin(), log.h_m.end());
    out.h_max_m = *std::max_element(log.h_m.begin(), log.h_m.end());
  }
  const LeastSquaresFit ls = fitLinear(
      n, 1,
      [&](std::size_t i, double* x, double& y, double& w) {
        double S = 0.0;
        for (const auto& c : log.n_rpm) S += c[i] * c[i];
        x[0] = S * (1.0 + thrust_ratio(log.h_m[i]));
        y = m * log.a_ext_W[2][i] + k_T * S;
        w = 1.0;
        return S > 0.0;
      },
      robust);
  if (!ls.ok) {
    throw IdentError(log.source + ": cannot fit k_T from the hover (" + ls.message + ")");
  }
  out.k_T_N_per_rpm2 = ls.estimate(0);
  out.stats = ls.stats;
  return out;
}

}  // namespace

HoverThrustFit fitHoverThrust(const FlightLog& log, const model::VehicleParams& base,
                              double min_height_m, const RobustOptions& robust) {
  const double m = base.mass_kg;
  const double k_T = base.rotor.k_T_N_per_rpm2;
  if (!(m > 0.0) || !(k_T > 0.0)) {
    throw std::invalid_argument("fitHoverThrust: mass and k_T must be positive");
  }
  const model::GroundEffectModel ge(base);
  HoverThrustFit out = fitKTOnly(log, m, k_T, [&](double h) { return ge.thrustRatio(h); }, robust);
  if (out.h_min_m < min_height_m) {
    out.warnings.push_back("hover k_T: the log goes down to " + num(out.h_min_m) +
                           " m, below " + num(min_height_m) +
                           " m; F_G's error there enters k_T (hover higher)");
  }
  detail::warnIfImprecise(out.warnings, "hover k_T", out.k_T_N_per_rpm2, "hover longer", 0.02);
  return out;
}

HoverThrustFit fitHoverThrustOutOfGroundEffect(const FlightLog& log, double mass_kg, double k_T,
                                               const RobustOptions& robust) {
  if (!(mass_kg > 0.0) || !(k_T > 0.0)) {
    throw std::invalid_argument("fitHoverThrustOutOfGroundEffect: mass and k_T must be positive");
  }
  HoverThrustFit out = fitKTOnly(log, mass_kg, k_T, [](double) { return 0.0; }, robust);
  detail::warnIfImprecise(out.warnings, "hover k_T", out.k_T_N_per_rpm2, "hover longer", 0.02);
  return out;
}

DragFit fitDrag(const FlightLog& log, double mass_kg, const DragFitOptions& options) {
  DragFit out;
  const std::size_t n = log.size();
  if (log.v_W[0].size() != n || log.q_WB[0].size() != n || log.a_ext_W[0].size() != n) {
    throw std::invalid_argument("fitDrag: the log lacks velocity, attitude or a_ext columns");
  }
  // Body-frame velocity and in-plane external force per sample.
  std::vector<Eigen::Vector2d> v_B(n);
  std::vector<Eigen::Vector2d> f_B(n);
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Quaterniond q(log.q_WB[0][i], log.q_WB[1][i], log.q_WB[2][i], log.q_WB[3][i]);
    if (!(q.norm() > 0.5)) {
      throw IdentError(log.source + ":" + std::to_string(log.first_data_line + i) +
                       ": the attitude quaternion is not normalised (norm " + num(q.norm()) + ")");
    }
    const Eigen::Matrix3d R_WB = q.normalized().toRotationMatrix();
    const Eigen::Vector3d v(log.v_W[0][i], log.v_W[1][i], log.v_W[2][i]);
    const Eigen::Vector3d a(log.a_ext_W[0][i], log.a_ext_W[1][i], log.a_ext_W[2][i]);
    v_B[i] = (R_WB.transpose() * v).head<2>();
    f_B[i] = mass_kg * (R_WB.transpose() * a).head<2>();
  }
  // The samples by height (ties by their index: the same order on every machine). Sorting the
  // (h, i) pairs themselves keeps the comparisons in cache, unlike an index sort through h; the
  // body-frame vectors are then gathered once into that order, for contiguous bands.
  std::vector<std::pair<double, std::size_t>> by_height(n);
  for (std::size_t i = 0; i < n; ++i) by_height[i] = {log.h_m[i], i};
  std::sort(by_height.begin(), by_height.end());
  std::vector<double> sorted_h(n);
  std::vector<Eigen::Vector2d> sorted_v(n);
  std::vector<Eigen::Vector2d> sorted_f(n);
  for (std::size_t m = 0; m < n; ++m) {
    const std::size_t i = by_height[m].second;
    sorted_h[m] = by_height[m].first;
    sorted_v[m] = v_B[i];
    sorted_f[m] = f_B[i];
  }
  by_height = {};
  v_B = {};
  f_B = {};
  for (const auto& range : detail::bandRanges(sorted_h, options.height_bands)) {
    // Named copies, not a structured binding: the lambda below captures them, which C++20
    // allows for structured bindings but clang 14 does not implement.
    const std::size_t first = range.first;
    const std::size_t last = range.second;
    DragBand band;
    band.count = last - first;
    band.h_min_m = sorted_h[first];
    band.h_max_m = sorted_h[last - 1];
    band.h_mean_m = std::accumulate(sorted_h.begin() + static_cast<std::ptrdiff_t>(first),
                                    sorted_h.begin() + static_cast<std::ptrdiff_t>(last), 0.0) /
                    static_cast<double>(band.count);
    const std::string where = "height band " + num(band.h_min_m) + "–" + num(band.h_max_m) + " m";
    if (band.count < options.min_band_samples) {
      out.warnings.push_back(where + ": only " + std::to_string(band.count) + " samples, not fitted");
      continue;
    }
    bool ok = true;
    for (int axis = 0; axis < 2; ++axis) {
      const auto ls = fitLinear(
          band.count, 1,
          [&](std::size_t m, double* x, double& y, double& w) {
            x[0] = -sorted_v[first + m](axis);
            y = sorted_f[first + m](axis);
            w = 1.0;
            return true;
          },
          options.robust);
      if (!ls.ok) {
        out.warnings.push_back(where + ": d_" + (axis == 0 ? "x" : "y") +
                               " not fitted (" + ls.message + "): fly faster along that axis");
        ok = false;
        break;
      }
      (axis == 0 ? band.d_x_N_per_mps : band.d_y_N_per_mps) = ls.estimate(0);
      (axis == 0 ? band.x : band.y) = ls.stats;
    }
    if (!ok) continue;
    detail::warnIfImprecise(out.warnings, where + ": d_x", band.d_x_N_per_mps,
                            "too little body-x speed");
    detail::warnIfImprecise(out.warnings, where + ": d_y", band.d_y_N_per_mps,
                            "too little body-y speed");
    out.bands.push_back(band);
  }
  if (out.bands.empty()) {
    throw IdentError(log.source + ": cannot fit the drag table: no height band could be fitted");
  }
  if (out.bands.size() == 1 && options.height_bands > 1) {
    // Said, not silent (issue 16): the table then gives every height the same drag.
    out.warnings.push_back("the drag table has one row (" + num(out.bands.front().h_min_m) + "–" +
                           num(out.bands.front().h_max_m) + " m) of the " + std::to_string(options.height_bands) +
                           " height bands asked: the log's heights do not spread; fly at several heights for "
                           "a drag that depends on height");
  }
  return out;
}

model::DragTableParams dragTable(const DragFit& fit) {
  model::DragTableParams t;
  for (const auto& b : fit.bands) {
    // A band fitted negative is no drag: left out, never written as 0 (issue 11).
    if (!(b.d_x_N_per_mps.value >= 0.0 && b.d_y_N_per_mps.value >= 0.0)) continue;
    // Bands are disjoint and sorted, so the mean heights increase strictly.
    t.heights_m.push_back(b.h_min_m == b.h_max_m ? b.h_min_m : b.h_mean_m);
    t.d_x_N_per_mps.push_back(b.d_x_N_per_mps.value);
    t.d_y_N_per_mps.push_back(b.d_y_N_per_mps.value);
  }
  return t;
}

}  // namespace geaware::ident
