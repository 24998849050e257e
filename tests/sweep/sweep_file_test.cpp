// SPDX-License-Identifier: BSD-3-Clause
// The sweep file (experiments/sweep.hpp, docs/sweeps.md): what it expands to, its keys and
// their file names, and the errors that name the file, the line and the key.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <span>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/experiments/fault_suite.hpp"
#include "geaware/experiments/robustness.hpp"
#include "geaware/experiments/sweep.hpp"
#include "geaware/io/config_error.hpp"
#include "geaware/io/provenance.hpp"
#include "sweep_support.hpp"

using geaware::experiments::parseSweepYaml;
using geaware::experiments::SweepSpec;
using geaware::sweep_test::slurp;
using geaware::sweep_test::sourceDir;

namespace {

std::string sweep64() { return slurp(sourceDir() / "tests/sweep/sweep64.yaml"); }

SweepSpec parse(const std::string& text) {
  return parseSweepYaml(text, "s.yaml", sourceDir() / "tests/sweep");
}

std::string replaced(const std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos) {
    throw std::logic_error("pattern must occur exactly once: " + from);
  }
  return text.substr(0, at) + to + text.substr(at + from.size());
}

int lineOf(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return at == std::string::npos ? -1 : 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

std::vector<geaware::io::ConfigProblem> problemsOf(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const geaware::io::ConfigError& e) {
    EXPECT_EQ(e.file(), "s.yaml");
    EXPECT_THAT(e.what(), ::testing::HasSubstr("s.yaml:"));
    return e.problems();
  }
  ADD_FAILURE() << "the sweep was accepted";
  return {};
}

/// The one problem of `text`: at `line`, key `key`, the message containing `words`.
void expectProblem(const std::string& text, int line, const std::string& key, const std::string& words) {
  const auto p = problemsOf(text);
  ASSERT_EQ(p.size(), 1u) << (p.empty() ? "" : p[0].message) << (p.size() > 1 ? " | " + p[1].key + ": " + p[1].message : "");
  EXPECT_EQ(p[0].line, line);
  EXPECT_EQ(p[0].key, key);
  EXPECT_THAT(p[0].message, ::testing::HasSubstr(words));
}

}  // namespace

TEST(SweepFile, TheTestSweepExpandsToSixtyFourKeysInSpecOrder) {
  const SweepSpec s = parse(sweep64());
  ASSERT_EQ(s.flights(), 64u);
  const auto keys = geaware::experiments::sweepKeys(s);
  ASSERT_EQ(keys.size(), 64u);
  EXPECT_EQ(keys.front(), "case=none/ctl=recommended/scn=lem-0.3m-1mps/seed=1");
  EXPECT_EQ(keys[1], "case=none/ctl=recommended/scn=lem-0.3m-1mps/seed=2");
  EXPECT_EQ(keys[4], "case=none/ctl=recommended/scn=slow-high/seed=1");
  EXPECT_EQ(keys[8], "case=none/ctl=indi:none/scn=lem-0.3m-1mps/seed=1");
  EXPECT_EQ(keys.back(), "case=windy/ctl=indi:none/scn=slow-high/seed=4");
  EXPECT_EQ(keys[16], "case=mass+10%/ctl=recommended/scn=lem-0.3m-1mps/seed=1");
  EXPECT_EQ(keys[32], "case=cushion+0.5/ctl=recommended/scn=lem-0.3m-1mps/seed=1");
  // The named suite case is the robustness suite's own.
  EXPECT_EQ(s.cases[1].kind, geaware::experiments::PerturbationKind::kMass);
  EXPECT_DOUBLE_EQ(s.cases[1].value, 0.10);
  EXPECT_EQ(s.cases[2].kind, geaware::experiments::PerturbationKind::kInFlightCushion);
  EXPECT_EQ(s.cases[3].kind, geaware::experiments::PerturbationKind::kGusts);
  EXPECT_FALSE(s.calibrate);
  EXPECT_EQ(s.start_hover_s, 1.0);
  // Every key parses back to itself, and the file names are distinct.
  std::set<std::string> files;
  for (const auto& k : keys) {
    EXPECT_EQ(geaware::experiments::sweepKeyText(s, geaware::experiments::parseSweepKey(s, k)), k);
    files.insert(geaware::experiments::sweepKeyFileName(k));
  }
  EXPECT_EQ(files.size(), keys.size());
}

TEST(SweepFile, KeyFileNamesAreSafeAndDistinct) {
  using geaware::experiments::sweepKeyFileName;
  EXPECT_EQ(sweepKeyFileName("case=mass+10%/ctl=model:model_indi/scn=a b/seed=3"),
            "case=mass+10_25,ctl=model_3amodel_5findi,scn=a_20b,seed=3.json");
  // '_' is escaped itself, so "a_2f" and "a/" cannot meet; '/' and ',' differ.
  EXPECT_NE(sweepKeyFileName("a_2c"), sweepKeyFileName("a,"));
  EXPECT_NE(sweepKeyFileName("a/"), sweepKeyFileName("a_2c"));
  EXPECT_EQ(sweepKeyFileName(".."), "_2e..json");
  EXPECT_EQ(sweepKeyFileName("x\xce\xbc"), "x_ce_bc.json");
}

TEST(SweepFile, BadKeysAreRefusedNamingThePart) {
  const SweepSpec s = parse(sweep64());
  using geaware::experiments::parseSweepKey;
  EXPECT_THROW((void)parseSweepKey(s, "case=none/ctl=recommended/scn=lem-0.3m-1mps/seed=5"), std::invalid_argument);
  EXPECT_THROW((void)parseSweepKey(s, "case=none/ctl=recommended/scn=lem-0.3m-1mps/seed=01"), std::invalid_argument);
  EXPECT_THROW((void)parseSweepKey(s, "case=none/ctl=recommended/scn=lem-0.3m-1mps"), std::invalid_argument);
  try {
    (void)parseSweepKey(s, "case=heavy/ctl=recommended/scn=lem-0.3m-1mps/seed=1");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("case='heavy' is not one of this sweep's"));
  }
}

TEST(SweepFile, ProblemsNameTheLineAndTheKey) {
  const std::string t = sweep64();
  expectProblem(replaced(t, "calibrate: false", "calibrate: maybe"), lineOf(t, "calibrate:"), "calibrate", "");
  expectProblem(replaced(t, "  - indi:none\n", "  - indi:fast\n"), lineOf(t, "  - indi:none"),
                "controllers[1]", "expected 'recommended' or ACC:TORQUE");
  expectProblem(replaced(t, "  - name: mass+10%\n", "  - name: mass+11%\n"), lineOf(t, "mass+10%"),
                "perturbations[1].name", "expected a case of the robustness suite");
  expectProblem(replaced(t, "{kind: cushion, value: 0.5}", "{kind: cushions, value: 0.5}"), lineOf(t, "kind: cushion"),
                "perturbations[2].kind", "");
  expectProblem(replaced(t, "{kind: gusts, value: 0.3, name: windy}", "{kind: gusts, value: .nan, name: windy}"),
                lineOf(t, "kind: gusts"), "perturbations[3].value", "not a finite number");
  expectProblem(replaced(t, "name: windy}", "name: mass+10%}"), lineOf(t, "name: windy"), "perturbations[3]",
                "listed twice");
  expectProblem(replaced(t, "name: slow-high}", "name: a/b}"), lineOf(t, "slow-high"), "scenarios[1].name",
                "without '/'");
  expectProblem(replaced(t, "speed_mps: 0.5,", "speed_mps: 0.5, colour: red,"), lineOf(t, "speed_mps: 0.5"),
                "scenarios[1].colour", "");
  expectProblem(replaced(t, "seeds: {first: 1, count: 4}", "seeds: {first: 1}"), lineOf(t, "seeds:"),
                "seeds.count", "missing");
  expectProblem(replaced(t, "world: default", "world: marsh"), lineOf(t, "world:"), "world", "cannot use the world");
  expectProblem(replaced(t, "format_version: 1", "format_version: 7"), lineOf(t, "format_version"),
                "format_version", "");
  expectProblem(replaced(t, "calibrate: false\n", "calibrate: false\nrepeats: 3\n"), lineOf(t, "calibrate:") + 1,
                "repeats", "");
  // A lemniscate that cannot be flown is refused at its item.
  expectProblem(replaced(t, "speed_mps: 0.5,", "speed_mps: -0.5,"), lineOf(t, "slow-high"), "scenarios[1].type",
                "not a usable lemniscate");
  // max_sim_s bounds every flight before any work: a flight longer than it is refused at its
  // scenario, naming the durations; the value itself is range-checked.
  expectProblem(replaced(t, "calibrate: false\n", "calibrate: false\nmax_sim_s: 12.5\n"), lineOf(t, "slow-high") + 1,
                "scenarios[1]", "at most max_sim_s = 12.5 s");
  expectProblem(replaced(t, "calibrate: false\n", "calibrate: false\nmax_sim_s: -1\n"), lineOf(t, "calibrate:") + 1,
                "max_sim_s", "expected a duration in (0, 86400] s");
  EXPECT_EQ(parse(replaced(t, "calibrate: false\n", "calibrate: false\nmax_sim_s: 600\n")).max_sim_s, 600.0);
}

TEST(SweepFile, ListSizesAndTheProductAreBoundedBeforeAnyWork) {
  const std::string t = sweep64();
  // 4 × 2 × 2 × 62,501 > 10^6 flights.
  expectProblem(replaced(t, "count: 4", "count: 62501"), lineOf(t, "seeds:"), "seeds", "expected at most 1000000");
  EXPECT_EQ(parse(replaced(t, "count: 4", "count: 62500")).flights(), 1'000'000u);
  std::string many = "controllers:\n";
  for (int i = 0; i < 101; ++i) many += "  - recommended\n";
  expectProblem(replaced(t, "controllers:\n  - recommended\n  - indi:none\n", many), lineOf(t, "controllers:"),
                "controllers", "has 101 items, expected at most 100");
}

TEST(SweepFile, AFaultItemNamesACaseOfTheFaultSuite) {
  // (The shipped files are the suites' grids: suite_sweep_test.cpp.)
  const std::string t = slurp(sourceDir() / "config/sweeps/faults.yaml");
  const SweepSpec s = parse(t);
  EXPECT_EQ(s.cases[9].name, "gyro bias 2° per s");  // a key's name cannot hold '/'
  EXPECT_EQ(s.case_faults[9].name, "gyro bias 2°/s");  // the suite's name
  // A `name` names the suite's case too.
  const SweepSpec named = parse(replaced(t, "fault: motor 50%", "{fault: motor 50%, name: half}"));
  EXPECT_EQ(named.cases[2].name, "half");
  EXPECT_EQ(named.case_faults[2].name, "half");
  EXPECT_EQ(named.case_faults[2].faults.size(), 1u);
  // A fault name that is not the suite's is refused at its line.
  expectProblem(replaced(t, "fault: motor 50%", "fault: motor 40%"), lineOf(t, "motor 50%"), "perturbations[2].fault",
                "expected a case of the fault suite");
}

TEST(SweepFile, ANameThatIsNotUtf8IsRefusedAtItsLine) {
  // A Latin-1 'é' would become a key the records (JSON, UTF-8) cannot hold: the sweep could
  // never finish. Refused before any work, the bytes shown; UTF-8 names are fine.
  const std::string t = sweep64();
  expectProblem(replaced(t, "name: windy}", "name: w\xE9t}"), lineOf(t, "name: windy"), "perturbations[3].name",
                "got 'w\\xE9t', not UTF-8 text");
  expectProblem(replaced(t, "name: slow-high}", "name: \xC0\xAF}"), lineOf(t, "slow-high"), "scenarios[1].name",
                "not UTF-8");  // an overlong '/'
  EXPECT_EQ(parse(replaced(t, "name: windy}", "name: w\xC3\xA9t}")).cases[3].name, "w\xC3\xA9t");
  // A scenario file whose name is not UTF-8 would name its scenario: a 'name' is asked for.
  const geaware::sweep_test::TempDir d("sweep-name");
  const std::string stem = "caf\xE9";
  std::filesystem::copy_file(sourceDir() / "config/scenarios/lemniscate_low.yaml", d.path() / (stem + ".yaml"));
  const std::string item = "{type: file, file: " + (d.path() / stem).string() + ".yaml";
  const std::string with_file = replaced(t, "{type: lemniscate, height_m: 1.0", item + "}\n  - {type: lemniscate, height_m: 1.0");
  expectProblem(with_file, lineOf(t, "slow-high"), "scenarios[1].file", "give a UTF-8 'name'");
  EXPECT_EQ(parse(replaced(with_file, item + "}", item + ", name: cafe}")).scenarios[1].name, "cafe");
}

TEST(SweepFile, AListOfTheWrongTypeOrMissingIsReportedOnce) {
  // A list the reader finds missing or of the wrong type reads as empty; the "at least one
  // item" check must not report the same key a second time.
  const std::string t = sweep64();
  expectProblem(replaced(t, "controllers:\n  - recommended\n  - indi:none\n", "controllers: 5\n"),
                lineOf(t, "controllers:"), "controllers", "expected a list of texts, got a scalar");
  expectProblem(replaced(t, "controllers:\n  - recommended\n  - indi:none\n", ""), 1, "controllers",
                "is missing (required)");
  // An empty list is read without a problem and is then reported, once.
  expectProblem(replaced(t, "controllers:\n  - recommended\n  - indi:none\n", "controllers: []\n"),
                lineOf(t, "controllers:"), "controllers", "expected a list of at least one item");
}

TEST(SweepFile, AConfigurationListedTwiceIsNotToldToTakeAName) {
  const std::string t = sweep64();
  expectProblem(replaced(t, "  - indi:none\n", "  - recommended\n"), lineOf(t, "  - indi:none"), "controllers[1]",
                "'recommended' is listed twice (expected each configuration once)");
}

TEST(SweepFile, TheSimulatedTimeOfAGridIsKnownBeforeAnyWork) {
  // The robustness suite's grid is far below the warning's threshold; the same file with 200
  // times its seeds is above it (`bench` and `sweep` warn before flying it).
  const SweepSpec s = parse(slurp(sourceDir() / "config/sweeps/robustness.yaml"));
  double one_of_each = 0.0;
  for (const auto& scn : s.scenarios) one_of_each += s.start_hover_s + scn.trajectory->duration();
  const double all = geaware::experiments::sweepSimulatedSeconds(s, s.cases.size(), s.controllers.size());
  EXPECT_DOUBLE_EQ(all, one_of_each * 16 * 7 * 5);
  EXPECT_LT(all, geaware::experiments::kSweepLongSimulatedS / 20);
  EXPECT_DOUBLE_EQ(geaware::experiments::sweepSimulatedSeconds(s, 1, 1, {s.scenarios[1].name}),
                   (s.start_hover_s + s.scenarios[1].trajectory->duration()) * 5);
  SweepSpec many = s;
  many.seed_count = 1000;
  EXPECT_GT(geaware::experiments::sweepSimulatedSeconds(many, many.cases.size(), many.controllers.size()),
            geaware::experiments::kSweepLongSimulatedS);
}

TEST(SweepFile, TheFingerprintCoversEveryFileTheSweepNames) {
  // A sweep that names no file is known by the SHA-256 of its bytes. One whose scenario file
  // names a height map is another sweep when either file changes, even by a comment: its
  // results directory then refuses the old records instead of merging them as this sweep's.
  const std::string t = sweep64();
  EXPECT_EQ(parse(t).fingerprint,
            geaware::io::sha256Hex(std::span(reinterpret_cast<const unsigned char*>(t.data()), t.size())));
  const geaware::sweep_test::TempDir d("sweep-fingerprint");
  const auto write = [&d](const std::string& name, const std::string& text) {
    std::ofstream(d.path() / name, std::ios::binary) << text;
  };
  const std::string map = "# origin_x_m: -5\n# origin_y_m: -5\n# cell_m: 0.5\n";
  std::string rows;
  for (int j = 0; j < 21; ++j) rows += "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n";  // 10 m × 10 m, level
  write("ground.csv", map + rows);
  std::string scenario = slurp(sourceDir() / "config/scenarios/lemniscate_low.yaml");
  scenario = replaced(scenario, "  type: flat                     # flat | tilted | step | height_map\n  height_m: 0.0\n",
                      "  type: height_map\n  file: ground.csv\n");
  write("low.yaml", scenario);
  const std::string with_file = replaced(t, "{type: lemniscate, height_m: 1.0",
                                         "{type: file, file: " + (d.path() / "low.yaml").string() +
                                             ", name: low}\n  - {type: lemniscate, height_m: 1.0");
  const std::string first = parse(with_file).fingerprint;
  EXPECT_NE(first, parse(t).fingerprint);
  EXPECT_EQ(parse(with_file).file_sha256,
            geaware::io::sha256Hex(std::span(reinterpret_cast<const unsigned char*>(with_file.data()), with_file.size())));
  EXPECT_EQ(parse(with_file).fingerprint, first);  // the same files: the same sweep
  write("ground.csv", map + "# a comment\n" + rows);
  const std::string map_edited = parse(with_file).fingerprint;
  EXPECT_NE(map_edited, first);
  write("low.yaml", scenario + "# a comment\n");
  EXPECT_NE(parse(with_file).fingerprint, map_edited);
}
