// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Comparison of Eigen matrices in tests: on failure both sides and the largest difference are
// printed, so a failing test says what was expected and what came out.

#include <sstream>
#include <string>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace geaware_test {

template <typename A, typename B>
::testing::AssertionResult matricesNear(const char* a_expr, const char* b_expr,
                                        const char* /*tol_expr*/, const Eigen::MatrixBase<A>& a,
                                        const Eigen::MatrixBase<B>& b, double tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure()
           << a_expr << " is " << a.rows() << "x" << a.cols() << " but " << b_expr << " is "
           << b.rows() << "x" << b.cols();
  }
  const double diff = (a.template cast<double>() - b.template cast<double>()).cwiseAbs().maxCoeff();
  if (diff <= tol) return ::testing::AssertionSuccess();
  const Eigen::IOFormat fmt(Eigen::FullPrecision, 0, ", ", ";\n", "[", "]");
  std::ostringstream os;
  os << "max |" << a_expr << " - " << b_expr << "| = " << diff << " > " << tol << "\n"
     << a_expr << " =\n"
     << a.format(fmt) << "\n"
     << b_expr << " =\n"
     << b.format(fmt);
  return ::testing::AssertionFailure() << os.str();
}

}  // namespace geaware_test

/// EXPECT_MATRIX_NEAR(a, b, tol): element-wise |a − b| ≤ tol, printing both on failure.
#define EXPECT_MATRIX_NEAR(a, b, tol) EXPECT_PRED_FORMAT3(::geaware_test::matricesNear, a, b, tol)
#define ASSERT_MATRIX_NEAR(a, b, tol) ASSERT_PRED_FORMAT3(::geaware_test::matricesNear, a, b, tol)
