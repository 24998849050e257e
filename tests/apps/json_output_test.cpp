// SPDX-License-Identifier: BSD-3-Clause
// Every command of the geaware binary with `--json -`: standard output must be one JSON
// document and nothing else (human text goes to stderr), parsed here with nlohmann-json, with
// the provenance of the run. A vehicle whose name holds quotes and a backslash must come back
// escaped and intact; non-finite numbers must be null (never `nan`).
//
// The commands are those main.cpp registers: model, fly, bench, rig (calibrate; the platform and
// rotor sweeps write CSV logs, used here as the logs of identify), identify (rotor, platform,
// correlations, flight).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <regex>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#ifndef GEAWARE_BINARY
#error "GEAWARE_BINARY must name the built geaware executable"
#endif

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

struct Run {
  int exit_code = -1;
  std::string out;
};

/// Runs `geaware ARGS` from the source root, stderr discarded, and returns stdout.
Run geaware(const std::string& args) {
  const std::string cmd = std::string("cd '") + GEAWARE_SOURCE_DIR + "' && '" GEAWARE_BINARY "' " +
                          args + " 2>/dev/null";
  Run r;
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// Parses stdout as exactly one JSON document (trailing whitespace only) with provenance.
Json parse(const Run& r, const std::string& what) {
  EXPECT_EQ(r.exit_code, 0) << what;
  Json doc;
  try {
    doc = Json::parse(r.out);  // throws on anything but one document
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": stdout is not one JSON document (" << e.what() << "):\n" << r.out;
    return doc;
  }
  EXPECT_TRUE(doc.is_object()) << what;
  EXPECT_TRUE(doc.contains("provenance")) << what;
  if (doc.contains("provenance")) {
    const Json& p = doc["provenance"];
    EXPECT_TRUE(p["geaware_version"].is_string()) << what;
    EXPECT_TRUE(p["commit"].is_string()) << what;
    EXPECT_NE(p["command_line"].get<std::string>().find("--json -"), std::string::npos) << what;
  }
  // A non-finite number must be null, never a bare token (which no JSON parser accepts).
  EXPECT_FALSE(std::regex_search(r.out, std::regex(R"([:\[,]\s*-?(nan|inf|NaN|Infinity))")))
      << what << ": a non-finite number in the JSON text";
  return doc;
}

/// A copy of the committed vehicle whose name holds a double quote and a backslash.
fs::path scratch();

fs::path oddlyNamedVehicle() {
  const fs::path dir = scratch();
  std::ifstream in(fs::path(GEAWARE_SOURCE_DIR) / "config/vehicles/paper_quad.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string key = "\nname: paper_quad";
  const auto at = yaml.find(key);
  EXPECT_NE(at, std::string::npos);
  yaml.replace(at, key.size(), "\nname: 'say \"hi\" \\ back'");
  const fs::path file = dir / "odd_name.yaml";
  std::ofstream(file) << yaml;
  return file;
}

TEST(JsonOutput, ModelPrintsOnlyJsonWithTheNameEscaped) {
  const fs::path vehicle = oddlyNamedVehicle();
  const Json doc = parse(geaware("model --heights 0.05:0.3:0.05 --vehicle '" + vehicle.string() +
                                 "' --json -"),
                         "model");
  EXPECT_EQ(doc["vehicle"], "say \"hi\" \\ back");
  ASSERT_EQ(doc["rows"].size(), 6u);
  EXPECT_EQ(doc["rows"][1]["h_m"], 0.1);
  EXPECT_GT(doc["rows"][1]["F_G"].get<double>(), 0.0);
  EXPECT_EQ(doc["provenance"]["inputs"][0]["sha256"].get<std::string>().size(), 64u);
}

TEST(JsonOutput, FlyPrintsOnlyJson) {
  const Json doc = parse(
      geaware("fly --trajectory hover-descent --from-height 0.5 --height 0.2 "
              "--controller model:model_indi --seed 2 --json -"),
      "fly");
  EXPECT_EQ(doc["controller"], "model:model_indi");
  EXPECT_EQ(doc["seed"], 2);
  EXPECT_EQ(doc["crashed"], false);
  EXPECT_TRUE(doc["crash"].is_null());
  EXPECT_GT(doc["rmse_all_cm"].get<double>(), 0.0);
  EXPECT_EQ(doc["provenance"]["seeds"], Json::array({2}));
}

TEST(JsonOutput, FlyAScenarioPrintsOnlyJson) {
  const Json doc = parse(geaware("fly --scenario config/scenarios/lemniscate_low.yaml --json -"),
                         "fly --scenario");
  EXPECT_EQ(doc["provenance"]["inputs"][0]["path"], "config/scenarios/lemniscate_low.yaml");
}

TEST(JsonOutput, BenchPrintsOnlyJsonWithNullForMissingNumbers) {
  // The shortest campaign: one seed of experiment 1 (no Neural-Lander training).
  const Json doc = parse(geaware("bench --only 1 --seeds 1 --no-cache --json -"), "bench");
  ASSERT_EQ(doc["experiments"].size(), 1u);
  EXPECT_EQ(doc["experiments"][0]["exp"], 1);
  // Not crashed: the crash time is not a number, written as null.
  if (doc["experiments"][0]["per_seed"][0]["crashed"] == false) {
    EXPECT_TRUE(doc["experiments"][0]["per_seed"][0]["crash_t_s"].is_null());
  }
  EXPECT_FALSE(doc["calibration"]["parameters"].empty());
}

TEST(JsonOutput, RobustnessSuitePrintsOnlyJsonInTheSuiteSchema) {
  // Two cells, two controllers, one seed: the suite schema parsed, not matched as text.
  const Json doc = parse(geaware("bench --suite robustness --cases none,mass+10% --controllers "
                                 "indi:none,recommended --seeds 1 --no-cache --quiet --json -"),
                         "bench --suite robustness");
  EXPECT_EQ(doc["suite"], "robustness");
  ASSERT_TRUE(doc["cells"].is_array());
  ASSERT_FALSE(doc["cells"].empty());
  for (const auto& cell : doc["cells"]) {
    EXPECT_TRUE(cell["case"] == "none" || cell["case"] == "mass+10%") << cell.dump();
    EXPECT_TRUE(cell["controller"] == "indi:none" || cell["controller"] == "recommended");
    EXPECT_TRUE(cell["strikes"].is_number_integer());
    // All-RMSE is a number, or null when every flight of the cell struck.
    EXPECT_TRUE(cell["rmse_all_cm"].is_number() || cell["strikes"] == cell["flights"]);
  }
}

/// A scratch directory for the logs the rigs and `fly` write.
fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / "geaware_json_output_test";
  fs::create_directories(dir);
  return dir;
}

TEST(JsonOutput, RigCalibratePrintsOnlyJson) {
  const Json doc = parse(geaware("rig calibrate --json -"), "rig calibrate");
  EXPECT_TRUE(doc["all_pass"].is_boolean());
  EXPECT_TRUE(doc["papers_rotors"].get<bool>());
  EXPECT_FALSE(doc["checks"].empty());
  // Another vehicle's rotors: the paper's targets are information, neither passed nor failed.
  const Json other = parse(geaware("rig calibrate --truth config/truths/quad5_as_built.yaml --json -"), "rig calibrate");
  EXPECT_FALSE(other["papers_rotors"].get<bool>());
  EXPECT_TRUE(other["all_pass"].is_null());
}

TEST(JsonOutput, IdentifyFromRigLogsPrintsOnlyJson) {
  const fs::path rotor = scratch() / "rotor.csv";
  const fs::path level = scratch() / "level.csv";
  ASSERT_EQ(geaware("rig rotor --out '" + rotor.string() + "'").exit_code, 0);
  ASSERT_EQ(geaware("rig platform --heights 0.07:1.0:0.05 --rpm 9000:15000:3000 --samples 5 --out '" +
                    level.string() + "'")
                .exit_code,
            0);
  const std::string vehicle = " --vehicle '" + oddlyNamedVehicle().string() + "'";
  for (const auto& [kind, log] : {std::pair{"rotor", rotor}, std::pair{"platform", level},
                                  std::pair{"correlations", level}}) {
    const Json doc = parse(geaware(std::string("identify ") + kind + " '" + log.string() + "'" +
                                   vehicle + " --json -"),
                           std::string("identify ") + kind);
    EXPECT_EQ(doc["command"], kind);
    EXPECT_FALSE(doc[std::string(kind) == "correlations" ? "correlations" : "parameters"].empty())
        << kind;
  }
}

TEST(JsonOutput, IdentifyFlightOnAFlyLogPrintsOnlyJson) {
  const fs::path log = scratch() / "fly.csv";
  ASSERT_EQ(geaware("fly --trajectory lemniscate --height 0.3 --speed 2 --controller model:model_indi "
                    "--quiet --out '" + log.string() + "'")
                .exit_code,
            0);
  const Json doc = parse(geaware("identify flight '" + log.string() + "' --mass-kg 1.696 --json -"), "identify flight");
  EXPECT_FALSE(doc["parameters"].empty());
  EXPECT_EQ(doc["base_vehicle"], "built-in paper quadrotor");
  // Without --vehicle or --mass-kg a flight fit is refused (issue 11: a 37 g vehicle's drag was
  // fitted with the built-in 1.7 kg quadrotor's mass, 46x off).
  EXPECT_EQ(geaware("identify flight '" + log.string() + "' --json -").exit_code, 2);
}

}  // namespace

namespace {

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

// `fly --learned-vehicle`: the vehicle file with F_G as the table the controller learned (issue
// 13 item 3). It loads, `geaware model` reads back exactly the learned knot values, the same
// flight writes the same bytes, and without a learning controller the option is refused.
TEST(JsonOutput, FlyWritesTheLearnedGroundEffectAsAVehicleFile) {
  const fs::path a = scratch() / "learned_a.yaml";
  const fs::path b = scratch() / "learned_b.yaml";
  const std::string flight =
      "fly --trajectory hover-descent --from-height 1.2 --height 0.1 --speed 0.1 "
      "--controller recommended+learn0 --seed 3 --quiet --json - --learned-vehicle ";
  const Json doc = parse(geaware(flight + "'" + a.string() + "'"), "fly --learned-vehicle");
  EXPECT_EQ(doc["controller"], "recommended+learn0");
  ASSERT_EQ(geaware(flight + "'" + b.string() + "'").exit_code, 0);
  const std::string text = readText(a);
  EXPECT_EQ(text, readText(b)) << "the same flight learns the same curve";
  const std::smatch knots = [&] {
    std::smatch m;
    std::regex_search(text, m, std::regex(R"(heights_m: \[([^\]]*)\]\s*\n\s*F_G: \[([^\]]*)\])"));
    return m;
  }();
  ASSERT_EQ(knots.size(), 3u) << text;
  EXPECT_EQ(knots[1].str(), "0.08, 0.1, 0.12, 0.14, 0.17, 0.2, 0.24, 0.28, 0.33, 0.4, 0.5");
  std::vector<double> f_g;
  std::stringstream values(knots[2].str());
  for (std::string v; std::getline(values, v, ',');) f_g.push_back(std::stod(v));
  ASSERT_EQ(f_g.size(), 11u);
  const Json model = parse(geaware("model --vehicle '" + a.string() + "' --heights 0.1:0.2:0.1 --json -"), "model");
  EXPECT_DOUBLE_EQ(model["rows"][0]["F_G"].get<double>(), f_g[1]);
  EXPECT_DOUBLE_EQ(model["rows"][1]["F_G"].get<double>(), f_g[5]);
  EXPECT_GT(f_g[1], 0.05) << "something was learned near the ground";
  // A level descent does not excite the leveling scale: the file's leveling torque is kept.
  const Json builtin = parse(geaware("model --heights 0.1:0.2:0.1 --json -"), "model");
  EXPECT_EQ(model["rows"][0]["M_G_m"].get<double>(), builtin["rows"][0]["M_G_m"].get<double>());
  EXPECT_EQ(model["rows"][1]["M_G_m"].get<double>(), builtin["rows"][1]["M_G_m"].get<double>());
  const fs::path c = scratch() / "learned_c.yaml";
  // A controller that does not learn cannot write what it learned: a usage error (status 2).
  EXPECT_EQ(geaware("fly --trajectory hover-descent --height 0.2 --speed 0.5 --controller recommended "
                    "--quiet --learned-vehicle '" + c.string() + "'")
                .exit_code,
            2);
  EXPECT_FALSE(fs::exists(c));
}

// A flight that learns F_G at no knot (a lemniscate at 1 m, above the learner's top knot) writes
// no vehicle file: it would hold only the learner's start (with +learn0, no ground effect at all)
// as if learned. The flight's other outputs are written; the exit status says the file is not.
TEST(JsonOutput, FlyWritesNoVehicleFileWhenNothingWasLearned) {
  const fs::path a = scratch() / "learned_nothing.yaml";
  const auto r = geaware("fly --trajectory lemniscate --height 1.0 --speed 1 --controller recommended+learn0 --seed 1 "
                        "--quiet --json - --learned-vehicle '" + a.string() + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_FALSE(fs::exists(a));
  const Json doc = Json::parse(r.out);
  ASSERT_EQ(doc["learned"]["f_g"]["learned"].size(), 11u);
  for (const auto& knot : doc["learned"]["f_g"]["learned"]) EXPECT_FALSE(knot.get<bool>());
}

// Two laps sweeping 0.1–0.3 m excite the leveling scale: the file's leveling torque comes out
// scaled by it, and `geaware model` reads M_G back scaled by the same factor at every height.
TEST(JsonOutput, FlyWritesTheLearnedLevelingScaleIntoTheVehicleFile) {
  const fs::path a = scratch() / "learned_leveling.yaml";
  const Json flight = parse(geaware("fly --trajectory lemniscate --height 0.1 --height-swing 0.2 --speed 1 "
                                    "--extent-x 1.5 --extent-y 0.8 --laps 2 --controller recommended+learn0 --seed 1 "
                                    "--quiet --json - --learned-vehicle '" + a.string() + "'"),
                            "fly --learned-vehicle");
  // The JSON says what was learned; `geaware model` reads the written file back: M_G scaled by
  // the learned scale at every height, and F_G the learned table at its knots.
  const Json& learned_json = flight["learned"];
  EXPECT_TRUE(learned_json["leveling_learned"].get<bool>());
  EXPECT_GT(learned_json["leveling_samples"].get<int>(), 1000);
  const double scale = learned_json["leveling_scale"].get<double>();
  EXPECT_GT(scale, 0.2);
  EXPECT_LT(scale, 1.0) << "the as-built world levels less than the platform said";
  ASSERT_EQ(learned_json["f_g"]["values"].size(), 11u);
  ASSERT_EQ(learned_json["f_g"]["heights_m"][1].get<double>(), 0.1);
  ASSERT_EQ(learned_json["f_g"]["heights_m"][5].get<double>(), 0.2);
  const Json learned = parse(geaware("model --vehicle '" + a.string() + "' --heights 0.1:0.3:0.1 --json -"), "model");
  const Json builtin = parse(geaware("model --heights 0.1:0.3:0.1 --json -"), "model");
  ASSERT_EQ(learned["rows"].size(), 3u);
  EXPECT_EQ(learned["rows"][0]["F_G"].get<double>(), learned_json["f_g"]["values"][1].get<double>());
  EXPECT_EQ(learned["rows"][1]["F_G"].get<double>(), learned_json["f_g"]["values"][5].get<double>());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(learned["rows"][i]["M_G_m"].get<double>() / builtin["rows"][i]["M_G_m"].get<double>(), scale,
                1e-12 * scale)
        << i;
  }
}
