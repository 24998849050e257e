// SPDX-License-Identifier: BSD-3-Clause
// Running a sweep (experiments/sweep.hpp): a key's record is the flight it names, the merged
// file is byte-identical for any number of threads, and a rerun flies only the keys without a
// record.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/fault_suite.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/robustness.hpp"
#include "geaware/experiments/suite_sweep.hpp"
#include "geaware/experiments/sweep.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/config_error.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/traj/lemniscate.hpp"
#include "sweep_support.hpp"

namespace ex = geaware::experiments;
namespace fs = std::filesystem;
using geaware::sweep_test::slurp;
using geaware::sweep_test::sourceDir;
using geaware::sweep_test::TempDir;

namespace {

const ex::SweepSpec& spec64() {
  static const ex::SweepSpec s = ex::loadSweepFile(sourceDir() / "tests/sweep/sweep64.yaml");
  return s;
}

/// Every key flown into a fresh `dir` on `threads` threads; the merged text.
std::string runAll(const fs::path& dir, int threads) {
  ex::prepareSweepDirectory(spec64(), dir);
  const auto keys = ex::missingSweepKeys(spec64(), dir);
  EXPECT_EQ(keys.size(), 64u);
  EXPECT_EQ(ex::runSweepKeys(spec64(), dir, keys, threads), 64u);
  EXPECT_TRUE(ex::missingSweepKeys(spec64(), dir).empty());
  return ex::mergeSweepText(spec64(), dir);
}

}  // namespace

TEST(SweepRun, AKeysRecordIsTheFlightItNames) {
  // The flight of case=mass+10%/ctl=indi:none/scn=slow-high/seed=3, built by hand as the file
  // says: the built-in vehicle in its default world, uncalibrated, the truth's mass × 1.1.
  ex::FlightScenario f;
  f.vehicle = geaware::io::builtinVehicle();
  ex::applyWorld(f, ex::defaultWorld(f.vehicle, true, "builtin"));
  f.start_hover_s = 1.0;
  f.truth->mass_kg *= 1.10;
  geaware::traj::LemniscateParams lp;
  lp.height_m = 1.0;
  lp.peak_speed_mps = 0.5;
  lp.half_extent_x_m = 0.6;
  lp.half_extent_y_m = 0.3;
  f.trajectory = std::make_shared<geaware::traj::Lemniscate>(lp);
  ASSERT_TRUE(geaware::control::parseConfiguration("indi:none", f.controller));
  f.seed = 3;
  const ex::FlightResult r = ex::runFlight(f);
  const ex::SuiteFlight expected = ex::toSuiteFlight(3, r);

  const std::string key = "case=mass+10%/ctl=indi:none/scn=slow-high/seed=3";
  const std::string record = ex::runSweepFlight(spec64(), key);
  const auto j = geaware::io::Json::parse(record);
  EXPECT_EQ(j["key"], key);
  EXPECT_EQ(j["case"], "mass+10%");
  EXPECT_EQ(j["controller"], "indi:none");
  EXPECT_EQ(j["scenario"], "slow-high");
  EXPECT_EQ(j["seed"], 3);
  EXPECT_EQ(j["struck"], expected.struck);
  EXPECT_EQ(j["rmse_all_cm"].get<double>(), expected.rmse_all_cm);
  EXPECT_EQ(j["rmse_xy_cm"].get<double>(), expected.rmse_xy_cm);
  EXPECT_EQ(j["max_cm"].get<double>(), expected.max_cm);
  EXPECT_EQ(j["simulated_s"].get<double>(), r.simulated_s);
  EXPECT_GT(expected.rmse_all_cm, 0.0);
  // One line, and the same bytes when flown again.
  EXPECT_EQ(record.find('\n'), std::string::npos);
  EXPECT_EQ(ex::runSweepFlight(spec64(), key), record);
  // Another seed is another flight.
  EXPECT_NE(ex::runSweepFlight(spec64(), "case=mass+10%/ctl=indi:none/scn=slow-high/seed=2"), record);
}

TEST(SweepRun, MergedResultsAreByteIdenticalForOneAndTwoThreadsAndAResumeFliesOnlyTheMissing) {
  TempDir a("sweep-a"), b("sweep-b");
  const std::string one = runAll(a.path(), 1);
  const std::string two = runAll(b.path(), 2);
  EXPECT_EQ(one, two);
  const auto doc = geaware::io::Json::parse(one);
  ASSERT_EQ(doc["records"].size(), 64u);
  EXPECT_EQ(doc["flights"], 64);
  const auto keys = ex::sweepKeys(spec64());
  for (std::size_t i = 0; i < keys.size(); ++i) EXPECT_EQ(doc["records"][i]["key"], keys[i]);
  // Flights differ (a merge of one record 64 times would not).
  std::set<double> rmse;
  for (const auto& r : doc["records"]) rmse.insert(r["rmse_all_cm"].get<double>());
  EXPECT_GT(rmse.size(), 60u);

  // Remove four records, truncate one and give one another key's text: exactly these six are
  // missing, a rerun flies six, the others are not touched, the merge is the same.
  std::map<std::string, fs::file_time_type> before;
  for (const auto& k : keys) before[k] = fs::last_write_time(ex::sweepFlightPath(a.path(), k));
  const std::vector<std::size_t> gone = {0, 17, 40, 63};
  for (const auto i : gone) fs::remove(ex::sweepFlightPath(a.path(), keys[i]));
  {  // cut half-way, as a write killed part-way would leave it
    const fs::path cut = ex::sweepFlightPath(a.path(), keys[5]);
    const std::string whole = slurp(cut);
    std::ofstream(cut, std::ios::trunc) << whole.substr(0, whole.size() / 2);
  }
  fs::copy_file(ex::sweepFlightPath(a.path(), keys[7]), ex::sweepFlightPath(a.path(), keys[9]),
                fs::copy_options::overwrite_existing);
  EXPECT_THROW((void)ex::mergeSweepText(spec64(), a.path()), std::runtime_error);
  const auto missing = ex::missingSweepKeys(spec64(), a.path());
  EXPECT_EQ(missing, (std::vector<std::string>{keys[0], keys[5], keys[9], keys[17], keys[40], keys[63]}));
  EXPECT_EQ(ex::runSweepKeys(spec64(), a.path(), missing, 2), 6u);
  EXPECT_EQ(ex::mergeSweepText(spec64(), a.path()), one);
  for (const auto& k : keys) {
    if (std::find(missing.begin(), missing.end(), k) != missing.end()) continue;
    EXPECT_EQ(fs::last_write_time(ex::sweepFlightPath(a.path(), k)), before[k]) << k;
  }
  // Nothing but the records (no temporary file left).
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(a.path() / "flights")) {
    EXPECT_EQ(e.path().extension(), ".json") << e.path();
    ++files;
  }
  EXPECT_EQ(files, 64u);
}

TEST(SweepRun, MergeNamesTheMissingAndADirectoryKeepsItsSweep) {
  TempDir d("sweep-d");
  ex::prepareSweepDirectory(spec64(), d.path());
  try {
    (void)ex::mergeSweepText(spec64(), d.path());
    FAIL() << "merged nothing";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("64 of 64 flights have no record"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("case=none/ctl=recommended/scn=lem-0.3m-1mps/seed=1"));
  }
  ex::SweepSpec other = spec64();
  other.fingerprint = "0123";
  other.file_sha256 = "0123";  // another sweep file
  try {
    ex::prepareSweepDirectory(other, d.path());
    FAIL() << "another sweep's directory was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("holds the results of another sweep ("));
  }
  ex::prepareSweepDirectory(spec64(), d.path());  // the same sweep: fine
  // A directory of a build whose fingerprint was the sweep file's SHA-256 alone, for a sweep
  // that names files: refused, with the line that resumes it if those files did not change.
  ex::SweepSpec named = spec64();
  named.fingerprint = "with-named-files";
  named.file_sha256 = spec64().fingerprint;
  try {
    ex::prepareSweepDirectory(named, d.path());
    FAIL() << "an older build's directory was taken as this sweep's";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("alone, as builds before 2026-11-29 wrote it"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("replace that line with with-named-files"));
  }
}

TEST(SweepRun, AFailingFlightIsReportedWithItsKey) {
  // A lemniscate at 6 m/s with 0.3 s ramps is beyond the motors. The file is refused at the
  // scenario's line before any work; a spec whose trajectory is swapped after the reading
  // (as if the calibrated belief made it infeasible) fails at the flight, the error naming the key.
  std::string text = slurp(sourceDir() / "tests/sweep/sweep64.yaml");
  const std::string from = "speed_mps: 1.0,";
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(text.find(from)), '\n');
  text.replace(text.find(from), from.size(), "speed_mps: 6.0, ramp_time_s: 0.3,");
  try {
    (void)ex::parseSweepYaml(text, "fast.yaml", sourceDir() / "tests/sweep");
    FAIL() << "an infeasible scenario was accepted";
  } catch (const geaware::io::ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].line, line);
    EXPECT_EQ(e.problems()[0].key, "scenarios[0]");
    EXPECT_THAT(e.problems()[0].message, ::testing::HasSubstr("cannot be flown: trajectory = rotor speeds beyond"));
  }
  ex::SweepSpec s = spec64();
  geaware::traj::LemniscateParams lp;
  lp.height_m = 0.3;
  lp.peak_speed_mps = 6.0;
  lp.ramp_time_s = 0.3;
  lp.half_extent_x_m = 1.0;
  lp.half_extent_y_m = 0.5;
  s.scenarios[0].trajectory = std::make_shared<geaware::traj::Lemniscate>(lp);
  s.fingerprint = "swapped";
  TempDir d("sweep-e");
  ex::prepareSweepDirectory(s, d.path());
  const std::vector<std::string> keys = {"case=none/ctl=recommended/scn=lem-0.3m-1mps/seed=1"};
  try {
    (void)ex::runSweepKeys(s, d.path(), keys, 1);
    FAIL() << "flew";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("flight case=none/ctl=recommended/scn=lem-0.3m-1mps/seed=1: "));
  }
  EXPECT_FALSE(ex::sweepFlightDone(d.path(), keys[0]));
}

TEST(SweepRun, ACalibratedSweepFliesTheRobustnessSuitesFlightBitForBit) {
  // One cell of `geaware bench --suite robustness` (calibrated once in the default world, then
  // mass +10 %) and the same flight as a sweep key: the same numbers, to the last bit.
  const std::string text =
      "vehicle: builtin\nworld: default\ncalibrate: true\n"
      "perturbations: [{name: mass+10%}]\ncontrollers: [recommended]\n"
      "scenarios: [{type: lemniscate, height_m: 0.12, speed_mps: 1.0, half_extent_x_m: 1.5, half_extent_y_m: 0.8}]\n"
      "seeds: {first: 2, count: 1}\n";
  const ex::SweepSpec s = ex::parseSweepYaml(text, "cal.yaml", sourceDir());
  const auto record = geaware::io::Json::parse(
      ex::runSweepFlight(s, "case=mass+10%/ctl=recommended/scn=lem-0.12m-1mps/seed=2"));

  // The suite flown from the same file (as `bench --suite robustness --sweep cal.yaml`).
  ex::RobustnessOptions o = ex::robustnessOptionsOf(s);
  o.jobs = 1;
  const ex::RobustnessResult r = ex::runRobustness(o);
  ASSERT_EQ(r.cells.size(), 1u);
  EXPECT_EQ(r.cells[0].case_name, "mass+10%");
  EXPECT_EQ(r.cells[0].controller, "recommended");
  EXPECT_EQ(r.seeds, std::vector<std::uint64_t>{2});
  const ex::SuiteFlight& f = r.cells[0].flights.at(0);
  EXPECT_EQ(record["struck"], f.struck);
  EXPECT_EQ(record["rmse_all_cm"].get<double>(), f.rmse_all_cm);
  EXPECT_EQ(record["rmse_xy_cm"].get<double>(), f.rmse_xy_cm);
  EXPECT_EQ(record["rmse_z_cm"].get<double>(), f.rmse_z_cm);
  EXPECT_EQ(record["max_cm"].get<double>(), f.max_cm);
  ASSERT_TRUE(f.guard_active_s.has_value());
  EXPECT_EQ(record["guard_active_s"].get<double>(), *f.guard_active_s);
}

TEST(SweepRun, AFaultKeyFliesTheFaultSuitesFlightBitForBit) {
  // `fault: motor 80%` flies what `geaware bench --suite faults` flies for that cell and seed.
  const std::string text =
      "vehicle: builtin\nworld: default\ncalibrate: true\n"
      "perturbations: [{fault: none}, {fault: motor 80%}]\ncontrollers: [recommended]\n"
      "scenarios: [{type: lemniscate, height_m: 0.12, speed_mps: 1.0, half_extent_x_m: 1.5, half_extent_y_m: 0.8}]\n"
      "seeds: {first: 1, count: 1}\n";
  const ex::SweepSpec s = ex::parseSweepYaml(text, "fault.yaml", sourceDir());
  const auto record = geaware::io::Json::parse(
      ex::runSweepFlight(s, "case=motor 80%/ctl=recommended/scn=lem-0.12m-1mps/seed=1"));

  // The campaign flown from the same file (as `bench --suite faults --sweep fault.yaml`).
  ex::FaultSuiteOptions o = ex::faultSuiteOptionsOf(s);
  o.jobs = 1;
  const ex::FaultSuiteResult r = ex::runFaultSuite(o);
  ASSERT_EQ(r.cells.size(), 2u);
  EXPECT_EQ(r.cells[1].cell.case_name, "motor 80%");
  EXPECT_EQ(r.cells[1].cell.controller, "recommended");
  const ex::FaultFlight& f = r.cells[1].flights.at(0);
  EXPECT_EQ(record["struck"], f.flight.struck);
  EXPECT_EQ(record["terminated"], f.terminated);
  EXPECT_EQ(record["non_finite_commands"], f.non_finite_commands);
  EXPECT_EQ(record["rmse_all_cm"].get<double>(), f.flight.rmse_all_cm);
  EXPECT_EQ(record["max_cm"].get<double>(), f.flight.max_cm);
  EXPECT_GT(f.flight.max_cm, 0.0);
  // And it is not the unbroken flight.
  EXPECT_NE(record["rmse_all_cm"].get<double>(), r.cells[0].flights.at(0).flight.rmse_all_cm);
}

TEST(SweepRun, ADirectoryThatIsNoSweepsIsRefusedAndLeftAsItWas) {
  // A results.json or records of unknown origin (no sweep.sha256): the merge would overwrite the
  // one and merge the others, so the directory is refused and nothing in it changes. Other
  // files are the user's to keep beside the sweep's.
  TempDir d("sweep-f");
  const fs::path mine = d.path() / "results.json";
  std::ofstream(mine) << "the results of another program\n";
  try {
    ex::prepareSweepDirectory(spec64(), d.path());
    FAIL() << "a directory holding someone's results.json was taken";
  } catch (const geaware::io::OutputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("results.json and no sweep.sha256"));
  }
  EXPECT_EQ(slurp(mine), "the results of another program\n");
  EXPECT_FALSE(fs::exists(d.path() / "sweep.sha256"));
  EXPECT_FALSE(fs::exists(d.path() / "flights"));

  fs::remove(mine);
  fs::create_directories(d.path() / "flights");
  const std::string key = ex::sweepKeys(spec64()).front();
  std::ofstream(ex::sweepFlightPath(d.path(), key)) << "{}\n";
  EXPECT_THROW(ex::prepareSweepDirectory(spec64(), d.path()), geaware::io::OutputError);
  EXPECT_FALSE(fs::exists(d.path() / "sweep.sha256"));

  fs::remove(ex::sweepFlightPath(d.path(), key));  // an empty flights/ (a run stopped at once)
  std::ofstream(d.path() / "notes.txt") << "mine\n";
  ex::prepareSweepDirectory(spec64(), d.path());
  EXPECT_TRUE(fs::exists(d.path() / "sweep.sha256"));
  EXPECT_EQ(slurp(d.path() / "notes.txt"), "mine\n");

  // A results.json that is not a file is refused before any flight, not after the last.
  fs::create_directory(mine);
  EXPECT_THROW(ex::prepareSweepDirectory(spec64(), d.path()), geaware::io::OutputError);
}

TEST(SweepRun, AFileWithTheKeyButNotARecordIsFlownAgain) {
  TempDir d("sweep-g");
  ex::prepareSweepDirectory(spec64(), d.path());
  const std::string key = ex::sweepKeys(spec64()).front();
  ex::writeSweepFlight(d.path(), key, geaware::io::Json{{"key", key}}.dump());
  EXPECT_FALSE(ex::sweepFlightDone(d.path(), key));
  ex::writeSweepFlight(d.path(), key, ex::runSweepFlight(spec64(), key));
  EXPECT_TRUE(ex::sweepFlightDone(d.path(), key));
}

// A run killed by SIGKILL leaves its record's temporary file; the next run of the same sweep
// removes it once it is an hour old (a younger one may be a concurrent writer's), and nothing else.
TEST(SweepRun, AResumeRemovesTheTemporaryFilesAKilledRunLeft) {
  TempDir d("sweep-t");
  ex::prepareSweepDirectory(spec64(), d.path());
  const fs::path flights = d.path() / "flights";
  const std::string key = ex::sweepFlightPath(d.path(), ex::sweepKeys(spec64()).front()).stem().string();
  const auto write = [&](const std::string& name, bool old) {
    std::ofstream(flights / name) << geaware::io::Json{{"key", key}}.dump().substr(0, 8);  // cut short
    if (old) fs::last_write_time(flights / name, fs::file_time_type::clock::now() - std::chrono::hours(2));
  };
  const std::string stale = "." + key + ".json.geaware-a1B2c3";
  write(stale, true);
  write("." + key + ".json.geaware-Z9y8x7", false);  // young: perhaps another process writing
  write(".notes.geaware-a1B2c3", true);             // not a record's
  write("." + key + ".json.geaware-a1B2", true);     // not mkstemp's six characters
  write(key + ".json.geaware-a1B2c3", true);         // not hidden
  ex::prepareSweepDirectory(spec64(), d.path());
  std::set<std::string> left;
  for (const auto& e : fs::directory_iterator(flights)) left.insert(e.path().filename().string());
  EXPECT_EQ(left, (std::set<std::string>{"." + key + ".json.geaware-Z9y8x7", ".notes.geaware-a1B2c3",
                                         "." + key + ".json.geaware-a1B2", key + ".json.geaware-a1B2c3"}));
}
