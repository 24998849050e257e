// SPDX-License-Identifier: BSD-3-Clause
// The throttle curve's voltage dependence from stand data with a voltage column
// (ident/voltage_fit.hpp): synthetic steady samples from a known law n = √(c(t))·(V/V_ref)^p with
// rpm noise, the exponent and the coefficients recovered within their standard errors; through
// fitRotorStand and into the vehicle update; a log at one voltage is refused with the reason.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "geaware/ident/identify.hpp"
#include "geaware/ident/rotor_fit.hpp"
#include "geaware/ident/voltage_fit.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::ident {
namespace {

struct Law {
  double c2, c1, c0, v_ref, p;
  [[nodiscard]] double rpm(double t, double v) const {
    return std::sqrt((c2 * t + c1) * t + c0) * std::pow(v / v_ref, p);
  }
};

/// A stand log: throttle steps 0.05…1 at battery voltages from 16.8 V down to 13.6 V (a
/// discharge), rpm noise σ = 20 rpm, thrust/torque from k_T, k_I.
RotorStandLog standLog(const Law& law, std::uint64_t seed, bool with_voltage = true) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 20.0);
  RotorStandLog log;
  log.source = "synthetic stand";
  double t_s = 0.0;
  for (int k = 0; k < 9; ++k) {
    const double v = 16.8 - 0.4 * k;
    for (int j = 1; j <= 20; ++j) {
      const double t = 0.05 * j;
      for (int r = 0; r < 5; ++r) {
        const double n = law.rpm(t, v);
        log.t_s.push_back(t_s);
        t_s += 0.2;  // steady: held long enough
        log.throttle.push_back(t);
        log.rpm.push_back(n + noise(rng));
        log.thrust_N.push_back(4.0083e-8 * n * n);
        log.torque_Nm.push_back(6.3859e-10 * n * n);
        if (with_voltage) log.voltage_V.push_back(v);
      }
    }
  }
  return log;
}

const Law kLaw{-1.448471e8, 5.228928e8, 1.033111e7, 15.2, 1.3};

TEST(VoltageFit, RecoversAKnownLawWithinItsStandardErrors) {
  int within = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const RotorStandLog log = standLog(kLaw, seed);
    const std::vector<char> use(log.size(), 1);
    const ThrottleVoltageFit f = fitThrottleVoltage(log.throttle, log.rpm, log.voltage_V, use, 15.2);
    ASSERT_TRUE(f.fit.ok) << f.fit.message;
    EXPECT_EQ(f.reference_voltage_V, 15.2);
    const Estimate p = f.fit.estimate(3);
    EXPECT_GT(p.std_error, 0.0);
    EXPECT_LT(p.std_error, 0.01);  // 900 samples over ±10 % of voltage determine p well
    EXPECT_LT(std::abs(p.value - kLaw.p), 4.0 * p.std_error) << "seed " << seed;
    within += std::abs(p.value - kLaw.p) <= p.std_error ? 1 : 0;
    const double truth[3] = {kLaw.c2, kLaw.c1, kLaw.c0};
    for (int i = 0; i < 3; ++i) {
      const Estimate c = f.fit.estimate(i);
      EXPECT_LT(std::abs(c.value - truth[i]), 4.0 * c.std_error) << "coefficient " << i << " seed " << seed;
    }
  }
  // The standard error is honest: about 68 % of the seeds within one of it (binomial 10, 0.68:
  // at least 3 with probability > 99.5 %).
  EXPECT_GE(within, 3);
}

TEST(VoltageFit, WithoutAReferenceTheMedianVoltageIsUsedAndTheCurveHoldsThere) {
  const RotorStandLog log = standLog(kLaw, 7);
  const std::vector<char> use(log.size(), 1);
  const ThrottleVoltageFit f = fitThrottleVoltage(log.throttle, log.rpm, log.voltage_V, use);
  ASSERT_TRUE(f.fit.ok) << f.fit.message;
  EXPECT_DOUBLE_EQ(f.reference_voltage_V, 15.2);  // the median of 16.8 … 13.6 V in 0.4 V steps
  const double scale = std::pow(15.2 / kLaw.v_ref, 2.0 * kLaw.p);
  EXPECT_NEAR(f.fit.x(1), kLaw.c1 * scale, 4.0 * std::sqrt(f.fit.covariance(1, 1)));
}

TEST(VoltageFit, RotorStandFitWritesTheVoltageKeys) {
  const RotorStandLog log = standLog(kLaw, 3);
  IdentifyOptions o;
  o.reference_voltage_V = 15.2;
  const IdentifyResult r = identifyRotorStand(log, o);
  ASSERT_TRUE(r.fits.rotor && r.fits.rotor->voltage_exponent);
  EXPECT_NEAR(r.fits.rotor->voltage_exponent->value, 1.3, 0.03);
  EXPECT_EQ(*r.fits.rotor->reference_voltage_V, 15.2);
  bool exponent = false, reference = false;
  for (const auto& e : r.update.entries()) {
    exponent = exponent || e.key == "throttle_curve.voltage_exponent";
    reference = reference || e.key == "throttle_curve.reference_voltage_V";
  }
  EXPECT_TRUE(exponent && reference);
  // Without the column: the curve alone, no voltage keys.
  const IdentifyResult plain = identifyRotorStand(standLog(kLaw, 3, false), {});
  ASSERT_TRUE(plain.fits.rotor);
  EXPECT_FALSE(plain.fits.rotor->voltage_exponent);
}

TEST(VoltageFit, AStandCsvWithAVoltageColumnIsReadAndFitted) {
  const RotorStandLog log = standLog(kLaw, 9);
  const auto path = std::filesystem::temp_directory_path() /
                    ("geaware_voltage_stand_" + std::to_string(::getpid()) + ".csv");
  {
    std::ofstream out(path);
    out.precision(17);
    out << "t_s,throttle,rpm,thrust_N,torque_Nm,vbat\n";
    for (std::size_t i = 0; i < log.size(); ++i) {
      out << log.t_s[i] << ',' << log.throttle[i] << ',' << log.rpm[i] << ',' << log.thrust_N[i]
          << ',' << log.torque_Nm[i] << ',' << log.voltage_V[i] << '\n';
    }
  }
  RotorStandColumns c;
  c.voltage = "vbat";
  const RotorStandLog back = readRotorStandLog(path, c);
  const RotorStandLog without = readRotorStandLog(path, {});  // the column is not read
  std::filesystem::remove(path);
  EXPECT_TRUE(without.voltage_V.empty());
  ASSERT_EQ(back.voltage_V, log.voltage_V);
  const RotorFit fit = fitRotorStand(back);
  ASSERT_TRUE(fit.voltage_exponent);
  EXPECT_LT(std::abs(fit.voltage_exponent->value - kLaw.p), 4.0 * fit.voltage_exponent->std_error);
}

TEST(VoltageFit, OneVoltageCannotSeparateTheDependence) {
  RotorStandLog log = standLog(kLaw, 5);
  for (auto& v : log.voltage_V) v = 16.0;
  const std::vector<char> use(log.size(), 1);
  const ThrottleVoltageFit f = fitThrottleVoltage(log.throttle, log.rpm, log.voltage_V, use);
  EXPECT_FALSE(f.fit.ok);
  EXPECT_NE(f.fit.message.find("cannot be separated"), std::string::npos) << f.fit.message;
  EXPECT_THROW((void)fitRotorStand(log), IdentError);
}

}  // namespace
}  // namespace geaware::ident
