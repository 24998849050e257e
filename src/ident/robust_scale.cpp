// SPDX-License-Identifier: BSD-3-Clause
// The robust scale of least_squares.hpp: 1.4826·MAD of the residuals, as the fits re-estimate
// it in their first iterations (robustSigma, RobustScale).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "geaware/ident/least_squares.hpp"

namespace geaware::ident {

namespace {

struct Identity {
  double operator()(double x) const noexcept { return x; }
};

/// The k-th smallest of f(v[i]) (0-based) when a sample brackets it; false otherwise (the
/// caller then selects from all values). On many values, the order statistics of an evenly
/// spaced sample of 1024 of them bracket the k-th in a window of about 1/8 of the values: one
/// pass counts those below the window and copies those in it, and only the window is selected
/// from. The pass has no data-dependent branch (every value of a block is written, the count
/// advances only for those in the window): the window holds the same values in the same order
/// as a pass with branches, so std::nth_element on it gives the same value whatever the values
/// are (NaN and ties included).
template <class F>
bool selectInWindow(std::span<const double> v, std::size_t k, F f, detail::ValueBuffer& window,
                    detail::ValueBuffer* inner, double& out) {
  constexpr std::size_t kSample = 1024;
  constexpr std::ptrdiff_t kMargin = 64;  // sample ranks either side: ~4 standard deviations
  const std::size_t n = v.size();
  if (n < 8 * kSample) return false;
  std::array<double, kSample> sample{};
  const std::size_t stride = n / kSample;
  bool sample_nan = false;
  for (std::size_t i = 0; i < kSample; ++i) {
    sample[i] = f(v[i * stride]);
    sample_nan = sample_nan || std::isnan(sample[i]);
  }
  const auto rank = static_cast<std::ptrdiff_t>(static_cast<double>(k) / static_cast<double>(n) * kSample);
  const std::ptrdiff_t lo_rank = rank - kMargin;
  const std::ptrdiff_t hi_rank = rank + kMargin;
  constexpr auto kSampleRanks = static_cast<std::ptrdiff_t>(kSample);
  // The sample's order statistics at lo_rank and hi_rank: selected, which gives the values a
  // sort gives (the bounds are only compared with, so a −0 for a +0 changes nothing); a sample
  // with NaN is sorted, as it always was.
  if (sample_nan) {
    std::sort(sample.begin(), sample.end());
  } else {
    auto rest = sample.begin();
    if (lo_rank >= 0) {
      std::nth_element(sample.begin(), sample.begin() + lo_rank, sample.end());
      rest = sample.begin() + lo_rank + 1;
    }
    if (hi_rank < kSampleRanks) std::nth_element(rest, sample.begin() + hi_rank, sample.end());
  }
  constexpr double kUnbounded = std::numeric_limits<double>::infinity();
  const double lo = lo_rank < 0 ? -kUnbounded : sample[static_cast<std::size_t>(lo_rank)];
  const double hi = hi_rank >= kSampleRanks ? kUnbounded : sample[static_cast<std::size_t>(hi_rank)];
  double* const w = window.get(n);
  std::size_t below = 0;
  std::size_t count = 0;
  std::size_t nan = 0;
  // Per block: flags and counts first (a loop without branches the compiler vectorizes), then,
  // if any value of the block lies in the window, the copy.
  constexpr std::size_t kBlock = 64;
  std::array<unsigned char, kBlock> in{};
  for (std::size_t first = 0; first < n; first += kBlock) {
    const double* const b = v.data() + first;
    const std::size_t m = std::min(kBlock, n - first);
    std::size_t block_below = 0;
    std::size_t block_in = 0;
    std::size_t block_nan = 0;
    for (std::size_t j = 0; j < m; ++j) {
      const double x = f(b[j]);
      block_nan += static_cast<unsigned char>(std::isnan(x));
      const auto is_below = static_cast<unsigned char>(x < lo);
      const auto is_in = static_cast<unsigned char>(static_cast<unsigned char>(!(x < lo)) & static_cast<unsigned char>(!(x > hi)));
      in[j] = is_in;
      block_below += is_below;
      block_in += is_in;
    }
    below += block_below;
    nan += block_nan;
    if (block_in == 0) continue;
    for (std::size_t j = 0; j < m; ++j) {
      w[count] = f(b[j]);
      count += in[j];
    }
  }
  if (!(below <= k && k < below + count)) return false;
  // A large window without NaN is bracketed once more, by a sample of its own values (`inner`
  // holds the window's window). Without NaN the k-th smallest is one value whichever exact
  // selection finds it (only a −0 and a +0, equal, may come out either way); with NaN the
  // comparisons are no order, and only the same steps as before give the same value.
  if (inner != nullptr && nan == 0 &&
      selectInWindow(std::span<const double>(w, count), k - below, Identity{}, *inner, nullptr, out)) {
    return true;
  }
  double* const at = w + (k - below);
  std::nth_element(w, at, w + count);
  out = *at;
  return true;
}

}  // namespace

double RobustScale::kthSmallest(std::span<const double> v, std::size_t k) {
  double out = 0.0;
  if (selectInWindow(v, k, Identity{}, window_, &inner_, out)) return out;
  values_.assign(v.begin(), v.end());
  const auto at = values_.begin() + static_cast<std::ptrdiff_t>(k);
  std::nth_element(values_.begin(), at, values_.end());
  return *at;
}

// The steps of robustSigma on a copy of v (median, |v − median| in place, its median), each
// selection as kthSmallest does it; the copy is made only where a selection reorders it.
double RobustScale::sigma(std::span<const double> v) {
  if (v.empty()) return kNaN;
  const std::size_t mid = v.size() / 2;
  std::span<const double> current = v;  // the copy's contents before the second step
  double median = 0.0;
  if (!selectInWindow(v, mid, Identity{}, window_, &inner_, median)) {
    values_.assign(v.begin(), v.end());
    std::nth_element(values_.begin(), values_.begin() + static_cast<std::ptrdiff_t>(mid), values_.end());
    median = values_[mid];
    current = values_;
  }
  const auto deviation = [median](double x) { return std::abs(x - median); };
  double mad = 0.0;
  if (!selectInWindow(current, mid, deviation, window_, &inner_, mad)) {
    if (current.data() != values_.data()) values_.assign(v.begin(), v.end());
    for (double& x : values_) x = deviation(x);
    std::nth_element(values_.begin(), values_.begin() + static_cast<std::ptrdiff_t>(mid), values_.end());
    mad = values_[mid];
  }
  return 1.482602218505602 * mad;
}

double robustSigma(std::vector<double> v) { return RobustScale().sigma(v); }

}  // namespace geaware::ident
