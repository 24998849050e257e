// SPDX-License-Identifier: BSD-3-Clause
// `geaware train-residual` as a user runs it (issue 11 item 6): flight logs from the truth
// simulator (`geaware fly --out`, read back as `identify flight` reads them) → a weight file.
// The network must explain part of the force the nominal model leaves on a flight it was not
// trained on, the same seed must give the same file, the file must load through the weights
// reader and fly the neural controller (`fly --neural-weights`, `bench --neural-weights`).

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "geaware/neural/weights_file.hpp"
#include "synthetic.hpp"

namespace {

struct CommandRun {
  int status = -1;
  std::string out;
};

/// Runs the geaware binary with `args` (a shell command tail), stderr discarded.
CommandRun geaware(const std::string& args) {
  const std::string cmd = std::string("'") + GEAWARE_EXE + "' " + args + " 2>/dev/null";
  CommandRun r;
  std::FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  r.status = pclose(p);
  return r;
}

/// The words joined by spaces (one append each: GCC 12 reports a false -Wstringop-overflow on
/// long chains of operator+).
std::string words(std::initializer_list<std::string> parts) {
  std::string s;
  for (const auto& p : parts) {
    if (!s.empty()) s.push_back(' ');
    s.append(p);
  }
  return s;
}

std::string slurp(const std::filesystem::path& f) {
  std::ifstream is(f, std::ios::binary);
  std::ostringstream os;
  os << is.rdbuf();
  return os.str();
}

TEST(TrainResidual, WeightsFromLogsReduceTheResidualOfAFlightTheyWereNotTrainedOn) {
  const auto dir = ident_test::tempDir("train_residual");
  const auto q = [&](const std::string& name) {
    std::string quoted(1, '\'');
    quoted.append((dir / name).string());
    quoted.push_back('\'');
    return quoted;
  };
  // Two training flights near the ground and one held out between them, flown without a
  // ground-effect model (the residual is then the ground effect the controller did not know).
  const std::string flight = "fly --truth ideal --trajectory lemniscate --speed 1 --laps 1 --quiet";
  const std::string fly = flight + " --controller indi:none";
  ASSERT_EQ(geaware(words({fly, "--height 0.12 --seed 1 --out", q("low.csv")})).status, 0);
  ASSERT_EQ(geaware(words({fly, "--height 0.4 --seed 2 --out", q("high.csv")})).status, 0);
  ASSERT_EQ(geaware(words({fly, "--height 0.2 --seed 3 --out", q("held.csv")})).status, 0);

  const std::string train = words({"train-residual", q("low.csv"), q("high.csv"),
                                   "--vehicle config/vehicles/paper_quad.yaml --epochs 40 --seed 7 --held-out",
                                   q("held.csv"), "--json - --out"});
  const CommandRun a = geaware(words({train, q("a.yaml")}));
  ASSERT_EQ(a.status, 0) << a.out;
  const auto doc = nlohmann::json::parse(a.out);
  EXPECT_GT(doc["rows"]["training"].get<int>(), 1000);
  EXPECT_GT(doc["rows"]["validation"].get<int>(), 200);
  const double with = doc["held_out"]["mse_with_network_N2"].get<double>();
  const double without = doc["held_out"]["mse_without_network_N2"].get<double>();
  EXPECT_LT(with, 0.5 * without) << "held-out MSE " << with << " N² with the network, " << without << " without";
  EXPECT_LT(doc["mse_N2"]["validation"].get<double>(), 0.5 * doc["mse_N2"]["labels"].get<double>());
  EXPECT_NE(doc["provenance"]["command_line"].get<std::string>().find("train-residual"), std::string::npos);

  // Deterministic: the same seed gives the same weights (the provenance names its own --out).
  ASSERT_EQ(geaware(words({train, q("b.yaml")})).status, 0);
  const auto wa = geaware::neural::loadWeights(dir / "a.yaml");  // round trip through the reader
  const auto wb = geaware::neural::loadWeights(dir / "b.yaml");
  EXPECT_EQ(geaware::neural::weightsToYaml({wa.weights, {}}), geaware::neural::weightsToYaml({wb.weights, {}}));
  EXPECT_EQ(wa.provenance.at("seed"), "7");
  EXPECT_EQ(wa.provenance.at("produced_by"), "geaware train-residual");
  EXPECT_NE(slurp(dir / "a.yaml").find("held.csv"), std::string::npos);  // the command line

  // The file flies the neural controller.
  EXPECT_EQ(geaware(words({flight, "--height 0.2 --seed 4 --controller neural:none --neural-weights", q("a.yaml")})).status,
            0);

  // bench flies it as its Neural-Lander baseline (row 3) instead of training one, in the world
  // it was trained in; the robustness suite (a network per world) refuses it.
  const CommandRun bench = geaware(words({"bench --only 3 --seeds 1 --truth ideal --quiet --json - --neural-weights",
                                          q("a.yaml")}));
  ASSERT_EQ(bench.status, 0) << bench.out;
  const auto table = nlohmann::json::parse(bench.out);
  EXPECT_TRUE(table["neural"]["user_file"].get<bool>());
  EXPECT_FALSE(table["neural"]["trained"].get<bool>());
  EXPECT_EQ(geaware(words({"bench --suite robustness --neural-weights", q("a.yaml")})).status / 256, 2);

  // A hover log (no velocity, attitude or horizontal a_ext) is refused, and --out is not written.
  ident_test::writeText(dir / "hover.csv", "t_s,h_m,az_ext_mps2,n1_rpm,n2_rpm,n3_rpm,n4_rpm\n0,1,0,9000,9000,9000,9000\n"
                                           "0.01,1,0,9000,9000,9000,9000\n");
  EXPECT_EQ(geaware(words({"train-residual", q("hover.csv"), "--mass-kg 1.7 --out", q("c.yaml")})).status / 256, 1);
  EXPECT_FALSE(std::filesystem::exists(dir / "c.yaml"));
  // Without a mass: a usage error.
  EXPECT_EQ(geaware(words({"train-residual", q("low.csv"), "--out", q("c.yaml")})).status / 256, 2);
}

}  // namespace
