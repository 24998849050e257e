// SPDX-License-Identifier: BSD-3-Clause
// Tabulated ground-effect curves (model::HeightTable and GroundEffectModel with tables): the
// interpolant passes through the knots, is C¹, never overshoots the data, reproduces the paper's
// closed forms when sampled from them, and decays as 1/h² above the table.
#include "geaware/model/height_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/model/ground_effect.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using geaware::model::GroundEffectModel;
using geaware::model::HeightTable;
using geaware::model::VehicleParams;
using geaware_test::paperParams;

std::vector<double> grid(double from, double to, double step) {
  std::vector<double> v;
  for (int k = 0; from + k * step <= to + 1e-12; ++k) v.push_back(from + k * step);
  return v;
}

/// The paper vehicle with both curves replaced by tables sampled from its own closed forms.
VehicleParams tabulatedPaperParams(const std::vector<double>& knots) {
  VehicleParams p = paperParams();
  const GroundEffectModel formula(p);
  p.additional_thrust.table.heights_m = knots;
  p.leveling_torque.table.heights_m = knots;
  for (double h : knots) {
    p.additional_thrust.table.values.push_back(formula.thrustRatio(h));
    p.leveling_torque.table.values.push_back(formula.levelingCoefficient(h));
  }
  // The closed forms' parameters are ignored once a table is given: spoil them to prove it.
  p.additional_thrust.g1_m2 = p.additional_thrust.g2_m2 = 1e3;
  p.leveling_torque.scale_m4 = 0.0;
  return p;
}

TEST(HeightTable, PassesThroughEveryKnot) {
  const std::vector<double> h = {0.05, 0.07, 0.1, 0.2, 0.5};
  const std::vector<double> v = {0.4, 0.33, 0.28, 0.13, 0.02};
  const HeightTable t(h, v);
  for (std::size_t i = 0; i < h.size(); ++i) EXPECT_DOUBLE_EQ(t.value(h[i]), v[i]) << i;
}

TEST(HeightTable, ReproducesLinearDataOnInteriorIntervals) {
  // Equal secants make every interior slope the secant, so each interior piece is the line.
  const std::vector<double> h = {0.1, 0.15, 0.3, 0.35, 0.6, 0.8};
  std::vector<double> v;
  for (double x : h) v.push_back(2.0 - 1.5 * x);
  const HeightTable t(h, v);
  for (double x = 0.1; x < 0.6; x += 0.0037) {
    EXPECT_NEAR(t.value(x), 2.0 - 1.5 * x, 1e-12) << x;
    EXPECT_NEAR(t.slope(x), -1.5, 1e-9) << x;
  }
}

TEST(HeightTable, NeverOvershootsMonotoneDataEvenAtASharpStep) {
  // A collapse like the leveling torque's where the slipstreams merge: flat, then a drop by
  // a factor 12 within two knots, then flat. An unconstrained cubic spline rings here.
  const std::vector<double> h = {0.25, 0.26, 0.27, 0.28, 0.29, 0.30, 0.31, 0.32};
  const std::vector<double> v = {0.17, 0.17, 0.171, 0.16, 0.03, 0.014, 0.014, 0.013};
  const HeightTable t(h, v);
  for (std::size_t k = 0; k + 1 < h.size(); ++k) {
    const double lo = std::min(v[k], v[k + 1]);
    const double hi = std::max(v[k], v[k + 1]);
    for (double x = h[k]; x <= h[k + 1]; x += 1e-4) {
      EXPECT_GE(t.value(x), lo - 1e-15) << x;
      EXPECT_LE(t.value(x), hi + 1e-15) << x;
    }
  }
}

TEST(HeightTable, SlopeIsTheDerivativeAndContinuousAtKnots) {
  const std::vector<double> h = {0.08, 0.1, 0.13, 0.17, 0.2, 0.26, 0.35, 0.5};
  const std::vector<double> v = {0.010, 0.016, 0.021, 0.023, 0.022, 0.017, 0.004, 0.001};
  const HeightTable t(h, v);
  const double e = 1e-7;
  for (double x = 0.0801; x < 0.7; x += 0.00313) {
    const double fd = (t.value(x + e) - t.value(x - e)) / (2.0 * e);
    EXPECT_NEAR(t.slope(x), fd, 1e-5) << x;
  }
  // C¹ at every interior knot and at the last (where the 1/h² tail begins).
  for (std::size_t k = 1; k < h.size(); ++k) {
    EXPECT_NEAR(t.slope(h[k] - 1e-9), t.slope(h[k] + 1e-9), 1e-5) << "knot " << k;
  }
}

TEST(HeightTable, HoldsBelowAndDecaysAsInverseSquareAbove) {
  const HeightTable t({0.1, 0.2, 0.4}, {0.3, 0.1, 0.03});
  EXPECT_EQ(t.value(0.02), 0.3);
  EXPECT_EQ(t.slope(0.02), 0.0);
  for (double x : {0.4, 0.8, 2.0, 10.0}) {
    EXPECT_NEAR(t.value(x), 0.03 * (0.4 / x) * (0.4 / x), 1e-15) << x;
    EXPECT_NEAR(t.slope(x), -2.0 * 0.03 * 0.16 / (x * x * x), 1e-13) << x;
  }
  EXPECT_TRUE(std::isnan(t.value(std::nan(""))));
}

TEST(HeightTable, RejectsTablesItCannotInterpolate) {
  EXPECT_THROW(HeightTable({0.1}, {0.2}), std::invalid_argument);
  EXPECT_THROW(HeightTable({0.1, 0.2}, {0.2}), std::invalid_argument);
  EXPECT_THROW(HeightTable({0.2, 0.1}, {0.2, 0.1}), std::invalid_argument);
  EXPECT_THROW(HeightTable({0.1, 0.1}, {0.2, 0.1}), std::invalid_argument);
  EXPECT_THROW(HeightTable({0.0, 0.1}, {0.2, 0.1}), std::invalid_argument);
  EXPECT_THROW(HeightTable({0.1, 0.2}, {0.2, std::nan("")}), std::invalid_argument);
}

TEST(GroundEffectTable, SampledFromTheClosedFormsReproducesThem) {
  // 1 cm knots from the landing gear (0.072 m) to 1 m: the interpolant follows the formulas to well
  // within a percent, and the slope F_G' (used by the flat map) within a few percent.
  const VehicleParams p = tabulatedPaperParams(grid(0.072, 1.0, 0.01));
  ASSERT_TRUE(p.validate().empty());
  const GroundEffectModel formula(paperParams());
  const GroundEffectModel table(p);
  for (double h = 0.072; h < 1.0; h += 0.0017) {
    EXPECT_NEAR(table.thrustRatio(h), formula.thrustRatio(h), 2e-3 * formula.thrustRatio(h)) << h;
    EXPECT_NEAR(table.thrustRatioSlope(h), formula.thrustRatioSlope(h),
                0.03 * std::abs(formula.thrustRatioSlope(h)) + 1e-4) << h;
    // PCHIP does not overshoot, so a peak between two knots is cut to the larger knot value:
    // 0.3 % of the peak (0.023 m) with 1 cm knots.
    EXPECT_NEAR(table.levelingCoefficient(h), formula.levelingCoefficient(h), 1e-4) << h;
  }
  EXPECT_NEAR(table.levelingPeakHeight(), formula.levelingPeakHeight(), 0.005);
  // J'(h) is built from the table like from the formula.
  EXPECT_NEAR(table.levelingInertiaIncrement(0.15), formula.levelingInertiaIncrement(0.15),
              1e-3 * formula.levelingInertiaIncrement(0.15));
}

TEST(GroundEffectTable, ZeroTablesReduceToNoGroundEffect) {
  VehicleParams p = paperParams();
  p.additional_thrust.table = {{0.07, 0.5, 1.0}, {0.0, 0.0, 0.0}};
  p.leveling_torque.table = {{0.07, 0.5, 1.0}, {0.0, 0.0, 0.0}};
  ASSERT_TRUE(p.validate().empty());
  const GroundEffectModel ge(p);
  for (double h : {0.05, 0.1, 0.7, 3.0}) {
    EXPECT_EQ(ge.thrustRatio(h), 0.0);
    EXPECT_EQ(ge.thrustRatioSlope(h), 0.0);
    EXPECT_EQ(ge.levelingCoefficient(h), 0.0);
    EXPECT_EQ(ge.levelingInertiaDiagonal(h), p.inertia_kgm2);
  }
}

TEST(GroundEffectTable, ValidationNamesTheBadEntry) {
  const auto fieldsOf = [](const VehicleParams& p) {
    std::vector<std::string> f;
    for (const auto& e : p.validate()) f.push_back(e.field);
    return f;
  };
  VehicleParams p = paperParams();
  p.additional_thrust.table = {{0.1, 0.3, 0.2}, {0.3, 0.1, 0.05}};
  EXPECT_EQ(fieldsOf(p), std::vector<std::string>{"ground_effect.additional_thrust.table.heights_m[2]"});
  p.additional_thrust.table = {{0.1, 0.2}, {0.3, -1.0}};  // thrust would vanish
  EXPECT_EQ(fieldsOf(p), std::vector<std::string>{"ground_effect.additional_thrust.table.F_G[1]"});
  p.additional_thrust.table = {{0.1, 0.2, 0.3}, {0.3, 0.1}};
  EXPECT_EQ(fieldsOf(p), std::vector<std::string>{"ground_effect.additional_thrust.table"});
  p.additional_thrust.table = {{0.1}, {0.3}};
  EXPECT_EQ(fieldsOf(p), std::vector<std::string>{"ground_effect.additional_thrust.table.heights_m"});
  p = paperParams();
  p.leveling_torque.table = {{0.1, 0.2}, {0.02, std::nan("")}};
  EXPECT_EQ(fieldsOf(p), std::vector<std::string>{"ground_effect.leveling_torque.table.M_G_m[1]"});
  // With a table, the formula's parameters are not checked (they are not used).
  p.leveling_torque.table = {{0.1, 0.2}, {0.02, 0.01}};
  p.leveling_torque.g4_m2 = -1.0;
  EXPECT_TRUE(p.validate().empty());
}

}  // namespace

// A table whose values are replaced in place (a curve learned in flight) is, bit for bit, the
// table built from the new values: value, slope and knot slopes at every height, above and
// below the knots included.
TEST(HeightTable, NewValuesInPlaceGiveTheTableBuiltFromThem) {
  const std::vector<double> knots = {0.08, 0.1, 0.13, 0.17, 0.22, 0.3, 0.45};
  const std::vector<double> first = {0.4, 0.3, 0.2, 0.12, 0.07, 0.03, 0.01};
  const std::vector<double> second = {0.2, 0.25, 0.1, 0.1, 0.11, 0.0, 0.02};  // extrema, a plateau
  HeightTable changed(knots, first);
  changed.setValues(second.data());
  const HeightTable built(knots, second);
  EXPECT_EQ(changed.values(), built.values());
  EXPECT_EQ(changed.knotSlopes(), built.knotSlopes());
  for (double h : grid(0.05, 0.8, 0.0037)) {
    EXPECT_EQ(changed.value(h), built.value(h)) << h;
    EXPECT_EQ(changed.slope(h), built.slope(h)) << h;
  }
  // And through the model, as the controller uses it.
  VehicleParams p = tabulatedPaperParams(knots);
  GroundEffectModel model(p);
  ASSERT_TRUE(model.thrustIsTable());
  model.setThrustTableValues(second.data());
  for (double h : grid(0.08, 0.8, 0.011)) EXPECT_EQ(model.thrustRatio(h), built.value(std::max(h, p.min_rotor_plane_height_m))) << h;
}
