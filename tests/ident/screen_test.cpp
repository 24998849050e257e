// SPDX-License-Identifier: BSD-3-Clause
// Screening before the fits (issue 11, "What was found"): the recorded defects reproduced on
// synthetic logs — rows at rpm = 0 in a stand log, an all-zero thrust column, a rotor channel
// alternating with 0 — each refused or dropped with a count, naming the file and the column.

#include "geaware/ident/screen.hpp"

#include <string>

#include <gtest/gtest.h>

#include "geaware/ident/rotor_fit.hpp"
#include "synthetic.hpp"

namespace {

namespace ident = geaware::ident;

/// The message of the IdentError `f` throws ("" when it throws none).
template <class F>
std::string identError(const F& f) {
  try {
    f();
  } catch (const ident::IdentError& e) {
    return e.what();
  }
  return "";
}

TEST(Screen, StandRowsAtZeroRpmAreDroppedAndCountedAndNoLongerWreckTheThrottleCurve) {
  // The defect: 13 rows of a stopped rotor (rpm 0, thrust 0, throttle 0.05) among 2,000 good
  // rows moved the throttle curve by −58 to −100 %.
  const auto& p = geaware_test::paperParams();
  ident_test::StandSpec spec;
  spec.duration_s = 2.0;
  ident::RotorStandLog log = ident_test::syntheticStand(spec, 4);
  const auto clean = ident::fitRotorStand(log);
  const std::size_t good = log.size();
  for (int k = 0; k < 13; ++k) {
    log.t_s.push_back(log.t_s.back() + spec.dt_s);
    log.throttle.push_back(0.05);
    log.rpm.push_back(0.0);
    log.thrust_N.push_back(0.0);
    log.torque_Nm.push_back(0.0);
  }
  const auto notes = ident::screenRotorStand(log, {});
  ASSERT_EQ(notes.size(), 1U);
  EXPECT_NE(notes[0].find("13 of " + std::to_string(good + 13) + " rows at rpm = 0 or thrust ≤ 0"),
            std::string::npos)
      << notes[0];
  EXPECT_EQ(log.size(), good);
  EXPECT_EQ(log.thrust_N.size(), good);
  // The screened log is the clean one: the same fit, to the last digit.
  const auto fit = ident::fitRotorStand(log);
  EXPECT_EQ(fit.c2_rpm2.value, clean.c2_rpm2.value);
  EXPECT_EQ(fit.c0_rpm2.value, clean.c0_rpm2.value);
  EXPECT_EQ(fit.k_T_N_per_rpm2.value, clean.k_T_N_per_rpm2.value);
  EXPECT_TRUE(ident_test::withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
}

TEST(Screen, AllZeroThrustColumnIsAnErrorNamingFileAndColumn) {
  // The defect: a stand whose thrust column is all zeros gave k_T = 0 ± 0 with no warning.
  const auto dir = ident_test::tempDir("screen_zero_thrust");
  std::string csv = "t_s,throttle,rpm,load_N,torque_Nm\n";
  for (int i = 0; i < 200; ++i) {
    csv += std::to_string(0.01 * i) + "," + std::to_string(0.2 + 0.003 * i) + "," + std::to_string(5000 + 40 * i) +
           ",0," + std::to_string(0.01 + 0.0001 * i) + "\n";
  }
  ident_test::writeText(dir / "stand.csv", csv);
  ident::RotorStandColumns c;
  c.thrust = "load_N";
  ident::RotorStandLog log = ident::readRotorStandLog(dir / "stand.csv", c);
  const std::string e = identError([&] { (void)ident::screenRotorStand(log, c); });
  EXPECT_NE(e.find("stand.csv"), std::string::npos) << e;
  EXPECT_NE(e.find("column 'load_N' is all zero"), std::string::npos) << e;
  // A constant column is named as such.
  ident::RotorStandLog flat = ident_test::syntheticStand({}, 1);
  for (auto& t : flat.torque_Nm) t = 0.25;
  const std::string f = identError([&] { (void)ident::screenRotorStand(flat, {}); });
  EXPECT_NE(f.find("column 'torque_Nm' is constant (0.25"), std::string::npos) << f;
}

TEST(Screen, RotorChannelAlternatingWithZeroIsNamedAndRefused) {
  // The defect: motor 1's rpm alternating 0 and 9,900 gave k_T +22 % with 0 outliers.
  ident::FlightLog log = ident_test::hoverDescent(3);
  for (std::size_t i = 0; i < log.size(); i += 2) log.n_rpm[0][i] = 0.0;
  ident::FlightColumns c;
  c.n[0] = "motor1_rpm";
  const std::string e = identError([&] { (void)ident::screenFlight(log, c); });
  EXPECT_NE(e.find("rotor channel 'motor1_rpm' alternates with 0"), std::string::npos) << e;
  EXPECT_NE(e.find(log.source), std::string::npos) << e;
}

TEST(Screen, AFlightStartingAndEndingOnTheGroundIsNotAlternatingItsRestingRowsAreDropped) {
  ident::FlightLog log = ident_test::hoverDescent(3);
  const std::size_t n = log.size();
  for (std::size_t i = 0; i < 100; ++i) {
    for (auto& r : log.n_rpm) r[i] = 0.0, r[n - 1 - i] = 0.0;
  }
  log.n_rpm[2][500] = 0.0;  // one telemetry dropout of one rotor
  EXPECT_EQ(ident::zeroSwitches(log.n_rpm[2]), 4U);
  const auto notes = ident::screenFlight(log, {});
  ASSERT_EQ(notes.size(), 1U);
  EXPECT_NE(notes[0].find("201 of " + std::to_string(n) + " rows with a rotor at 0 rpm"), std::string::npos)
      << notes[0];
  EXPECT_EQ(log.size(), n - 201);
  EXPECT_EQ(log.a_ext_W[2].size(), n - 201);
  EXPECT_TRUE(log.v_W[0].empty());  // absent columns stay absent
  // A dead rotor channel is all zero, named.
  for (auto& x : log.n_rpm[3]) x = 0.0;
  const std::string e = identError([&] { (void)ident::screenFlight(log, {}); });
  EXPECT_NE(e.find("column 'n4_rpm' is all zero"), std::string::npos) << e;
}

}  // namespace
