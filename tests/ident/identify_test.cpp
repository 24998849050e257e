// SPDX-License-Identifier: BSD-3-Clause
// The identification API (ident/identify.hpp) end to end: logs of the virtual rigs (sim/rigs.hpp)
// and synthetic flight logs → one call per kind → parameters, update, plots; checked against
// the truth that made the logs and against the fits called directly.

#include "geaware/ident/identify.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/model/ground_effect.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/sim/rigs.hpp"
#include "synthetic.hpp"

namespace {

namespace ident = geaware::ident;
namespace sim = geaware::sim;
using ident_test::withinSigmas;

std::vector<double> grid(double from, double to, double step) {
  std::vector<double> v;
  for (int k = 0; from + k * step <= to + 1e-9; ++k) v.push_back(from + k * step);
  return v;
}

/// The round trip's platform log in memory: level board 0.07–1 m, a 10° board 0.08–0.35 m,
/// rpm differences at 1–2 m (as the campaign's calibration runs them).
ident::PlatformLog rigPlatformLog(bool tilted = true) {
  const sim::ForceTorquePlatform rig(sim::rigGeometry(geaware_test::paperParams()),
                                     sim::RotorAeroParams{}, sim::PlatformParams{});
  sim::PlatformSweep level;
  level.heights_m = grid(0.07, 1.0, 0.01);
  level.tilts_deg = {0.0};
  level.rpm = {9000.0, 12000.0, 15000.0};
  sim::PlatformSweep tilt = level;
  tilt.heights_m = grid(0.08, 0.35, 0.01);
  tilt.tilts_deg = {4.0, 8.0};
  sim::PlatformSweep mixing = level;
  mixing.heights_m = {1.0, 1.5, 2.0};
  mixing.rpm_diffs = {-1500.0, -750.0, 0.0, 750.0, 1500.0};
  ident::PlatformLog log;
  log.source = "virtual platform";
  std::vector<sim::PlatformSweep> sweeps{level, mixing};
  if (tilted) sweeps.push_back(tilt);
  for (std::size_t k = 0; k < sweeps.size(); ++k) {
    const double t0 = log.t_s.empty() ? 0.0 : log.t_s.back() + 1.0;
    (void)rig.sweep(sweeps[k], 10 + k, [&](const sim::PlatformRow& r) {
      log.t_s.push_back(t0 + r.t_s);
      log.h_m.push_back(r.h_m);
      log.tilt_deg.push_back(r.tilt_deg);
      for (std::size_t i = 0; i < 4; ++i) log.n_rpm[i].push_back(r.n_rpm[i]);
      for (std::size_t a = 0; a < 3; ++a) {
        log.f_N[a].push_back(r.force_B[static_cast<int>(a)]);
        log.tau_Nm[a].push_back(r.torque_B[static_cast<int>(a)]);
      }
    });
  }
  return log;
}

const ident::IdentifiedValue* find(const ident::IdentifyResult& r, const std::string& name) {
  const auto it = std::find_if(r.parameters.begin(), r.parameters.end(),
                               [&](const auto& p) { return p.name == name; });
  return it == r.parameters.end() ? nullptr : &*it;
}

bool updates(const ident::IdentifyResult& r, const std::string& key) {
  const auto& e = r.update.entries();
  return std::any_of(e.begin(), e.end(), [&](const auto& x) { return x.key == key; });
}

/// The truth's mixing coefficient of mixer row 1 (k_TX), 2 (k_TY) or 3 (k_I), out of ground
/// effect (as the round-trip test computes it).
double truthMixing(int row) {
  sim::PlatformParams quiet;
  quiet.force_noise_N = 0.0;
  quiet.torque_noise_Nm = 0.0;
  const sim::ForceTorquePlatform rig(sim::rigGeometry(geaware_test::paperParams()),
                                     sim::RotorAeroParams{}, quiet);
  const Eigen::Matrix4d& A = geaware::model::Mixer::allocationPattern();
  const double arm = std::sqrt(2.0) * geaware_test::paperParams().diagonal_rotor_distance_m / 4.0;
  std::array<double, 4> n{};
  double s = 0.0;
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<std::size_t>(i);
    n[k] = 12000.0 + 1500.0 * A(row, i);
    s += A(row, i) * n[k] * n[k];
  }
  return rig.wrench(50.0, 0.0, n).wrench.torque_B[row - 1] / ((row == 3 ? 1.0 : arm) * s);
}

TEST(Identify, PlatformRecoversTheRigsMixingAndMatchesTheFitsCalledDirectly) {
  const auto& base = geaware_test::paperParams();
  const auto log = rigPlatformLog();
  const auto r = ident::identifyPlatform(log, base);
  EXPECT_EQ(r.kind, "platform");
  // The truth's mixing out of ground effect is eq. 2 exactly: within 2 % (the round trip's).
  for (const auto& [key, row] : std::vector<std::pair<std::string, int>>{
           {"rotor.k_TX_N_per_rpm2", 1}, {"rotor.k_TY_N_per_rpm2", 2}, {"rotor.k_I_Nm_per_rpm2", 3}}) {
    const auto* p = find(r, key);
    ASSERT_NE(p, nullptr) << key;
    EXPECT_NEAR(p->estimate.value / truthMixing(row), 1.0, 0.02) << key;
    EXPECT_TRUE(updates(r, key)) << key;
  }
  // The same numbers as the fits themselves (the API adds no arithmetic of its own).
  const auto thrust = ident::fitAdditionalThrust(log);
  ASSERT_TRUE(r.fits.additional_thrust.has_value());
  EXPECT_EQ(find(r, "rotor.k_T_N_per_rpm2")->estimate.value, thrust.k_T_N_per_rpm2.value);
  EXPECT_EQ(find(r, "ground_effect.additional_thrust.g2_m2")->estimate.value, thrust.g2_m2.value);
  ASSERT_TRUE(r.fits.leveling.has_value());
  const auto* g3 = find(r, "ground_effect.leveling_torque.g3_m");
  ASSERT_NE(g3, nullptr);
  EXPECT_EQ(g3->estimate.value, r.fits.leveling->g3_m.value);
  for (const char* key : {"rotor.k_T_N_per_rpm2", "ground_effect.additional_thrust.g1_m2",
                          "ground_effect.leveling_torque.scale_m4"}) {
    EXPECT_TRUE(updates(r, key)) << key;
  }
  // Residual rows: thrust, roll, pitch, yaw, leveling; the report's tables and both plots.
  EXPECT_EQ(r.residuals.size(), 5U);
  ASSERT_EQ(r.plots.size(), 2U);
  for (const auto& plot : r.plots) {
    for (const auto& c : plot.curves) {
      EXPECT_EQ(c.x.size(), c.y.size()) << plot.title << ": " << c.name;
      EXPECT_FALSE(c.x.empty()) << plot.title << ": " << c.name;
    }
  }
  // The measured M̃_G scatter lies around the fitted curve (same samples as the fit): the
  // median relative deviation is small.
  const auto& measured = r.plots[1].curves[0];
  std::vector<double> dev;
  for (std::size_t i = 0; i < measured.x.size(); ++i) {
    const double fit = ident::levelingCoefficient(r.fits.leveling->g3_m.value, r.fits.leveling->g4_m2.value,
                                                  r.fits.leveling->scale_m4.value, measured.x[i]);
    dev.push_back(std::abs(measured.y[i] / fit - 1.0));
  }
  std::nth_element(dev.begin(), dev.begin() + static_cast<std::ptrdiff_t>(dev.size() / 2), dev.end());
  EXPECT_LT(dev[dev.size() / 2], 0.5);
  EXPECT_EQ(r.report_tables.size(), 3U);  // parameters, residuals, height bands
  EXPECT_NE(ident::resultText(r).find("rotor.k_TY_N_per_rpm2"), std::string::npos);
}

TEST(Identify, PlatformTablesGoIntoTheUpdateAsTables) {
  ident::IdentifyOptions o;
  o.ground_effect = ident::CurveForm::kTable;
  const auto r = ident::identifyPlatform(rigPlatformLog(), geaware_test::paperParams(), o);
  ASSERT_EQ(r.tables.size(), 2U);
  EXPECT_EQ(r.tables[0].section, "additional_thrust");
  EXPECT_EQ(r.tables[1].values_key, "M_G_m");
  // F_G's knots stop at the table top (0.5 m); every knot is a parameter row.
  EXPECT_LE(r.tables[0].curve.heights_m.back(), 0.5);
  EXPECT_NE(find(r, "F_G(h = 0.07 m)"), nullptr);
  int tables = 0;
  for (const auto& e : r.update.entries()) tables += e.table ? 1 : 0;
  EXPECT_EQ(tables, 2);
  EXPECT_FALSE(updates(r, "ground_effect.additional_thrust.g1_m2"));
  // The truth's F_G at 0.1 m against the table (the round trip's 5 % near the ground).
  const auto& fg = r.tables[0].curve;
  const auto it = std::find_if(fg.heights_m.begin(), fg.heights_m.end(),
                               [](double h) { return std::abs(h - 0.10) < 1e-9; });
  ASSERT_NE(it, fg.heights_m.end());
  sim::PlatformParams quiet;
  quiet.force_noise_N = 0.0;
  const sim::ForceTorquePlatform clean(sim::rigGeometry(geaware_test::paperParams()),
                                       sim::RotorAeroParams{}, quiet);
  double k_sum = 0.0;
  for (double k : clean.aerodynamics().geometry().k_T_N_per_rpm2) k_sum += k;
  const double n = 12000.0;
  const double truth = clean.wrench(0.10, 0.0, {n, n, n, n}).wrench.force_B.z() / (k_sum * n * n) - 1.0;
  EXPECT_NEAR(fg.values[static_cast<std::size_t>(it - fg.heights_m.begin())].value / truth, 1.0, 0.05);
}

TEST(Identify, PlatformWithoutTiltedBoardWarnsAndLeavesTheLevelingOut) {
  const auto r = ident::identifyPlatform(rigPlatformLog(false), geaware_test::paperParams());
  EXPECT_FALSE(r.fits.leveling.has_value());
  EXPECT_EQ(find(r, "ground_effect.leveling_torque.g3_m"), nullptr);
  EXPECT_FALSE(updates(r, "ground_effect.leveling_torque.g3_m"));
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("no tilted-board samples"), std::string::npos);
  EXPECT_EQ(r.plots.size(), 1U);
}

TEST(Identify, RotorStandRecoversTheStandsRotor) {
  const auto& p = geaware_test::paperParams();
  const sim::RotorStand stand(p, sim::RotorStandParams{});
  ident::RotorStandLog log;
  log.source = "virtual stand";
  (void)stand.sweep(grid(0.0, 1.0, 0.1), 1, [&](const sim::RotorStandRow& r) {
    log.t_s.push_back(r.t_s);
    log.throttle.push_back(r.throttle);
    log.rpm.push_back(r.rpm);
    log.thrust_N.push_back(r.thrust_N);
    log.torque_Nm.push_back(r.torque_Nm);
  });
  const auto r = ident::identifyRotorStand(log);
  EXPECT_EQ(r.kind, "rotor");
  EXPECT_NEAR(find(r, "rotor.k_T_N_per_rpm2")->estimate.value / p.rotor.k_T_N_per_rpm2, 1.0, 0.02);
  EXPECT_NEAR(find(r, "rotor.k_I_Nm_per_rpm2")->estimate.value / p.rotor.k_I_Nm_per_rpm2, 1.0, 0.02);
  const auto* J = find(r, "rotor.J_R_kgm2");
  ASSERT_NE(J, nullptr);
  EXPECT_NEAR(J->estimate.value / p.rotor.J_R_kgm2, 1.0, 0.10);
  for (const char* key : {"rotor.k_T_N_per_rpm2", "rotor.J_R_kgm2", "throttle_curve.c2_rpm2"}) {
    EXPECT_TRUE(updates(r, key)) << key;
  }
  EXPECT_EQ(r.residuals.size(), 3U);
  EXPECT_EQ(r.plots.size(), 2U);
}

TEST(Identify, HoverDescentRecoversFGAndWritesKTWithIt) {
  const auto& p = geaware_test::paperParams();
  ident::IdentifyOptions o;
  o.robust = ident::robustLoss("cauchy");
  const auto r = ident::identifyHover(ident_test::hoverDescent(7), p, o);
  EXPECT_EQ(r.kind, "hover");
  EXPECT_TRUE(withinSigmas(find(r, "ground_effect.additional_thrust.g1_m2")->estimate,
                           p.additional_thrust.g1_m2));
  EXPECT_TRUE(withinSigmas(find(r, "ground_effect.additional_thrust.g2_m2")->estimate,
                           p.additional_thrust.g2_m2));
  EXPECT_TRUE(updates(r, "rotor.k_T_N_per_rpm2"));
  EXPECT_TRUE(updates(r, "ground_effect.additional_thrust.g2_m2"));
}

TEST(Identify, HoverFarFromTheGroundGivesKTAloneAndSaysSo) {
  // Issue 11: a log at 0.4–0.6 m (4.5–6.7 rotor radii of the paper quadrotor, no ground effect
  // in its world) reported an 8 % "ground effect". The rule: F_G only below 3 rotor radii.
  const auto& p = geaware_test::paperParams();
  geaware::model::VehicleParams observer = p;
  observer.rotor.k_T_N_per_rpm2 *= 1.03;  // the observer's k_T 3 % high: the fit must undo it
  const auto r = ident::identifyHover(ident_test::hoverNoGroundEffect(3, 0.4, 0.6, 1.03), observer, {});
  EXPECT_EQ(r.kind, "hover");
  ASSERT_EQ(r.parameters.size(), 1U);
  EXPECT_TRUE(withinSigmas(find(r, "rotor.k_T_N_per_rpm2")->estimate, p.rotor.k_T_N_per_rpm2));
  EXPECT_EQ(find(r, "ground_effect.additional_thrust.g1_m2"), nullptr);
  EXPECT_EQ(find(r, "ground_effect.additional_thrust.g2_m2"), nullptr);
  EXPECT_TRUE(updates(r, "rotor.k_T_N_per_rpm2"));
  EXPECT_FALSE(updates(r, "ground_effect.additional_thrust.g2_m2"));
  EXPECT_FALSE(r.fits.additional_thrust.has_value());
  ASSERT_TRUE(r.fits.hover_thrust.has_value());
  ASSERT_EQ(r.notes.size(), 1U);
  EXPECT_NE(r.notes[0].find("F_G not fitted"), std::string::npos) << r.notes[0];
  EXPECT_NE(ident::resultText(r).find("note: F_G not fitted"), std::string::npos);
  // A descent down to 0.075 m (< 3·0.089 m) fits F_G.
  const auto low = ident::identifyHover(ident_test::hoverDescent(7), p, {});
  EXPECT_NE(find(low, "ground_effect.additional_thrust.g2_m2"), nullptr);
  EXPECT_TRUE(low.notes.empty());
}

TEST(Identify, ADragBandFittedNegativeBlocksTheOut) {
  // Issue 11: a drag band fitted negative was flagged but still written as 0 into --out. The
  // external acceleration's sign flipped (a frame error): every band fits d < 0, each blocks.
  const auto& p = geaware_test::paperParams();
  auto log = ident_test::dragFlights(2);
  for (auto& a : log.a_ext_W) {
    for (auto& x : a) x = -x;
  }
  ident::IdentifyOptions o;
  o.height_bands = 4;
  const auto r = ident::identifyFlight(log, p, o);
  ASSERT_EQ(r.fits.drag->bands.size(), 4U);
  EXPECT_EQ(r.blocking.size(), 8U);  // d_x and d_y of each band
  EXPECT_NE(r.blocking[0].find("fitted negative"), std::string::npos) << r.blocking[0];
  // Never written, not even as 0 (--accept-warnings): the bands are left out of the table.
  EXPECT_TRUE(ident::dragTable(*r.fits.drag).heights_m.empty());
  EXPECT_FALSE(updates(r, "drag.d_x_N_per_mps"));
  // The right sign blocks nothing.
  EXPECT_TRUE(ident::identifyFlight(ident_test::dragFlights(2), p, o).blocking.empty());
  EXPECT_TRUE(ident::identifyHover(ident_test::hoverDescent(7), p, {}).blocking.empty());
}

TEST(Identify, AParameterAtItsBoundBlocksTheOut) {
  // Issue 11: parameters stuck at a bound were reported only as "poorly constrained". An F_G
  // that rises faster than the closed form allows, g2/(h² − 0.002 m²), puts g1's optimum below
  // its bound 1e-9 m²: blocked.
  const auto& p = geaware_test::paperParams();
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  ident::PlatformLog log = ident_test::syntheticPlatform(spec, 3);
  const geaware::model::GroundEffectModel ge(p);
  for (std::size_t i = 0; i < log.size(); ++i) {
    const double h = log.h_m[i];
    log.f_N[2][i] *= (1.0 + p.additional_thrust.g2_m2 / (h * h - 0.002)) / (1.0 + ge.thrustRatio(h));
  }
  const auto r = ident::identifyPlatform(log, p, {});
  ASSERT_FALSE(r.blocking.empty());
  EXPECT_NE(r.blocking[0].find("g1 = 1e-09 ended at its bound (allowed [1e-09, 100])"), std::string::npos)
      << r.blocking[0];
  // The paper's curve is inside its bounds: nothing blocks.
  EXPECT_TRUE(ident::identifyPlatform(ident_test::syntheticPlatform(spec, 3), p, {}).blocking.empty());
}

TEST(Identify, EveryFitCarriesItsConditionNumber) {
  const auto& p = geaware_test::paperParams();
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  const auto r = ident::identifyPlatform(ident_test::syntheticPlatform(spec, 3), p, {});
  ASSERT_FALSE(r.residuals.empty());
  for (const auto& f : r.residuals) {
    if (f.stats.count == 0) continue;  // a coefficient without excitation: not fitted
    EXPECT_GE(f.stats.condition_number, 1.0) << f.name;
    EXPECT_LT(f.stats.condition_number, ident::kIllConditioned) << f.name;
  }
  EXPECT_NE(ident::resultText(r).find("condition number"), std::string::npos);
  for (const auto& w : r.warnings) EXPECT_EQ(w.find("condition number"), std::string::npos) << w;
  // One rpm and heights only out of ground effect (1.5, 2 m): k_T and the F_G curve trade off.
  spec.level_heights_m = {1.5, 2.0};
  spec.mixing_rpm = 0.0;
  try {
    const auto flat = ident::identifyPlatform(ident_test::syntheticPlatform(spec, 3), p, {});
    const bool warned = std::any_of(flat.warnings.begin(), flat.warnings.end(), [](const std::string& w) {
      return w.find("condition number") != std::string::npos;
    });
    EXPECT_TRUE(warned || !flat.blocking.empty());
  } catch (const ident::IdentError& e) {
    EXPECT_NE(std::string(e.what()).find("not identifiable"), std::string::npos) << e.what();
  }
}

TEST(Identify, FlightRecoversTheDragTablePerBand) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::RotorDragModel drag(p.drag);
  ident::IdentifyOptions o;
  o.height_bands = 4;
  const auto r = ident::identifyFlight(ident_test::dragFlights(2), p, o);
  ASSERT_TRUE(r.fits.drag.has_value());
  ASSERT_EQ(r.fits.drag->bands.size(), 4U);
  EXPECT_EQ(r.parameters.size(), 8U);  // d_x, d_y per band
  for (const auto& b : r.fits.drag->bands) {
    EXPECT_TRUE(withinSigmas(b.d_x_N_per_mps, drag.coefficients(b.h_mean_m).x(), 5.0)) << b.h_mean_m;
  }
  EXPECT_FALSE(r.update.empty());
}

TEST(Identify, CorrelationsHaveNoUpdateAndPrintTheMatrix) {
  const auto r = ident::identifyCorrelations(rigPlatformLog(), geaware_test::paperParams());
  ASSERT_TRUE(r.fits.correlations.has_value());
  EXPECT_TRUE(r.update.empty());
  EXPECT_TRUE(r.parameters.empty());
  const std::string text = ident::resultText(r);
  EXPECT_NE(text.find("N_base(1)"), std::string::npos);
  EXPECT_EQ(r.report_tables.size(), 1U);
}

TEST(Identify, RobustLossByName) {
  EXPECT_EQ(ident::robustLoss("huber").loss, ident::RobustLoss::kHuber);
  EXPECT_EQ(ident::robustLoss("cauchy").loss, ident::RobustLoss::kCauchy);
  EXPECT_EQ(ident::robustLoss("none").loss, ident::RobustLoss::kNone);
  EXPECT_THROW((void)ident::robustLoss("l1"), std::invalid_argument);
}

}  // namespace
