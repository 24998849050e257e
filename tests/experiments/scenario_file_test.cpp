// SPDX-License-Identifier: BSD-3-Clause
// Scenario files: the committed examples load into the scenario they describe; every kind of
// bad file is rejected with the file, the line and the key.
#include "geaware/experiments/scenario_file.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "geaware/sim/terrains.hpp"
#include "geaware/sim/world.hpp"
#include "geaware/traj/lemniscate.hpp"
#include "geaware/traj/touchdown.hpp"

namespace {

using geaware::experiments::FlightScenario;
using geaware::experiments::parseScenarioYaml;

std::filesystem::path sourceDir() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return dir ? std::filesystem::path(dir) : std::filesystem::current_path();
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

const std::string& lowText() {
  static const std::string t = slurp(sourceDir() / "config/scenarios/lemniscate_low.yaml");
  return t;
}

/// The text with exactly one occurrence of `from` replaced; throws if it does not occur once,
/// so a test cannot pass because its edit silently missed.
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

/// The problems of a rejected text (fails the test when the text is accepted).
std::vector<geaware::io::ConfigProblem> problemsOf(const std::string& text) {
  try {
    (void)parseScenarioYaml(text, "s.yaml", sourceDir() / "config/scenarios");
  } catch (const geaware::io::ConfigError& e) {
    return e.problems();
  }
  ADD_FAILURE() << "the scenario was accepted";
  return {};
}

TEST(ScenarioFile, ControllerRecommendedSelectsGeawaresConfiguration) {
  const std::string text =
      replaced(lowText(), "controller:\n  acceleration: model            # none | indi | neural | model\n"
                          "  torque: model_indi             # none | model | indi | model_indi\n",
               "controller: recommended\n");
  const FlightScenario s = parseScenarioYaml(text, "s.yaml", sourceDir() / "config/scenarios");
  EXPECT_EQ(geaware::control::configurationName(s.controller), "recommended");
  EXPECT_TRUE(s.controller.clearance_guard);
  // Any other word is not a controller section.
  const auto problems = problemsOf(replaced(text, "controller: recommended", "controller: best"));
  ASSERT_FALSE(problems.empty());
  EXPECT_EQ(problems[0].key, "controller");
  EXPECT_NE(problems[0].message.find("expected 'recommended' or ACC:TORQUE"), std::string::npos)
      << problems[0].message;
  // Any configuration --controller takes, switches included.
  const FlightScenario r =
      parseScenarioYaml(replaced(text, "controller: recommended", "controller: model:model_indi+rotors"),
                        "s.yaml", sourceDir() / "config/scenarios");
  EXPECT_EQ(geaware::control::configurationName(r.controller), "model:model_indi+rotors");
  EXPECT_TRUE(r.controller.per_rotor_ground_effect);
}

TEST(ScenarioFile, CommittedExamplesLoad) {
  const FlightScenario s = geaware::experiments::loadScenarioFile(sourceDir() / "config/scenarios/lemniscate_low.yaml");
  EXPECT_EQ(s.seed, 1u);
  EXPECT_EQ(s.controller.acceleration, geaware::control::AccelerationCompensation::kModel);
  EXPECT_EQ(s.controller.torque, geaware::control::TorqueCompensation::kModelIndi);
  const auto* lem = dynamic_cast<const geaware::traj::Lemniscate*>(s.trajectory.get());
  ASSERT_NE(lem, nullptr);
  EXPECT_DOUBLE_EQ(lem->params().height_m, 0.12);
  EXPECT_DOUBLE_EQ(lem->params().peak_speed_mps, 1.0);
  EXPECT_NE(dynamic_cast<const geaware::sim::FlatGround*>(s.terrain.get()), nullptr);
  EXPECT_TRUE(s.disturbances.turbulence);
  EXPECT_FALSE(s.disturbances.wind);
  EXPECT_FALSE(s.mismatch.has_value());
  EXPECT_EQ(s.vehicle.name, "paper_quad");

  const FlightScenario edge = geaware::experiments::loadScenarioFile(sourceDir() / "config/scenarios/table_edge.yaml");
  const auto* step = dynamic_cast<const geaware::sim::StepTerrain*>(edge.terrain.get());
  ASSERT_NE(step, nullptr);
  EXPECT_DOUBLE_EQ(step->heightAt(0.5, 0.0), 0.10);
  EXPECT_DOUBLE_EQ(step->heightAt(-0.5, 0.0), 0.0);
  ASSERT_TRUE(edge.mismatch.has_value());
  EXPECT_DOUBLE_EQ(edge.mismatch->mass_rel, 0.05);
  EXPECT_NEAR(edge.trajectory->sample(0.0).p_W.x(), -1.0, 1e-12);
}

TEST(ScenarioFile, LandingAndTakeOffComeWithGroundContact) {
  const FlightScenario land = geaware::experiments::loadScenarioFile(sourceDir() / "config/scenarios/landing.yaml");
  const auto* l = dynamic_cast<const geaware::traj::Landing*>(land.trajectory.get());
  ASSERT_NE(l, nullptr);
  EXPECT_DOUBLE_EQ(l->params().touchdown_height_m, land.vehicle.min_rotor_plane_height_m);
  EXPECT_DOUBLE_EQ(l->params().touchdown_speed_mps, 0.1);
  EXPECT_TRUE(land.plant.ground_contact);
  EXPECT_TRUE(land.land_detector.has_value());
  EXPECT_FALSE(land.start_on_ground);
  EXPECT_FALSE(land.controller.clearance_guard);  // "recommended" has it; a landing does not

  const FlightScenario up = geaware::experiments::loadScenarioFile(sourceDir() / "config/scenarios/takeoff.yaml");
  ASSERT_NE(dynamic_cast<const geaware::traj::TakeOff*>(up.trajectory.get()), nullptr);
  EXPECT_TRUE(up.plant.ground_contact);
  EXPECT_TRUE(up.start_on_ground);
  EXPECT_FALSE(up.land_detector.has_value());

  // The lemniscate keeps the strike rule and the guard.
  const FlightScenario low = geaware::experiments::loadScenarioFile(sourceDir() / "config/scenarios/lemniscate_low_recommended.yaml");
  EXPECT_FALSE(low.plant.ground_contact);
  EXPECT_TRUE(low.controller.clearance_guard);

  // A flare that does not fit is refused at its key, with the reason.
  const std::string text = slurp(sourceDir() / "config/scenarios/landing.yaml");
  const auto problems = problemsOf(replaced(text, "from_height_m: 1.0", "from_height_m: 0.4"));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].key, "trajectory.type");
  EXPECT_NE(problems[0].message.find("from_height_m = 0.4 (expected >= 0.622"), std::string::npos);
}

TEST(ScenarioFile, FormatVersionAbsentIsOneAndUnknownIsRefused) {
  const std::string text = lowText();
  const std::string line = "format_version: 1";
  ASSERT_NE(text.find(line), std::string::npos);  // the committed file says its version
  const std::string unversioned = replaced(text, line, "");
  const auto a = parseScenarioYaml(unversioned, "s.yaml", sourceDir() / "config/scenarios");
  const auto b = parseScenarioYaml(text, "s.yaml", sourceDir() / "config/scenarios");
  EXPECT_EQ(a.seed, b.seed);
  const std::string v3 = replaced(text, line, "format_version: 3");
  const auto p = problemsOf(v3);
  ASSERT_EQ(p.size(), 1u);  // nothing else is read
  EXPECT_EQ(p[0].key, "format_version");
  EXPECT_EQ(p[0].line, lineOf(v3, "format_version"));
  EXPECT_NE(p[0].message.find("supported: 1"), std::string::npos);
}

TEST(ScenarioFile, UnknownAndMissingKeysNameTheKeyAndLine) {
  {
    const std::string text = replaced(lowText(), "  laps: 1\n", "  laps: 1\n  lap_count: 2\n");
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "trajectory.lap_count");
    EXPECT_EQ(p[0].line, lineOf(text, "lap_count"));
    EXPECT_NE(p[0].message.find("unknown key"), std::string::npos);
  }
  {
    const std::string text = replaced(lowText(), "  peak_speed_mps: 1.0\n", "");
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "trajectory.peak_speed_mps");
    EXPECT_EQ(p[0].line, lineOf(text, "trajectory:"));
    EXPECT_NE(p[0].message.find("missing"), std::string::npos);
  }
}

TEST(ScenarioFile, WrongChoicesAndTypesAreNamed) {
  {
    const auto p = problemsOf(replaced(lowText(), "acceleration: model ", "acceleration: pid "));
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "controller.acceleration");
    EXPECT_NE(p[0].message.find("none, indi, neural, model"), std::string::npos) << p[0].message;
  }
  {
    const auto p = problemsOf(replaced(lowText(), "turbulence: true", "turbulence: maybe"));
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "disturbances.turbulence");
    EXPECT_NE(p[0].message.find("true or false"), std::string::npos);
  }
  {
    const auto p = problemsOf(replaced(lowText(), "wind_mps: [0.0, 0.0, 0.0]", "wind_mps: [0.0, 0.0]"));
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "disturbances.wind_mps");
    EXPECT_NE(p[0].message.find("3 numbers"), std::string::npos);
  }
  {
    const auto p = problemsOf(replaced(lowText(), "laps: 1", "laps: 1.5"));
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "trajectory.laps");
  }
}

// The residual network of acceleration "neural" is not part of the file (`fly --neural-weights`
// gives it): the file loads, and only flying it without a network is refused, naming it.
TEST(ScenarioFile, ANeuralScenarioLoadsAndNeedsItsNetworkOnlyToFly) {
  const auto s = parseScenarioYaml(replaced(lowText(), "acceleration: model ", "acceleration: neural "),
                                   "s.yaml", sourceDir() / "config/scenarios");
  EXPECT_EQ(s.controller.acceleration, geaware::control::AccelerationCompensation::kNeural);
  EXPECT_FALSE(s.residual);
  try {
    (void)geaware::experiments::runFlight(s);
    ADD_FAILURE() << "flew without a residual network";
  } catch (const geaware::experiments::InvalidScenario& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].field, "residual");
  }
}

TEST(ScenarioFile, AnImpossibleTrajectoryIsRefusedWithTheReason) {
  // Ramps longer than the flight: the trajectory's own validation explains it.
  const auto p = problemsOf(replaced(lowText(), "ramp_time_s: 2.0", "ramp_time_s: 50.0"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].key, "trajectory.type");
  EXPECT_NE(p[0].message.find("ramp_time_s"), std::string::npos) << p[0].message;
}

TEST(ScenarioFile, MissingFilesAreNamed) {
  {
    const auto p = problemsOf(replaced(lowText(), "vehicle: builtin", "vehicle: no_such_quad.yaml"));
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "vehicle");
    EXPECT_NE(p[0].message.find("no_such_quad.yaml"), std::string::npos) << p[0].message;
  }
  {
    const auto p = problemsOf(replaced(lowText(), "  type: flat                     # flat | tilted | step | height_map\n  height_m: 0.0\n",
                                       "  type: height_map\n  file: no_such_map.csv\n"));
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "terrain.file");
    EXPECT_NE(p[0].message.find("no_such_map.csv"), std::string::npos) << p[0].message;
  }
  EXPECT_THROW((void)geaware::experiments::loadScenarioFile("/nonexistent/scenario.yaml"), std::runtime_error);
}

// The world of a scenario: `truth:` names a built-in world or a truth file (relative to the
// scenario), a caller's world (`fly --truth`) replaces it, and the old `truth_mismatch:` is an
// error that names its new place.
TEST(ScenarioFile, TruthNamesTheWorld) {
  const FlightScenario ideal = parseScenarioYaml(lowText(), "s.yaml", sourceDir() / "config/scenarios");
  ASSERT_TRUE(ideal.truth.has_value());
  EXPECT_EQ(ideal.truth->mass_kg, 1.696);
  EXPECT_FALSE(ideal.mismatch.has_value());

  // The table-edge scenario's world varies per flight: its truth file says by how much.
  const FlightScenario edge = geaware::experiments::loadScenarioFile(sourceDir() / "config/scenarios/table_edge.yaml");
  ASSERT_TRUE(edge.mismatch.has_value());
  EXPECT_DOUBLE_EQ(edge.mismatch->thrust_spread_rel, 0.02);

  // A world given by the caller replaces the file's.
  geaware::sim::World other = geaware::sim::idealWorld(ideal.vehicle, "test");
  other.truth.cog_offset_B.x() = 0.004;
  other.sensors.mocap.latency_s = 0.02;
  const FlightScenario over = parseScenarioYaml(lowText(), "s.yaml", sourceDir() / "config/scenarios", &other);
  ASSERT_TRUE(over.truth.has_value());
  EXPECT_EQ(over.truth->cog_offset_B.x(), 0.004);
  EXPECT_EQ(over.sensors.mocap.latency_s, 0.02);

  // No `truth:`: the default world of the built-in vehicle.
  const std::string none = replaced(lowText(), "truth: ideal ", "# no truth ");
  const FlightScenario def = parseScenarioYaml(none, "s.yaml", sourceDir() / "config/scenarios");
  ASSERT_TRUE(def.truth.has_value());
  EXPECT_EQ(def.truth->mass_kg, ideal.truth->mass_kg);
}

TEST(ScenarioFile, ABadTruthIsNamed) {
  const std::string text = replaced(lowText(), "truth: ideal ", "truth: no_such_world.yaml ");
  const auto p = problemsOf(text);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].key, "truth");
  EXPECT_EQ(p[0].line, lineOf(text, "truth:"));
  EXPECT_NE(p[0].message.find("no_such_world.yaml"), std::string::npos) << p[0].message;
}

TEST(ScenarioFile, TruthMismatchMovedIntoTheTruthFile) {
  const std::string text = lowText() + "truth_mismatch:\n  mass_rel: 0.05\n";
  const auto p = problemsOf(text);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].key, "truth_mismatch");
  EXPECT_EQ(p[0].line, lineOf(text, "truth_mismatch:"));
  EXPECT_NE(p[0].message.find("truth.per_flight_variation"), std::string::npos) << p[0].message;
}

TEST(ScenarioFile, MalformedYamlGivesTheLine) {
  try {
    (void)parseScenarioYaml("seed: 1\ntrajectory: [a, b\n", "bad.yaml", ".");
    FAIL() << "accepted";
  } catch (const geaware::io::ConfigError& e) {
    ASSERT_FALSE(e.problems().empty());
    EXPECT_GE(e.problems()[0].line, 2);
    EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos);
  }
}

}  // namespace

namespace {

const std::string& ceilingText() {
  static const std::string t = slurp(sourceDir() / "config/scenarios/ceiling_pass.yaml");
  return t;
}

TEST(ScenarioFile, ObstaclesAndBeamRangersLoad) {
  const FlightScenario s = geaware::experiments::loadScenarioFile(sourceDir() / "config/scenarios/ceiling_pass.yaml");
  ASSERT_TRUE(s.obstacles);
  ASSERT_EQ(s.obstacles->boxes().size(), 1u);
  const geaware::sim::Box& b = s.obstacles->boxes()[0];
  EXPECT_EQ(b.name, "ceiling");
  EXPECT_NEAR(b.centre_W.z() - b.half_extent_m.z(), 1.15, 1e-12);  // the underside
  EXPECT_TRUE(s.beam_rangers.empty());  // the default set flies
  EXPECT_TRUE(s.controller.proximity_compensation);
  const FlightScenario w = geaware::experiments::loadScenarioFile(sourceDir() / "config/scenarios/wall_pass.yaml");
  ASSERT_TRUE(w.obstacles);
  EXPECT_NEAR(w.obstacles->clearance(Eigen::Vector3d(0.5, 0.0, 1.0)), 0.4127, 1e-12);

  // A yawed box and one configured beam.
  const std::string text = replaced(
      ceilingText(), "  - {type: box, name: ceiling, min_m: [0.0, -1.0, 1.15], max_m: [1.5, 1.0, 1.35]}\n",
      "  - {type: box, name: ceiling, min_m: [0.0, -1.0, 1.15], max_m: [1.5, 1.0, 1.35], yaw_deg: 30}\n"
      "beam_rangers:\n  - {direction_B: [0, 0, 2], mount_B_m: [0, 0, 0.02], rate_Hz: 25}\n");
  const FlightScenario y = parseScenarioYaml(text, "s.yaml", sourceDir() / "config/scenarios");
  ASSERT_EQ(y.beam_rangers.size(), 1u);
  EXPECT_TRUE(y.beam_rangers[0].direction_B.isApprox(Eigen::Vector3d::UnitZ()));  // normalised
  EXPECT_DOUBLE_EQ(y.beam_rangers[0].rate_Hz, 25.0);
  EXPECT_NEAR(y.obstacles->boxes()[0].R_WO(1, 0), 0.5, 1e-12);  // sin 30°
  // A slab tilted 5° about y.
  const std::string tilted = replaced(ceilingText(), "max_m: [1.5, 1.0, 1.35]}", "max_m: [1.5, 1.0, 1.35], pitch_deg: 5}");
  const FlightScenario t = parseScenarioYaml(tilted, "s.yaml", sourceDir() / "config/scenarios");
  EXPECT_NEAR(t.obstacles->boxes()[0].R_WO(0, 2), std::sin(5.0 * std::acos(-1.0) / 180.0), 1e-12);
}

TEST(ScenarioFile, BadObstaclesAreNamedWithTheirLine) {
  {
    const std::string text = replaced(ceilingText(), "max_m: [1.5, 1.0, 1.35]", "max_m: [1.5, 1.0, 1.15]");
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "obstacles[0].max_m");
    EXPECT_EQ(p[0].line, lineOf(text, "type: box"));
    EXPECT_NE(p[0].message.find("greater than min_m"), std::string::npos) << p[0].message;
  }
  {
    const std::string text = replaced(ceilingText(), "type: box", "type: sphere");
    const auto p = problemsOf(text);
    ASSERT_FALSE(p.empty());
    EXPECT_EQ(p[0].key, "obstacles[0].type");
  }
  {
    // The reference straight through a pillar: refused before flying, naming it.
    const std::string text = replaced(ceilingText(), "name: ceiling, min_m: [0.0, -1.0, 1.15]", "name: pillar, min_m: [0.0, -1.0, 0.5]");
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "trajectory");
    EXPECT_NE(p[0].message.find("pillar"), std::string::npos) << p[0].message;
  }
  {
    const std::string text = ceilingText() + "beam_rangers:\n  - {direction_B: [0, 0, 1], mount_B_m: [0, 0, 0], rate_Hz: -5}\n";
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "beam_rangers[0].rate_Hz");
  }
}

}  // namespace
