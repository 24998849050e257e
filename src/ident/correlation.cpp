// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/correlation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "geaware/model/mixer.hpp"
#include "geaware/model/units.hpp"

namespace geaware::ident {

std::vector<double> averageRanks(std::span<const double> v) {
  const std::size_t n = v.size();
  // Sorting (value, index) pairs keeps the comparisons in cache, unlike an index sort.
  std::vector<std::pair<double, std::size_t>> s(n);
  for (std::size_t i = 0; i < n; ++i) s[i] = {v[i], i};
  std::sort(s.begin(), s.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> ranks(n);
  std::size_t first = 0;
  while (first < n) {
    std::size_t last = first + 1;
    while (last < n && s[last].first == s[first].first) ++last;
    // Ranks first+1 … last share their mean.
    const double rank = 0.5 * static_cast<double>(first + 1 + last);
    for (std::size_t k = first; k < last; ++k) ranks[s[k].second] = rank;
    first = last;
  }
  return ranks;
}

double pearson(std::span<const double> x, std::span<const double> y) {
  const std::size_t n = x.size();
  if (n != y.size()) throw std::invalid_argument("pearson: x and y differ in length");
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  double mx = 0.0;
  double my = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0.0;
  double sxx = 0.0;
  double syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = x[i] - mx;
    const double dy = y[i] - my;
    sxy += dx * dy;
    sxx += dx * dx;
    syy += dy * dy;
  }
  if (!(sxx > 0.0) || !(syy > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return sxy / std::sqrt(sxx * syy);
}

std::vector<double> averageRanks(std::span<const double> v, std::span<const double> w) {
  const std::size_t n = v.size();
  if (w.size() != n) throw std::invalid_argument("averageRanks: v and w differ in length");
  std::vector<std::pair<double, std::size_t>> s(n);
  for (std::size_t i = 0; i < n; ++i) s[i] = {v[i], i};
  std::sort(s.begin(), s.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> ranks(n);
  std::size_t first = 0;
  double before = 0.0;  // samples ranked below the tie group
  while (first < n) {
    std::size_t last = first;
    double group = 0.0;
    while (last < n && s[last].first == s[first].first) group += w[s[last++].second];
    // Expanded, the group holds ranks before+1 … before+group: they share their mean.
    const double rank = before + 0.5 * (group + 1.0);
    for (std::size_t k = first; k < last; ++k) ranks[s[k].second] = rank;
    before += group;
    first = last;
  }
  return ranks;
}

double pearson(std::span<const double> x, std::span<const double> y, std::span<const double> w) {
  const std::size_t n = x.size();
  if (n != y.size() || n != w.size()) throw std::invalid_argument("pearson: x, y and w differ in length");
  double total = 0.0;
  double mx = 0.0;
  double my = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    total += w[i];
    mx += w[i] * x[i];
    my += w[i] * y[i];
  }
  if (!(total >= 2.0)) return std::numeric_limits<double>::quiet_NaN();
  mx /= total;
  my /= total;
  double sxy = 0.0;
  double sxx = 0.0;
  double syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = x[i] - mx;
    const double dy = y[i] - my;
    sxy += w[i] * dx * dy;
    sxx += w[i] * dx * dx;
    syy += w[i] * dy * dy;
  }
  if (!(sxx > 0.0) || !(syy > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return sxy / std::sqrt(sxx * syy);
}

double spearman(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) throw std::invalid_argument("spearman: x and y differ in length");
  const auto rx = averageRanks(x);
  const auto ry = averageRanks(y);
  return pearson(rx, ry);
}

CorrelationTable platformCorrelations(const PlatformLog& log, const model::VehicleParams& vehicle,
                                      const CorrelationOptions& options) {
  const std::size_t n = log.size();
  const model::Mixer mixer(vehicle);
  const double k_T = vehicle.rotor.k_T_N_per_rpm2;

  // The variables, per sample.
  std::vector<std::vector<double>> rows(6, std::vector<double>(n));    // N_base(1..4), h, δ
  std::vector<std::vector<double>> cols(5);                            // see column_names
  for (auto& c : cols) c.resize(n);
  std::vector<std::size_t> tilted;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector4d n2;
    for (int k = 0; k < 4; ++k) n2(k) = log.n_rpm[static_cast<std::size_t>(k)][i] * log.n_rpm[static_cast<std::size_t>(k)][i];
    const Eigen::Vector4d base = mixer.baseSpeeds(n2);
    const Eigen::Vector4d wrench = mixer.wrench(n2);
    for (std::size_t k = 0; k < 4; ++k) rows[k][i] = base(static_cast<Eigen::Index>(k));
    rows[4][i] = log.h_m[i];
    rows[5][i] = log.tilt_deg[i];
    const double tau_G_y = log.tau_Nm[1][i] - wrench(2);
    cols[0][i] = log.tau_Nm[0][i];
    cols[1][i] = log.tau_Nm[2][i];
    cols[2][i] = tau_G_y;
    cols[3][i] = tau_G_y / std::sin(log.tilt_deg[i] * model::kDegToRad);
    cols[4][i] = log.f_N[2][i] - k_T * n2.sum();
    if (std::abs(log.tilt_deg[i]) > options.level_tilt_deg) tilted.push_back(i);
  }

  CorrelationTable table;
  table.row_names = {"N_base(1)", "N_base(2)", "N_base(3)", "N_base(4)", "h", "delta"};
  table.column_names = {"x_W'tau_B", "z_W'tau_B", "y_W'tau_G", "y_W'tau_G/sin(delta)", "f_G"};
  table.r.resize(6, 5);

  auto subset = [&](const std::vector<double>& v) {
    std::vector<double> s(tilted.size());
    for (std::size_t j = 0; j < tilted.size(); ++j) s[j] = v[tilted[j]];
    return s;
  };
  // Rows that are means weigh as their count (the table of the log expanded to its counts).
  const bool weighted = !log.count.empty();
  const std::vector<double> all_w = weighted ? log.count : std::vector<double>{};
  const std::vector<double> tilted_w = weighted ? subset(log.count) : std::vector<double>{};
  const auto ranks = [&](const std::vector<double>& v, const std::vector<double>& w) {
    return weighted ? averageRanks(v, w) : averageRanks(v);
  };
  const auto correlation = [&](const std::vector<double>& a, const std::vector<double>& b,
                               const std::vector<double>& w) { return weighted ? pearson(a, b, w) : pearson(a, b); };
  const auto total = [&](const std::vector<double>& w, std::size_t count) {
    if (!weighted) return count;
    double sum = 0.0;
    for (const double x : w) sum += x;
    return static_cast<std::size_t>(std::llround(sum));
  };
  const std::size_t all_n = total(all_w, n);
  table.samples = {all_n, all_n, all_n, total(tilted_w, tilted.size()), all_n};

  // Rank every variable once on all samples, and once on the tilted subset.
  std::vector<std::vector<double>> row_ranks(6);
  for (std::size_t k = 0; k < 6; ++k) row_ranks[k] = ranks(rows[k], all_w);
  for (std::size_t c = 0; c < 5; ++c) {
    if (c == 3) {
      const auto cr = ranks(subset(cols[c]), tilted_w);
      for (std::size_t k = 0; k < 6; ++k) {
        table.r(static_cast<Eigen::Index>(k), 3) = correlation(ranks(subset(rows[k]), tilted_w), cr, tilted_w);
      }
      continue;
    }
    const auto cr = ranks(cols[c], all_w);
    for (std::size_t k = 0; k < 6; ++k) {
      table.r(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) = correlation(row_ranks[k], cr, all_w);
    }
  }
  return table;
}

}  // namespace geaware::ident
