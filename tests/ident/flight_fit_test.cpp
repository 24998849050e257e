// Flight logs: F_G from a hover descent (paper eq. 10) and the drag table D(h).

#include "geaware/ident/flight_fit.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "synthetic.hpp"

namespace {

using ident_test::withinSigmas;

/// Hover descent from 1.5 m to 0.075 m: speeds hold m·g = T·(1 + F_G(h)); the observer's
/// external acceleration is F_G·T/m plus noise.
/// `observer_k_T_scale`: the observer's k_T relative to the truth's (1: right).
geaware::ident::FlightLog hoverDescent(std::uint64_t seed, double observer_k_T_scale = 1.0) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::GroundEffectModel ge(p);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  geaware::ident::FlightLog log;
  log.source = "hover_" + std::to_string(seed);
  const int n = 12000;  // 60 s at 200 Hz
  for (int i = 0; i < n; ++i) {
    const double h = 1.5 - (1.5 - 0.075) * i / (n - 1.0);
    const double T = p.mass_kg * geaware::model::kGravity / (1.0 + ge.thrustRatio(h));
    const double rpm = std::sqrt(T / (4.0 * p.rotor.k_T_N_per_rpm2));
    log.t_s.push_back(0.005 * i);
    log.h_m.push_back(h);
    // The observer explains k_T,obs·Σn² = observer_k_T_scale·T of the total T·(1 + F_G).
    log.a_ext_W[2].push_back((T * (1.0 + ge.thrustRatio(h)) - observer_k_T_scale * T) / p.mass_kg +
                             0.05 * noise(rng));
    for (auto& c : log.n_rpm) c.push_back(rpm);
  }
  return log;
}

TEST(FlightFit, HoverDescentRecoversFG) {
  const auto& p = geaware_test::paperParams();
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    const auto fit = geaware::ident::fitHoverAdditionalThrust(hoverDescent(seed), p.mass_kg,
                                                              p.rotor.k_T_N_per_rpm2);
    EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
    EXPECT_TRUE(withinSigmas(fit.g1_m2, p.additional_thrust.g1_m2));
    EXPECT_TRUE(withinSigmas(fit.g2_m2, p.additional_thrust.g2_m2));
    EXPECT_NEAR(fit.stats.residual_rms, 0.05 * p.mass_kg, 0.01 * p.mass_kg);
  }
}

TEST(FlightFit, HoverDescentFindsTheTrueKTWhenTheObserversIsOff) {
  // The observer ran with a k_T 3 % too high: it attributes 3 % too much to the rotors and its
  // a_ext is 3 % of T short everywhere. The fit gives the true k_T and the true F_G, where the
  // paper's eq. 10 with the observer's k_T would put F_G 3 % too low at every height.
  const auto& p = geaware_test::paperParams();
  const auto fit = geaware::ident::fitHoverAdditionalThrust(hoverDescent(4, 1.03), p.mass_kg,
                                                            1.03 * p.rotor.k_T_N_per_rpm2);
  EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
  EXPECT_LT(fit.k_T_N_per_rpm2.std_error, 1e-3 * p.rotor.k_T_N_per_rpm2);
  EXPECT_TRUE(withinSigmas(fit.g1_m2, p.additional_thrust.g1_m2));
  EXPECT_TRUE(withinSigmas(fit.g2_m2, p.additional_thrust.g2_m2));
}

/// Flights at four heights with random velocities and attitudes; the external acceleration is
/// (f_D + f_G)/m plus noise, f_D from the vehicle's drag table.
geaware::ident::FlightLog dragFlights(std::uint64_t seed) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::RotorDragModel drag(p.drag);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  geaware::ident::FlightLog log;
  log.source = "flight_" + std::to_string(seed);
  const std::vector<double> heights = {0.1, 0.2, 0.5, 2.0};
  for (int i = 0; i < 8000; ++i) {
    const double h = heights[static_cast<std::size_t>(i / 2000)];
    const Eigen::Quaterniond q =
        Eigen::AngleAxisd(6.283 * unit(rng), Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(0.3 * (unit(rng) - 0.5), Eigen::Vector3d::UnitY()) *
        Eigen::AngleAxisd(0.3 * (unit(rng) - 0.5), Eigen::Vector3d::UnitX());
    const Eigen::Matrix3d R = q.toRotationMatrix();
    const Eigen::Vector3d v(4.0 * (unit(rng) - 0.5), 4.0 * (unit(rng) - 0.5), 0.5 * (unit(rng) - 0.5));
    const Eigen::Vector3d f = geaware::model::RotorDragModel::force_W(R, v, drag.coefficients(h)) +
                              2.0 * R.col(2);  // an additional thrust along z_B: must not matter
    log.t_s.push_back(0.005 * i);
    log.h_m.push_back(h);
    for (int k = 0; k < 3; ++k) {
      log.v_W[static_cast<std::size_t>(k)].push_back(v(k));
      log.a_ext_W[static_cast<std::size_t>(k)].push_back(f(k) / p.mass_kg + 0.05 * noise(rng));
    }
    log.q_WB[0].push_back(q.w());
    log.q_WB[1].push_back(q.x());
    log.q_WB[2].push_back(q.y());
    log.q_WB[3].push_back(q.z());
    for (auto& c : log.n_rpm) c.push_back(10000.0);
  }
  return log;
}

TEST(FlightFit, DragTablePerHeight) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::RotorDragModel truth(p.drag);
  geaware::ident::DragFitOptions o;
  o.height_bands = 4;
  const auto fit = geaware::ident::fitDrag(dragFlights(1), p.mass_kg, o);
  ASSERT_EQ(fit.bands.size(), 4u);
  for (const auto& b : fit.bands) {
    SCOPED_TRACE(b.h_mean_m);
    const Eigen::Vector2d d = truth.coefficients(b.h_mean_m);
    EXPECT_TRUE(withinSigmas(b.d_x_N_per_mps, d.x()));
    EXPECT_TRUE(withinSigmas(b.d_y_N_per_mps, d.y()));
  }
  const auto table = geaware::ident::dragTable(fit);
  EXPECT_EQ(table.heights_m, (std::vector<double>{0.1, 0.2, 0.5, 2.0}));
}

}  // namespace
