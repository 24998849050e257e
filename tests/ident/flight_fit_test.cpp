// SPDX-License-Identifier: BSD-3-Clause
// Flight logs: F_G from a hover descent (paper eq. 10) and the drag table D(h).

#include "geaware/ident/flight_fit.hpp"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "synthetic.hpp"

namespace {

using ident_test::dragFlights;
using ident_test::hoverDescent;
using ident_test::withinSigmas;

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

/// The samples of `log` at or above `h_min_m`.
geaware::ident::FlightLog above(const geaware::ident::FlightLog& log, double h_min_m) {
  geaware::ident::FlightLog out;
  out.source = log.source;
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (log.h_m[i] < h_min_m) continue;
    out.t_s.push_back(log.t_s[i]);
    out.h_m.push_back(log.h_m[i]);
    out.a_ext_W[2].push_back(log.a_ext_W[2][i]);
    for (std::size_t k = 0; k < 4; ++k) out.n_rpm[k].push_back(log.n_rpm[k][i]);
  }
  return out;
}

TEST(FlightFit, HoverOutOfGroundEffectGivesKTAlone) {
  // The campaign's hover flight (experiments/calibration.hpp): heights 1.0–1.5 m only, which
  // cannot fix g1, g2, with an observer 3 % high. k_T alone comes back; the full descent warns
  // that it went below 1 m.
  const auto& p = geaware_test::paperParams();
  geaware::model::VehicleParams observer = p;
  observer.rotor.k_T_N_per_rpm2 *= 1.03;
  const auto hover = above(hoverDescent(2, 1.03), 1.0);
  ASSERT_GT(hover.size(), 1000u);
  const auto fit = geaware::ident::fitHoverThrust(hover, observer);
  EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
  EXPECT_LT(fit.k_T_N_per_rpm2.std_error, 1e-3 * p.rotor.k_T_N_per_rpm2);
  EXPECT_TRUE(fit.warnings.empty());
  EXPECT_GE(fit.h_min_m, 1.0);
  const auto low = geaware::ident::fitHoverThrust(hoverDescent(2, 1.03), observer);
  ASSERT_EQ(low.warnings.size(), 1u);
  EXPECT_NE(low.warnings[0].find("below 1 m"), std::string::npos);
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

// A log at one height gives a one-row drag table (the same drag at every height): said in a
// warning, not silent (issue 16); the table of a log that spreads has no such warning.
TEST(FlightFit, OneHeightDragTableIsAWarning) {
  const auto& p = geaware_test::paperParams();
  geaware::ident::DragFitOptions o;
  o.height_bands = 4;
  for (const auto& w : geaware::ident::fitDrag(dragFlights(1), p.mass_kg, o).warnings) {
    EXPECT_EQ(w.find("one row"), std::string::npos) << w;
  }
  auto log = dragFlights(1);
  for (auto& h : log.h_m) h = 0.3;
  const auto fit = geaware::ident::fitDrag(log, p.mass_kg, o);
  ASSERT_EQ(fit.bands.size(), 1u);
  bool said = false;
  for (const auto& w : fit.warnings) said = said || w.find("the drag table has one row (0.3–0.3 m) of the 4") == 0;
  EXPECT_TRUE(said);
}

}  // namespace
