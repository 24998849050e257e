// Flight logs: F_G from a hover descent (paper eq. 10) and the drag table D(h).

#include "geaware/ident/flight_fit.hpp"

#include <cmath>
#include <random>

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
