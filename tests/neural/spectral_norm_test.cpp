// SPDX-License-Identifier: BSD-3-Clause
// Spectral norm: the exact SVD value on closed-form matrices, and the power iteration of
// spectral normalisation (Miyato et al. 2018) against it.

#include "geaware/neural/spectral_norm.hpp"

#include <gtest/gtest.h>

#include <random>

namespace geaware::neural {
namespace {

Eigen::MatrixXd randomMatrix(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    m.data()[i] = static_cast<double>(rng() >> 11) * 0x1.0p-53 - 0.5;
  }
  return m;
}

TEST(SpectralNorm, DiagonalMatrixGivesLargestAbsoluteEntry) {
  const Eigen::MatrixXd d = Eigen::Vector3d(3.0, -5.0, 1.0).asDiagonal();
  EXPECT_NEAR(spectralNorm(d), 5.0, 1e-14);
}

TEST(SpectralNorm, RankOneMatrixGivesProductOfNorms) {
  // σ_max(u vᵀ) = ‖u‖·‖v‖ exactly.
  const Eigen::Vector3d u(1.0, 2.0, 2.0);       // ‖u‖ = 3
  const Eigen::Vector4d v(0.0, 3.0, 4.0, 0.0);  // ‖v‖ = 5
  EXPECT_NEAR(spectralNorm(Eigen::MatrixXd(u * v.transpose())), 15.0, 1e-13);
}

TEST(PowerIteration, ConvergesToSvdValueFromBelow) {
  const Eigen::MatrixXd w = randomMatrix(32, 17, 7);
  const double exact = spectralNorm(w);
  Eigen::VectorXd v;
  double previous = 0.0;
  for (int k = 1; k <= 200; ++k) {
    const double estimate = powerIterationNorm(w, v, 1);  // warm-started, one step at a time
    // ‖Wᵀu‖ with ‖u‖ = 1 is a lower bound of σ_max; a few ulps of rounding allowed.
    EXPECT_LE(estimate, exact * (1.0 + 1e-14)) << "iteration " << k;
    // Warm-started power iteration is monotone in exact arithmetic.
    EXPECT_GE(estimate, previous * (1.0 - 1e-14)) << "iteration " << k;
    previous = estimate;
  }
  EXPECT_NEAR(previous, exact, 1e-9 * exact);
}

TEST(PowerIteration, WorksOnFloatMapsOfTransposedStorage) {
  // The trainer runs it on dlib's row-major float storage of Wᵀ: same σ_max.
  const Eigen::MatrixXd w = randomMatrix(8, 5, 3);
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> w_t =
      w.transpose().cast<float>();
  Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> map(w_t.data(),
                                                                                        5, 8);
  Eigen::VectorXf v;
  EXPECT_NEAR(powerIterationNorm(map, v, 100), spectralNorm(w), 1e-5);
}

TEST(PowerIteration, ZeroMatrixGivesZero) {
  Eigen::VectorXd v;
  EXPECT_EQ(powerIterationNorm(Eigen::MatrixXd::Zero(4, 3), v, 5), 0.0);
}

}  // namespace
}  // namespace geaware::neural
