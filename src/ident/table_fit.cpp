// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/table_fit.hpp"

#include <algorithm>
#include <cmath>

#include "fit_support.hpp"

namespace geaware::ident {

std::vector<double> chooseKnots(const std::vector<double>& h, const TableOptions& options,
                                const std::string& source, const std::string& what) {
  using detail::num;
  if (!options.heights_m.empty()) {
    const auto& k = options.heights_m;
    for (std::size_t i = 0; i < k.size(); ++i) {
      if (!std::isfinite(k[i]) || !(k[i] > 0.0) || (i > 0 && !(k[i] > k[i - 1]))) {
        throw IdentError(source + ": cannot fit " + what + ": knot heights must be positive and " +
                         "strictly increasing (knot " + std::to_string(i) + " is " + num(k[i]) +
                         " m)");
      }
    }
    if (k.size() < 2) {
      throw IdentError(source + ": cannot fit " + what + ": a table needs at least 2 knots");
    }
    return k;
  }
  // Distinct heights to 0.1 mm, with their sample counts.
  std::vector<double> sorted;
  sorted.reserve(h.size());
  for (double x : h) {
    if (x <= options.top_m) sorted.push_back(std::round(x * 1e4) / 1e4);
  }
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> knots;
  if (sorted.empty()) {
    knots = {};
  } else {
    std::vector<double> distinct;
    for (double x : sorted) {
      if (distinct.empty() || x != distinct.back()) distinct.push_back(x);
    }
    if (distinct.size() <= options.max_knots) {
      knots = std::move(distinct);
    } else {
      // Thin by sample count: knots at equally spaced quantiles of the samples.
      const std::size_t m = std::max<std::size_t>(options.max_knots, 2);
      for (std::size_t q = 0; q < m; ++q) {
        const double x = sorted[q * (sorted.size() - 1) / (m - 1)];
        if (knots.empty() || x > knots.back()) knots.push_back(x);
      }
    }
  }
  if (knots.size() < 2) {
    throw IdentError(source + ": cannot fit " + what + " as a table: the samples span " +
                     std::to_string(knots.size()) + " distinct height(s) up to " +
                     num(options.top_m) + " m, at least 2 are needed");
  }
  return knots;
}

int tableBasis(const std::vector<double>& k, double h, int* index, double* weight) noexcept {
  const std::size_t n = k.size();
  if (h <= k.front()) {
    index[0] = 0;
    weight[0] = 1.0;
    return 1;
  }
  if (h >= k.back()) {
    const double r = k.back() / h;
    index[0] = static_cast<int>(n - 1);
    weight[0] = r * r;
    return 1;
  }
  const auto it = std::upper_bound(k.begin(), k.end(), h);
  const auto j = static_cast<std::size_t>(it - k.begin());  // k[j-1] < h < k[j] (or = k[j-1])
  const double t = (h - k[j - 1]) / (k[j] - k[j - 1]);
  index[0] = static_cast<int>(j - 1);
  weight[0] = 1.0 - t;
  if (t == 0.0) return 1;
  index[1] = static_cast<int>(j);
  weight[1] = t;
  return 2;
}

double tableValue(const std::vector<double>& knots, const std::vector<double>& values,
                  double h) noexcept {
  int index[2];
  double weight[2];
  const int n = tableBasis(knots, h, index, weight);
  double v = 0.0;
  for (int e = 0; e < n; ++e) v += weight[e] * values[static_cast<std::size_t>(index[e])];
  return v;
}

}  // namespace geaware::ident
