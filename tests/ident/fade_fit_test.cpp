// SPDX-License-Identifier: BSD-3-Clause
// The ground effect's forward-flight fade (ident/fade_fit.hpp) from synthetic flights whose whole
// z_B force follows the model with known k_T', c_TL, s and v_i, with seeded noise.

#include "geaware/ident/fade_fit.hpp"

#include <cmath>
#include <random>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/model/ground_effect.hpp"
#include "synthetic.hpp"

namespace {

using ident_test::withinSigmas;

struct Truth {
  double k_T = 4.0e-8;   // the flight's [N/rpm²]
  double c_TL = 0.002;   // [s²/m²]
  double s = 0.45;       // [-]
  double v_i = 8.26;     // [m/s]
};

// Straight runs at `heights` and speeds 0…5 m/s, pitched forward by the drag tilt; the observer
// ran with a k_T 3 % high. Noise of σ = 0.15 N on the z_B force.
geaware::ident::FlightLog runs(const Truth& t, std::vector<double> heights, double max_speed_mps, std::uint64_t seed) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::GroundEffectModel ge(p);
  const double m = p.mass_kg, k_obs = 1.03 * p.rotor.k_T_N_per_rpm2;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.15);
  geaware::ident::FlightLog log;
  log.source = "runs";
  std::size_t i = 0;
  for (const double h : heights) {
    for (int k = 0; k < 600; ++k, ++i) {
      const double V = max_speed_mps * static_cast<double>(k % 100) / 99.0;
      const double heading = 0.01 * k;
      const Eigen::Vector3d v(V * std::cos(heading), V * std::sin(heading), 0.0);
      const double pitch = 0.02 * V;  // tilted into the motion
      const Eigen::Quaterniond q(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
      const double n = 10000.0 + 50.0 * static_cast<double>(k % 7);
      const double S = 4.0 * n * n;
      const double fade = t.v_i * t.v_i / (t.v_i * t.v_i + V * V);
      const double along_z_B = t.k_T * S * (1.0 + t.c_TL * V * V + t.s * ge.thrustRatio(h) * fade) + noise(rng);
      // a_ext with m·z_Bᵀa_ext + k_obs·S = along_z_B, and an in-plane part the fit must ignore.
      const Eigen::Matrix3d R = q.toRotationMatrix();
      const Eigen::Vector3d a = R * Eigen::Vector3d(-0.3 * V, 0.1, (along_z_B - k_obs * S) / m);
      log.t_s.push_back(0.01 * static_cast<double>(i));
      log.h_m.push_back(h);
      for (int c = 0; c < 3; ++c) log.v_W[static_cast<std::size_t>(c)].push_back(v[c]);
      for (int c = 0; c < 3; ++c) log.a_ext_W[static_cast<std::size_t>(c)].push_back(a[c]);
      log.q_WB[0].push_back(q.w()), log.q_WB[1].push_back(q.x()), log.q_WB[2].push_back(q.y()), log.q_WB[3].push_back(q.z());
      for (auto& r : log.n_rpm) r.push_back(n);
    }
  }
  return log;
}

geaware::model::VehicleParams observer() {
  auto p = geaware_test::paperParams();
  p.rotor.k_T_N_per_rpm2 *= 1.03;
  return p;
}

TEST(FadeFit, RunsLowAndHighRecoverTheFadeApartFromTranslationalLift) {
  const Truth t;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    const auto fit = geaware::ident::fitForwardFade(runs(t, {0.15, 0.25, 1.5}, 5.0, seed), observer());
    EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, t.k_T));
    EXPECT_TRUE(withinSigmas(fit.translational_lift_per_mps2, t.c_TL));
    EXPECT_TRUE(withinSigmas(fit.cushion_scale, t.s));
    EXPECT_TRUE(withinSigmas(fit.w_s2_per_m2, 1.0 / (t.v_i * t.v_i)));
    EXPECT_NEAR(fit.induced_velocity_mps.value, t.v_i, 4.0 * fit.induced_velocity_mps.std_error);
    EXPECT_LT(fit.induced_velocity_mps.std_error, 0.15 * t.v_i);
    EXPECT_TRUE(fit.blocking.empty());
    EXPECT_EQ(fit.far_from_ground, 480u);  // the 1.5 m run above 1 m/s
  }
}

TEST(FadeFit, NoFadeInTheDataIsSaidAndBlocks) {
  Truth t;
  t.v_i = 1e6;  // no fade
  const auto fit = geaware::ident::fitForwardFade(runs(t, {0.15, 0.25, 1.5}, 5.0, 4), observer());
  ASSERT_FALSE(fit.blocking.empty()) << fit.w_s2_per_m2.value << " +- " << fit.w_s2_per_m2.std_error << " v_i "
                                     << fit.induced_velocity_mps.value;
  const std::string& b = fit.blocking.front();
  EXPECT_TRUE(b.find("no forward-flight fade in the data") != std::string::npos ||
              b.find("within 2 standard errors of no fade") != std::string::npos)
      << b;
  // w at 0 (v_i NaN) or within 2 standard errors of it: either way --out gets no v_i.
}

TEST(FadeFit, OneHeightCannotTellTheFadeFromTranslationalLiftAndSaysSo) {
  const auto fit = geaware::ident::fitForwardFade(runs(Truth{}, {0.2}, 5.0, 5), observer());
  bool said = false;
  for (const auto& w : fit.warnings) said = said || w.find("only 0 samples out of ground effect") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(FadeFit, AFlightFarFromTheGroundIsRefused) {
  EXPECT_THROW((void)geaware::ident::fitForwardFade(runs(Truth{}, {2.0}, 5.0, 6), observer()),
               geaware::ident::IdentError);
}

}  // namespace
