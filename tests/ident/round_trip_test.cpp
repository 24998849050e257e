// SPDX-License-Identifier: BSD-3-Clause
// Round trip against the simulator (issue 5, "What it must show"): logs of the virtual rigs
// (sim/rigs.hpp) → the identification fits → curves compared with the truth's own curves.
//
// The truth is NOT the controller's model: it is the per-rotor aerodynamics of
// docs/sim-aerodynamics.md, whose level-board thrust gain has a kink where the slipstreams
// merge (≈ 0.305 m) and whose leveling torque switches on sharply below ≈ 0.33 m. The
// controller's forms F_G = g2/(h² + g1) and M_G = scale·h/(h² + g3·h + g4)² cannot follow
// either exactly, so next to each fitted curve this file also computes the best that ANY
// parameters of the form can do (a minimax search over the form's parameters on the noise-free
// truth curve). Where that bound is above the issue's tolerance, no identification can meet it
// and the test asserts the tolerance the identification does meet, with the reason beside it
// (docs/identification.md, "Round trip against the simulator").
//
// Experiments, as the paper's rigs (coarse grids: the file runs in well under a second):
//  - level board, equal speeds, 0.07–1.0 m: k_T, g1, g2;
//  - board tilted by 15°, equal speeds, 0.10–0.35 m: the leveling torque at the target's tilt;
//  - rpm-difference (mixing) sweeps on the roll, pitch and yaw rows, out of ground effect
//    (1–2 m): k_TX, k_TY, k_I, and k_T from heights where F_G is nearly zero;
//  - the single-rotor stand in free air: k_T, k_I, J_R and the throttle curve.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/ident/fits.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/motor.hpp"
#include "geaware/model/units.hpp"
#include "geaware/sim/rigs.hpp"
#include "synthetic.hpp"

namespace {

namespace ident = geaware::ident;
namespace model = geaware::model;
namespace sim = geaware::sim;

constexpr std::array<std::uint64_t, 3> kSeeds = {1, 2, 3};
constexpr double kTargetRpm = 15000.0;  // the torque target's speed (docs/paper-facts.md's table)
constexpr double kTargetTiltDeg = 15.0;

// Tolerances of the issue.
constexpr double kIssueThrustTol = 0.05;    // F_G, relative, 0.07–1 m
constexpr double kIssueTorqueTol = 0.10;    // leveling torque at 15°, relative, 0.1–0.35 m
constexpr double kIssueMixingTol = 0.02;    // k_TX, k_TY, k_I (and the stand's k_T, k_I)

std::vector<double> grid(double from, double to, double step) {
  std::vector<double> v;
  for (int k = 0; from + k * step <= to + 1e-9; ++k) v.push_back(from + k * step);
  return v;
}

/// The three platform sweeps of one round trip, in the order they are logged.
std::vector<sim::PlatformSweep> platformSweeps() {
  sim::PlatformSweep level;
  level.heights_m = grid(0.07, 1.0, 0.01);
  level.tilts_deg = {0.0};
  level.rpm = {9000.0, 12000.0, 15000.0};
  sim::PlatformSweep tilted;
  tilted.heights_m = grid(0.10, 0.35, 0.01);
  tilted.tilts_deg = {kTargetTiltDeg};
  tilted.rpm = {9000.0, 12000.0, 15000.0};
  sim::PlatformSweep mixing;
  mixing.heights_m = {1.0, 1.5, 2.0};
  mixing.tilts_deg = {0.0};
  mixing.rpm = {9000.0, 12000.0, 15000.0};
  mixing.rpm_diffs = {-1500.0, -750.0, 0.0, 750.0, 1500.0};  // 0: the equal-speed row
  return {level, tilted, mixing};
}

/// The platform as logged: 1 s at 100 Hz per setpoint (`--samples 100`), the rig's default noise.
/// The leveling torque at 0.35 m is 0.014 N·m against 0.004 N·m of sensor noise per sample, so
/// a 10 % match there needs ~100 samples per setpoint, not the rig's default 5.
sim::PlatformParams loggedPlatform() {
  sim::PlatformParams p;
  p.samples_per_setpoint = 100;
  return p;
}

/// Writes the sweeps as one platform log in the rigs' CSV format (`geaware rig platform`),
/// each sweep with its own seed (10·k + seed) and the time running on across sweeps.
void writePlatformLog(const std::filesystem::path& file, std::uint64_t seed) {
  const sim::ForceTorquePlatform rig(sim::rigGeometry(geaware_test::paperParams()),
                                     sim::RotorAeroParams{}, loggedPlatform());
  std::ofstream os(file);
  os.precision(17);
  os << "t_s,h_m,tilt_deg,n1_rpm,n2_rpm,n3_rpm,n4_rpm,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm\n";
  double t0 = 0.0;
  double last = 0.0;
  const auto sweeps = platformSweeps();
  for (std::size_t k = 0; k < sweeps.size(); ++k) {
    (void)rig.sweep(sweeps[k], 10 * k + seed, [&](const sim::PlatformRow& r) {
      last = t0 + r.t_s;
      os << last << ',' << r.h_m << ',' << r.tilt_deg;
      for (double n : r.n_rpm) os << ',' << n;
      for (int a = 0; a < 3; ++a) os << ',' << r.force_B[a];
      for (int a = 0; a < 3; ++a) os << ',' << r.torque_B[a];
      os << '\n';
    });
    t0 = last + 1.0;
  }
  os.close();
  ASSERT_FALSE(os.fail()) << file << ": write failed";
}

void writeStandLog(const std::filesystem::path& file, std::uint64_t seed) {
  const sim::RotorStand stand(geaware_test::paperParams(), sim::RotorStandParams{});
  std::ofstream os(file);
  os.precision(17);
  os << "t_s,throttle,rpm,thrust_N,torque_Nm\n";
  (void)stand.sweep(grid(0.0, 1.0, 0.1), seed, [&](const sim::RotorStandRow& r) {
    os << r.t_s << ',' << r.throttle << ',' << r.rpm << ',' << r.thrust_N << ',' << r.torque_Nm
       << '\n';
  });
  os.close();
  ASSERT_FALSE(os.fail()) << file << ": write failed";
}

// ---------------------------------------------------------------------------------- the truth

/// The truth's curves, from the noise-free platform (as `geaware rig calibrate` reads them).
class Truth {
 public:
  Truth()
      : platform_(sim::rigGeometry(geaware_test::paperParams()), sim::RotorAeroParams{},
                  quiet()) {
    for (double k : platform_.aerodynamics().geometry().k_T_N_per_rpm2) k_sum_ += k;
  }

  /// Level-board additional-thrust ratio ΣF_z/ΣT_free − 1 (independent of the speed) [-].
  [[nodiscard]] double thrustRatio(double h) const {
    const double n = kTargetRpm;
    return platform_.wrench(h, 0.0, {n, n, n, n}).wrench.force_B.z() / (k_sum_ * n * n) - 1.0;
  }
  /// Torque about y_B at the target's tilt and speed [N·m] (negative: leveling).
  [[nodiscard]] double torque(double h) const {
    const double n = kTargetRpm;
    return platform_.wrench(h, kTargetTiltDeg, {n, n, n, n}).wrench.torque_B.y();
  }
  /// The mixing coefficient of mixer row 1 (k_TX), 2 (k_TY) or 3 (k_I), as the rig's response
  /// to a speed difference far from the board (50 m: no ground effect), as in calibrate().
  [[nodiscard]] double mixing(int row) const {
    const Eigen::Matrix4d& A = model::Mixer::allocationPattern();
    const double arm = geaware::model::mixerArm_m(geaware_test::paperParams().diagonal_rotor_distance_m);
    std::array<double, 4> n{};
    double s = 0.0;
    for (int i = 0; i < 4; ++i) {
      n[static_cast<std::size_t>(i)] = 12000.0 + 1500.0 * A(row, i);
      s += A(row, i) * n[static_cast<std::size_t>(i)] * n[static_cast<std::size_t>(i)];
    }
    const double tau = platform_.wrench(50.0, 0.0, n).wrench.torque_B[row - 1];
    return tau / ((row == 3 ? 1.0 : arm) * s);
  }

 private:
  static sim::PlatformParams quiet() {
    sim::PlatformParams p;
    p.force_noise_N = 0.0;
    p.torque_noise_Nm = 0.0;
    return p;
  }
  sim::ForceTorquePlatform platform_;
  double k_sum_ = 0.0;
};

const Truth& truth() {
  static const Truth t;
  return t;
}

/// Heights [from, to] every 2.5 mm, where the curves are compared.
std::vector<double> compareHeights(double from, double to) { return grid(from, to, 0.0025); }

/// min over c of max_i |c/r_i − 1| for ratios r_i of one sign: the best relative error of a
/// curve whose free scale factor is c (c = 2·lo·hi/(lo + hi), error (hi − lo)/(hi + lo)).
double minimaxScaleError(const std::vector<double>& r) {
  double lo = std::abs(r.front());
  double hi = lo;
  for (double x : r) {
    lo = std::min(lo, std::abs(x));
    hi = std::max(hi, std::abs(x));
  }
  return (hi - lo) / (hi + lo);
}

/// The smallest worst-case relative error of ANY g2/(h² + g1) against the truth's F_G over
/// [from, to]: g2 exactly (minimaxScaleError), g1 on a log grid 1e-4 … 10 m².
double bestThrustFormError(double from, double to) {
  const auto hs = compareHeights(from, to);
  std::vector<double> F;
  for (double h : hs) F.push_back(truth().thrustRatio(h));
  double best = 1.0;
  std::vector<double> r(hs.size());
  for (int k = 0; k <= 5000; ++k) {
    const double g1 = 1e-4 * std::pow(10.0, k / 1000.0);
    for (std::size_t i = 0; i < hs.size(); ++i) r[i] = F[i] * (hs[i] * hs[i] + g1);
    best = std::min(best, minimaxScaleError(r));
  }
  return best;
}

/// The same for scale·h/(h² + g3·h + g4)²·T·sin δ against the truth's torque at 15°: the scale
/// exactly, (g3, g4) on a grid over the valid shapes (g3 ∈ [−0.8, 0.4] m, g4 ∈ [1e-3, 1] m²).
double bestTorqueFormError(double from, double to) {
  const auto hs = compareHeights(from, to);
  std::vector<double> tau;
  for (double h : hs) tau.push_back(truth().torque(h));
  double best = 1.0;
  std::vector<double> r(hs.size());
  for (int a = 0; a <= 300; ++a) {
    const double g3 = -0.8 + 0.004 * a;
    for (int c = 0; c <= 300; ++c) {
      const double g4 = 1e-3 * std::pow(10.0, c / 100.0);
      if (!(g3 >= 0.0 || g3 * g3 < 4.0 * g4)) continue;  // denominator vanishes for some h ≥ 0
      for (std::size_t i = 0; i < hs.size(); ++i) {
        r[i] = tau[i] / ident::levelingCoefficient(g3, g4, 1.0, hs[i]);
      }
      best = std::min(best, minimaxScaleError(r));
    }
  }
  return best;
}

// --------------------------------------------------------------------------- one round trip

struct RoundTrip {
  ident::AdditionalThrustFit thrust;
  ident::MixingFit mixing;
  ident::LevelingFit leveling;
  ident::RotorFit stand;
  // The same logs with both curves fitted as tables (--ground-effect table).
  ident::AdditionalThrustTableFit thrust_table;
  ident::LevelingTableFit leveling_table;
  std::optional<model::GroundEffectModel> table_model;  ///< the vehicle with the fitted tables

  /// The fitted tables' F_G(h), through the controller's own model (PCHIP).
  [[nodiscard]] double tableThrustRatio(double h) const { return table_model->thrustRatio(h); }
  /// The fitted tables' leveling torque at the target's tilt and speed [N·m].
  [[nodiscard]] double tableTorque(double h) const {
    const double T = thrust_table.k_T_N_per_rpm2.value * 4.0 * kTargetRpm * kTargetRpm;
    return -table_model->levelingCoefficient(h) * T * std::sin(kTargetTiltDeg * model::kDegToRad);
  }

  /// The fitted F_G(h).
  [[nodiscard]] double thrustRatio(double h) const {
    return thrust.g2_m2.value / (h * h + thrust.g1_m2.value);
  }
  /// The fitted leveling torque −M_G(h)·T·sin δ at the target's tilt and speed, with the k_T
  /// the scale was fitted with [N·m].
  [[nodiscard]] double torque(double h) const {
    const double T = thrust.k_T_N_per_rpm2.value * 4.0 * kTargetRpm * kTargetRpm;
    return -ident::levelingCoefficient(leveling.g3_m.value, leveling.g4_m2.value,
                                       leveling.scale_m4.value, h) *
           T * std::sin(kTargetTiltDeg * model::kDegToRad);
  }
};

/// Rigs → CSV logs → readers → fits, once per seed (the tests below share the result).
const RoundTrip& roundTrip(std::uint64_t seed) {
  static std::map<std::uint64_t, RoundTrip> cache;
  const auto it = cache.find(seed);
  if (it != cache.end()) return it->second;
  // One directory per test (CTest runs each test as its own process, possibly in parallel).
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const auto dir = ident_test::tempDir("round_trip_" + test + "_" + std::to_string(seed));
  writePlatformLog(dir / "platform.csv", seed);
  writeStandLog(dir / "rotor.csv", seed);
  const double b = geaware_test::paperParams().diagonal_rotor_distance_m;

  RoundTrip rt;
  const auto platform = ident::readPlatformLog(dir / "platform.csv");
  rt.thrust = ident::fitAdditionalThrust(platform);
  rt.mixing = ident::fitMixing(platform, b);
  // The leveling torque is fitted on the 15° board: the truth's torque stops growing in
  // proportion to sin δ above about 10° (as the paper measured), so M_G·T·sin δ fitted at
  // ≤ 10° (the default limit) overestimates the 15° torque by ~25 % at its peak.
  ident::LevelingFitOptions lo;
  lo.max_tilt_deg = kTargetTiltDeg;
  rt.leveling = ident::fitLeveling(
      platform, {rt.thrust.k_T_N_per_rpm2.value, rt.mixing.k_TY_N_per_rpm2.value().value, b},
      lo);
  rt.stand = ident::fitRotorStand(ident::readRotorStandLog(dir / "rotor.csv"));

  rt.thrust_table = ident::fitAdditionalThrustTable(platform);
  rt.leveling_table = ident::fitLevelingTable(
      platform,
      {rt.thrust_table.k_T_N_per_rpm2.value, rt.mixing.k_TY_N_per_rpm2.value().value, b}, lo);
  model::VehicleParams v = geaware_test::paperParams();
  v.min_rotor_plane_height_m = 0.07;  // the rig's lowest board height
  const auto values = [](const ident::TableCurve& c) {
    std::vector<double> out;
    for (const auto& e : c.values) out.push_back(e.value);
    return out;
  };
  v.additional_thrust.table = {rt.thrust_table.F_G.heights_m, values(rt.thrust_table.F_G)};
  v.leveling_torque.table = {rt.leveling_table.M_G.heights_m, values(rt.leveling_table.M_G)};
  rt.table_model.emplace(v);
  return cache.emplace(seed, std::move(rt)).first->second;
}

struct WorstError {
  double value = 0.0;  ///< signed error of largest magnitude
  double h_m = 0.0;    ///< where
};

template <typename Error>
WorstError worstOver(double from, double to, Error error) {
  WorstError w;
  for (double h : compareHeights(from, to)) {
    const double e = error(h);
    if (std::abs(e) > std::abs(w.value)) w = {e, h};
  }
  return w;
}

double relative(double fitted, double truth_value) { return fitted / truth_value - 1.0; }

// ------------------------------------------------------------------------------------ tests

TEST(RoundTrip, MixingCoefficientsWithinTwoPercentOfTheTruth) {
  // Issue tolerance, met: out of ground effect the truth's mixing is exactly the form of eq. 2.
  const auto& p = geaware_test::paperParams();
  for (std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto& m = roundTrip(seed).mixing;
    ASSERT_TRUE(m.k_TX_N_per_rpm2 && m.k_TY_N_per_rpm2 && m.k_I_Nm_per_rpm2);
    const double e_TX = relative(m.k_TX_N_per_rpm2->value, truth().mixing(1));
    const double e_TY = relative(m.k_TY_N_per_rpm2->value, truth().mixing(2));
    const double e_I = relative(m.k_I_Nm_per_rpm2->value, truth().mixing(3));
    EXPECT_NEAR(e_TX, 0.0, kIssueMixingTol);
    EXPECT_NEAR(e_TY, 0.0, kIssueMixingTol);
    EXPECT_NEAR(e_I, 0.0, kIssueMixingTol);
    // The single-rotor stand (free air) holds the same rotor: its k_T and k_I are the truth's.
    const auto& s = roundTrip(seed).stand;
    const double e_T_stand = relative(s.k_T_N_per_rpm2.value, p.rotor.k_T_N_per_rpm2);
    const double e_I_stand = relative(s.k_I_Nm_per_rpm2.value, p.rotor.k_I_Nm_per_rpm2);
    EXPECT_NEAR(e_T_stand, 0.0, kIssueMixingTol);
    EXPECT_NEAR(e_I_stand, 0.0, kIssueMixingTol);
    ASSERT_TRUE(s.J_R_kgm2.has_value());
    // J_R comes from the 30 ms speed transients only: 10 %.
    EXPECT_NEAR(relative(s.J_R_kgm2->value, p.rotor.J_R_kgm2), 0.0, 0.10);
    std::printf("[ round trip seed %d ] platform k_TX %+.2f %%, k_TY %+.2f %%, k_I %+.2f %%; "
                "stand k_T %+.2f %%, k_I %+.2f %%, J_R %+.1f %%\n",
                static_cast<int>(seed), 100.0 * e_TX, 100.0 * e_TY, 100.0 * e_I,
                100.0 * e_T_stand, 100.0 * e_I_stand,
                100.0 * relative(s.J_R_kgm2->value, p.rotor.J_R_kgm2));
    const model::ThrottleCurve curve(p.throttle);
    for (double t : {0.2, 0.5, 1.0}) {
      const double n = std::sqrt((s.c2_rpm2.value * t + s.c1_rpm2.value) * t + s.c0_rpm2.value);
      EXPECT_NEAR(relative(n, curve.speedRpm(t)), 0.0, 0.01) << "throttle " << t;
    }
  }
}

TEST(RoundTrip, AdditionalThrustMatchesTheTruthAsCloseAsItsFormAllows) {
  // The issue asks for F_G within 5 % over 0.07–1 m. NO g2/(h² + g1) can do that here: the
  // truth's F_G is the sum of a vehicle-scale cushion with a ~1/h² tail and a rotor-resolved
  // impingement term that switches on below the wake-merge height (0.305 m). One scale g2
  // cannot fit both the tail above 0.3 m (≈ 0.0062/h²) and the steeper rise below it; the best
  // possible curve is still 10 % off somewhere in the range (computed here, exact in g2).
  const double bound = bestThrustFormError(0.07, 1.0);
  EXPECT_GT(bound, kIssueThrustTol) << "the form can now meet the issue's 5 %: tighten below";
  EXPECT_NEAR(bound, 0.103, 0.005);
  // The fit minimises force residuals in newtons (the sensor's additive noise), so it follows
  // the large near-ground values and leaves the small tail ~20 % high: a residual of 0.01 in
  // F_G is 0.36 N at 0.07 m but the whole F_G at 0.85 m. Tolerance it meets (seeds 1–3:
  // 22–23 %, at 1 m), documented in docs/identification.md.
  constexpr double kMetThrustTol = 0.25;
  for (std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto& rt = roundTrip(seed);
    const auto worst = worstOver(0.07, 1.0, [&](double h) {
      return relative(rt.thrustRatio(h), truth().thrustRatio(h));
    });
    EXPECT_LT(std::abs(worst.value), kMetThrustTol) << "at h = " << worst.h_m << " m";
    // The issue's 5 % holds where the form can follow the truth: above the truth's near-ground
    // saturation (its rotor-resolved gain is held at its peak below z* ≈ 0.083 m, so the
    // truth flattens while the form keeps rising) and below the wake-merge kink.
    const auto near = worstOver(0.10, 0.25, [&](double h) {
      return relative(rt.thrustRatio(h), truth().thrustRatio(h));
    });
    EXPECT_LT(std::abs(near.value), kIssueThrustTol) << "at h = " << near.h_m << " m";
    std::printf("[ round trip seed %d ] F_G: worst %+.1f %% at %.3f m (0.07-1 m), "
                "worst %+.1f %% over 0.10-0.25 m (k_T %.5g, g1 %.4g, g2 %.4g)\n",
                static_cast<int>(seed), 100.0 * worst.value, worst.h_m, 100.0 * near.value,
                rt.thrust.k_T_N_per_rpm2.value, rt.thrust.g1_m2.value, rt.thrust.g2_m2.value);
  }
}

TEST(RoundTrip, LevelingTorqueMatchesTheTruthAsCloseAsItsFormAllows) {
  // The issue asks for the torque at 15° within 10 % over 0.1–0.35 m. The truth's torque (like
  // the paper's measurement, docs/paper-facts.md) collapses above 0.27 m where slipstreams merge:
  // −0.171 N·m at 0.27 m, −0.035 at 0.33, −0.014 at 0.35, a factor 12 in 8 cm. M_G's smooth
  // peak cannot fall that fast; the best possible curve of the form is 54 % off somewhere in
  // the range (a pointwise relative error, dominated by the small values near 0.35 m).
  const double bound = bestTorqueFormError(0.10, 0.35);
  EXPECT_GT(bound, kIssueTorqueTol) << "the form can now meet the issue's 10 %: tighten below";
  EXPECT_NEAR(bound, 0.54, 0.03);
  // Tolerances it meets: relative to the truth's peak torque (0.209 N·m), the error stays
  // below 30 % over the whole range (seeds 1–3: 29.3–29.5 %, at 0.34 m, where the truth has
  // collapsed and the form has not; the best possible curve: 19 %);
  // pointwise, the issue's 10 % holds below the collapse, 0.10–0.24 m.
  constexpr double kMetPeakRelativeTol = 0.30;
  double peak = 0.0;
  for (double h : compareHeights(0.10, 0.35)) peak = std::max(peak, std::abs(truth().torque(h)));
  for (std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto& rt = roundTrip(seed);
    const auto worst = worstOver(0.10, 0.35, [&](double h) {
      return (rt.torque(h) - truth().torque(h)) / peak;
    });
    EXPECT_LT(std::abs(worst.value), kMetPeakRelativeTol) << "at h = " << worst.h_m << " m";
    const auto pointwise = worstOver(0.10, 0.35, [&](double h) {
      return relative(rt.torque(h), truth().torque(h));
    });
    const auto below = worstOver(0.10, 0.24, [&](double h) {
      return relative(rt.torque(h), truth().torque(h));
    });
    EXPECT_LT(std::abs(below.value), kIssueTorqueTol) << "at h = " << below.h_m << " m";
    std::printf("[ round trip seed %d ] torque(15 deg): worst %+.1f %% of the peak at %.3f m, "
                "pointwise %+.0f %% at %.3f m (0.10-0.35 m), %+.1f %% at %.3f m (0.10-0.24 m) "
                "(g3 %.4g, g4 %.4g, scale %.4g)\n",
                static_cast<int>(seed), 100.0 * worst.value, worst.h_m, 100.0 * pointwise.value,
                pointwise.h_m, 100.0 * below.value, below.h_m, rt.leveling.g3_m.value,
                rt.leveling.g4_m2.value, rt.leveling.scale_m4.value);
  }
}

TEST(RoundTrip, TablesMeetTheIssueTolerancesForBothCurves) {
  // With both curves identified as tables (knots at the logged heights; F_G's tail above
  // 0.5 m fixes k_T), evaluated through model::GroundEffectModel exactly as the controller
  // would, the issue's tolerances hold: F_G within 5 % over 0.07–1 m and the torque at 15°
  // within 10 % over 0.1–0.35 m, pointwise, comparing every 2.5 mm (between the 1 cm knots).
  for (std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto& rt = roundTrip(seed);
    const auto thrust = worstOver(0.07, 1.0, [&](double h) {
      return relative(rt.tableThrustRatio(h), truth().thrustRatio(h));
    });
    const auto torque = worstOver(0.10, 0.35, [&](double h) {
      return relative(rt.tableTorque(h), truth().torque(h));
    });
    EXPECT_LT(std::abs(thrust.value), kIssueThrustTol) << "at h = " << thrust.h_m << " m";
    EXPECT_LT(std::abs(torque.value), kIssueTorqueTol) << "at h = " << torque.h_m << " m";
    const double e_kT = relative(rt.thrust_table.k_T_N_per_rpm2.value,
                                 geaware_test::paperParams().rotor.k_T_N_per_rpm2);
    EXPECT_NEAR(e_kT, 0.0, kIssueMixingTol);
    for (const auto& w : rt.thrust_table.warnings) ADD_FAILURE() << "F_G table: " << w;
    for (const auto& w : rt.leveling_table.warnings) ADD_FAILURE() << "M_G table: " << w;
    std::printf("[ round trip seed %d ] tables: F_G worst %+.2f %% at %.4f m (0.07-1 m, %zu "
                "knots), torque(15 deg) worst %+.2f %% at %.4f m (0.10-0.35 m, %zu knots), "
                "k_T %+.3f %%\n",
                static_cast<int>(seed), 100.0 * thrust.value, thrust.h_m,
                rt.thrust_table.F_G.heights_m.size(), 100.0 * torque.value, torque.h_m,
                rt.leveling_table.M_G.heights_m.size(), 100.0 * e_kT);
  }
}

}  // namespace
