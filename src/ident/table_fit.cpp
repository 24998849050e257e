// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/table_fit.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "fit_support.hpp"

namespace geaware::ident {

namespace {

/// The distinct values of round(x·1e4)/1e4 over the x ≤ top in h, ascending, with how often
/// each occurs: what sorting those values and counting runs gives, without sorting them all
/// (a platform logs many samples at few heights). Nothing when there are many distinct values
/// or a −0 (which equals +0, so a sort may put either first) or a NaN: then sort.
std::optional<std::pair<std::vector<double>, std::vector<std::size_t>>> distinctCounts(
    const std::vector<double>& h, double top) {
  constexpr std::size_t kMaxDistinct = 4096;
  std::vector<double> distinct;
  std::vector<std::size_t> count;
  std::size_t last = 0;  // index of the previous value's entry: logs repeat heights in runs
  for (const double x : h) {
    if (!(x <= top)) {
      if (std::isnan(x)) return std::nullopt;
      continue;
    }
    const double v = std::round(x * 1e4) / 1e4;
    if (v == 0.0 && std::signbit(v)) return std::nullopt;
    if (!distinct.empty() && distinct[last] == v) {
      ++count[last];
      continue;
    }
    const auto it = std::lower_bound(distinct.begin(), distinct.end(), v);
    last = static_cast<std::size_t>(it - distinct.begin());
    if (it != distinct.end() && *it == v) {
      ++count[last];
      continue;
    }
    if (distinct.size() == kMaxDistinct) return std::nullopt;
    distinct.insert(it, v);
    count.insert(count.begin() + static_cast<std::ptrdiff_t>(last), 1);
  }
  if (distinct.empty()) return std::nullopt;
  return std::pair{std::move(distinct), std::move(count)};
}

}  // namespace

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
  // Distinct heights to 0.1 mm; when there are more than max_knots, thinned by sample count:
  // knots at equally spaced quantiles of the samples, at(r) the r-th smallest of `total`
  // rounded heights (r non-decreasing from call to call).
  const auto thin = [&options](std::vector<double> distinct, std::size_t total, auto&& at) {
    if (distinct.size() <= options.max_knots) return distinct;
    std::vector<double> k;
    const std::size_t m = std::max<std::size_t>(options.max_knots, 2);
    for (std::size_t q = 0; q < m; ++q) {
      const double x = at(q * (total - 1) / (m - 1));
      if (k.empty() || x > k.back()) k.push_back(x);
    }
    return k;
  };
  std::vector<double> knots;
  if (auto counted = distinctCounts(h, options.top_m)) {
    // Named references, not a structured binding: clang 14 cannot capture bindings in lambdas.
    const std::vector<double>& distinct = counted->first;
    const std::vector<std::size_t>& count = counted->second;
    std::size_t total = 0;
    for (const std::size_t c : count) total += c;
    // The r-th smallest is the distinct height whose cumulative count first exceeds r.
    std::size_t d = 0;
    std::size_t through = count[0];  // heights up to and including distinct[d]
    knots = thin(distinct, total, [&](std::size_t r) {
      while (through <= r) through += count[++d];
      return distinct[d];
    });
  } else {
    std::vector<double> sorted;
    sorted.reserve(h.size());
    for (double x : h) {
      if (x <= options.top_m) sorted.push_back(std::round(x * 1e4) / 1e4);
    }
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> distinct;
    for (double x : sorted) {
      if (distinct.empty() || x != distinct.back()) distinct.push_back(x);
    }
    knots = thin(std::move(distinct), sorted.size(), [&sorted](std::size_t r) { return sorted[r]; });
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
