// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A known residual force for the trainer and weight-file tests: the paper vehicle's additional
// ground-effect thrust along the body z axis plus a linear rotor drag,
//   f_W = F_G(h)·T·z_B − d·(v_x, v_y, 0),   F_G(h) = g2/(h² + g1),   T = k_T·Σn²,
// with the coefficients of config/vehicles/paper_quad.yaml (g1 = 1.804e-2 m², g2 = 7.339e-3 m²,
// k_T = 4.0083e-8 N/rpm²) and d = 0.35 N·s/m. Rows are sampled over the range the controller
// flies in near the ground: h log-uniform in [0.1, 1.5] m (denser where F_G is steep), |v| ≤ 1
// m/s per axis, tilt ≤ 15°, rotor speeds 8,000–13,000 rpm (hover ≈ 10,200 rpm).

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "geaware/neural/trainer.hpp"

namespace geaware_test {

struct SyntheticResidual {
  double g1_m2 = 1.804e-2;
  double g2_m2 = 7.339e-3;
  double k_T_N_per_rpm2 = 4.0083e-8;
  double drag_N_per_mps = 0.35;

  [[nodiscard]] Eigen::Vector3d force_W(const geaware::control::ResidualFeatures& f) const {
    const double thrust = k_T_N_per_rpm2 * f.rotor_speeds_rpm.squaredNorm();
    const double ratio = g2_m2 / (f.height_m * f.height_m + g1_m2);
    const Eigen::Vector3d z_B = f.q_WB.normalized() * Eigen::Vector3d::UnitZ();
    return ratio * thrust * z_B - drag_N_per_mps * Eigen::Vector3d(f.v_W.x(), f.v_W.y(), 0.0);
  }

  /// One random sample. Uses only the engine's raw output (fixed by the standard), so the
  /// rows are the same on every platform.
  [[nodiscard]] geaware::control::ResidualFeatures sample(std::mt19937_64& rng) const {
    const auto u = [&rng](double lo, double hi) {
      return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
    };
    geaware::control::ResidualFeatures f;
    f.height_m = 0.1 * std::exp(u(0.0, std::log(15.0)));
    f.v_W = {u(-1.0, 1.0), u(-1.0, 1.0), u(-1.0, 1.0)};
    const double tilt = u(0.0, 15.0) * std::numbers::pi / 180.0;
    const double axis_angle = u(0.0, 2.0 * std::numbers::pi);
    const double yaw = u(-std::numbers::pi, std::numbers::pi);
    f.q_WB =
        Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(axis_angle), std::sin(axis_angle), 0));
    for (int i = 0; i < 4; ++i) f.rotor_speeds_rpm(i) = u(8000.0, 13000.0);
    return f;
  }

  [[nodiscard]] geaware::neural::TrainingSet makeSet(int rows, std::uint64_t seed) const {
    std::mt19937_64 rng(seed);
    geaware::neural::TrainingSet set;
    for (int i = 0; i < rows; ++i) {
      const auto f = sample(rng);
      static_cast<void>(set.add(f, force_W(f)));
    }
    return set;
  }
};

}  // namespace geaware_test
