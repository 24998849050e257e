// SPDX-License-Identifier: BSD-3-Clause
// The residual network: feature layout, inference on hand-computed cases, validation, the
// Lipschitz certificate as a property, and no allocation in predict_W.

#include "geaware/neural/residual_network.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <numbers>
#include <random>

#include "geaware_test/allocation_counter.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace geaware::neural {
namespace {

/// 17 → 2 → 3 with weights that can be followed by hand: hidden unit 0 = ReLU(h̄), hidden
/// unit 1 = ReLU(−v̄_x); output = (2·unit0, 3·unit1, unit0 + unit1) + (0.1, 0.2, 0.3).
NetworkWeights handNetwork() {
  NetworkWeights w;
  DenseLayer hidden{Eigen::MatrixXd::Zero(2, kFeatureCount), Eigen::VectorXd::Zero(2)};
  hidden.weights(0, 0) = 1.0;
  hidden.weights(1, 1) = -1.0;
  DenseLayer out{Eigen::MatrixXd::Zero(3, 2), Eigen::Vector3d(0.1, 0.2, 0.3)};
  out.weights << 2.0, 0.0, 0.0, 3.0, 1.0, 1.0;
  w.layers = {hidden, out};
  w.input_mean(0) = 0.5;  // h̄ = (h − 0.5)/0.25
  w.input_std(0) = 0.25;
  w.input_std(1) = 2.0;  // v̄_x = v_x/2
  return w;
}

/// A random network 17 → 32 → 32 → 3 (seeded), for properties.
NetworkWeights randomNetwork(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto fill = [&rng](Eigen::MatrixXd& m) {
    for (Eigen::Index i = 0; i < m.size(); ++i) {
      m.data()[i] = static_cast<double>(rng() >> 11) * 0x1.0p-53 - 0.5;
    }
  };
  NetworkWeights w;
  const int widths[] = {kFeatureCount, 32, 32, kOutputCount};
  for (int l = 0; l < 3; ++l) {
    DenseLayer d{Eigen::MatrixXd(widths[l + 1], widths[l]), Eigen::VectorXd(widths[l + 1])};
    fill(d.weights);
    Eigen::MatrixXd b(widths[l + 1], 1);
    fill(b);
    d.bias = b;
    w.layers.push_back(d);
  }
  w.input_std.setConstant(0.5);
  return w;
}

bool hasField(const InvalidNetwork& e, const std::string& field) {
  for (const auto& f : e.errors()) {
    if (f.field.rfind(field, 0) == 0) return true;
  }
  return false;
}

TEST(Features, LayoutIsHeightVelocityRotationRowMajorAndScaledRotorSpeeds) {
  control::ResidualFeatures f;
  f.height_m = 0.3;
  f.v_W = {1.0, 2.0, 3.0};
  f.q_WB =
      Eigen::AngleAxisd(std::numbers::pi / 2.0, Eigen::Vector3d::UnitZ());  // x_B = y_W, y_B = −x_W
  f.rotor_speeds_rpm = {10000.0, 12000.0, 9000.0, 11000.0};
  FeatureVector expected;
  expected << 0.3, 1.0, 2.0, 3.0,  //
      0.0, -1.0, 0.0,              // R row 0
      1.0, 0.0, 0.0,               // R row 1
      0.0, 0.0, 1.0,               // R row 2
      1.0, 1.2, 0.9, 1.1;
  EXPECT_MATRIX_NEAR(makeFeatures(f), expected, 1e-15);
  EXPECT_EQ(featureNames()[4], "R_WB.00");
  EXPECT_EQ(featureNames()[13], "rotor_1_rpm/1e4");
}

TEST(Features, AntipodalQuaternionsGiveTheSameFeatures) {
  // The reason for the rotation matrix over the quaternion: q and −q are one attitude.
  control::ResidualFeatures a;
  a.q_WB = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized();
  control::ResidualFeatures b = a;
  b.q_WB.coeffs() = -a.q_WB.coeffs();
  EXPECT_MATRIX_NEAR(makeFeatures(a), makeFeatures(b), 1e-15);
}

TEST(ResidualNetwork, HandComputedOutput) {
  const ResidualNetwork net(handNetwork());
  control::ResidualFeatures f;
  f.height_m = 1.0;  // h̄ = 2 → unit0 = 2
  f.v_W.x() = -3.0;  // v̄_x = −1.5 → unit1 = 1.5
  EXPECT_MATRIX_NEAR(net.predict_W(f), Eigen::Vector3d(4.1, 4.7, 3.8), 1e-14);
  f.height_m = 0.0;  // h̄ = −2 → ReLU cuts unit0
  f.v_W.x() = 1.0;   // v̄_x = 0.5 → ReLU cuts unit1
  EXPECT_MATRIX_NEAR(net.predict_W(f), Eigen::Vector3d(0.1, 0.2, 0.3), 1e-15);
}

TEST(ResidualNetwork, NonFiniteFeaturesGiveZeroNotNaN) {
  const ResidualNetwork net(handNetwork());
  control::ResidualFeatures f;
  f.height_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(net.predict_W(f), Eigen::Vector3d::Zero());
  f.height_m = 1.0;
  f.q_WB.coeffs().setZero();  // normalises to NaN
  EXPECT_EQ(net.predict_W(f), Eigen::Vector3d::Zero());
}

TEST(ResidualNetwork, LipschitzBoundIsProductOfSpectralNorms) {
  // Hidden W has singular values 1, 1; the output W = [[2,0],[0,3],[1,1]] has
  // σ_max² = largest eigenvalue of WᵀW = [[5,1],[1,10]] = (15 + √29)/2.
  const ResidualNetwork net(handNetwork());
  EXPECT_NEAR(net.lipschitzBound(), std::sqrt((15.0 + std::sqrt(29.0)) / 2.0), 1e-13);
}

TEST(ResidualNetwork, OutputChangeIsBoundedByLipschitzBound) {
  // Property: ‖f(x) − f(y)‖ ≤ L·‖x̄ − ȳ‖ for the standardised features, on random pairs.
  const ResidualNetwork net(randomNetwork(11));
  const FeatureVector inv_std = net.weights().input_std.cwiseInverse();
  std::mt19937_64 rng(5);
  const auto u = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53 * 4.0 - 2.0; };
  for (int i = 0; i < 1000; ++i) {
    FeatureVector x, y;
    for (int k = 0; k < kFeatureCount; ++k) {
      x(k) = u();
      y(k) = x(k) + 0.1 * u();
    }
    const double lhs = (net.predictFeatures(x) - net.predictFeatures(y)).norm();
    const double rhs = net.lipschitzBound() * (x - y).cwiseProduct(inv_std).norm();
    EXPECT_LE(lhs, rhs * (1.0 + 1e-12)) << "pair " << i;
  }
}

TEST(ResidualNetwork, RejectsInvalidWeightsNamingTheField) {
  {
    NetworkWeights w = handNetwork();
    w.layers[0].weights.resize(2, 16);  // the first layer must take 17 features
    try {
      ResidualNetwork net(w);
      FAIL() << "accepted 2x16 first layer";
    } catch (const InvalidNetwork& e) {
      EXPECT_TRUE(hasField(e, "layers[0].weights")) << e.what();
    }
  }
  {
    NetworkWeights w = handNetwork();
    w.layers[1].bias(2) = std::numeric_limits<double>::quiet_NaN();
    try {
      ResidualNetwork net(w);
      FAIL() << "accepted NaN bias";
    } catch (const InvalidNetwork& e) {
      EXPECT_TRUE(hasField(e, "layers[1].bias")) << e.what();
    }
  }
  {
    NetworkWeights w = handNetwork();
    w.input_std(5) = 0.0;
    try {
      ResidualNetwork net(w);
      FAIL() << "accepted zero std";
    } catch (const InvalidNetwork& e) {
      EXPECT_TRUE(hasField(e, "input_std[5]")) << e.what();
    }
  }
  {
    NetworkWeights w = handNetwork();
    w.lipschitz_gamma = 1.0;  // the true bound is ≈ 3.2: the claim is false
    try {
      ResidualNetwork net(w);
      FAIL() << "accepted a false Lipschitz claim";
    } catch (const InvalidNetwork& e) {
      EXPECT_TRUE(hasField(e, "lipschitz_gamma")) << e.what();
    }
  }
  {
    NetworkWeights w = handNetwork();
    w.layers.pop_back();  // 17 → 2: the output must have 3 components
    EXPECT_THROW(ResidualNetwork{w}, InvalidNetwork);
  }
}

TEST(ResidualNetwork, PredictDoesNotAllocate) {
  const ResidualNetwork net(randomNetwork(3));
  control::ResidualFeatures f;
  f.height_m = 0.4;
  f.v_W = {0.3, -0.2, 0.1};
  f.rotor_speeds_rpm.setConstant(10500.0);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const long before = geaware_test::allocationCount();
  for (int i = 0; i < 100; ++i) {
    f.height_m += 0.001;
    sum += net.predict_W(f);
  }
  const long after = geaware_test::allocationCount();
  EXPECT_EQ(after - before, 0);
  EXPECT_TRUE(sum.allFinite());
}

TEST(ResidualNetwork, AllocationCounterSeesAllocations) {
  // Guards the test above: the counters are in effect, for operator new and for Eigen.
  long before = geaware_test::allocationCount();
  auto* p = new int(3);
  EXPECT_GE(geaware_test::allocationCount() - before, 1);
  delete p;
#if defined(__GLIBC__)
  before = geaware_test::allocationCount();
  Eigen::MatrixXd m = Eigen::MatrixXd::Random(40, 40);
  EXPECT_GE(geaware_test::allocationCount() - before, 1);
  EXPECT_TRUE(m.allFinite());
#endif
}

}  // namespace
}  // namespace geaware::neural
