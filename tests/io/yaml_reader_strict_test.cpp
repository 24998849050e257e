// SPDX-License-Identifier: BSD-3-Clause
// The strict MapReader methods (finite numbers, lists with a length, rows, lists of maps,
// texts, free-form text maps, a word in place of a value): each problem names the key path and
// its line, and readers keep going so that one run reports everything.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/io/yaml_reader.hpp"

namespace geaware::io {
namespace {

/// The problems of reading `yaml` with `read` (a MapReader on the document's root map).
template <typename Read>
std::vector<ConfigProblem> problemsOf(const std::string& yaml, Read read) {
  YamlContext ctx;
  MapReader root(YAML::Load(yaml), "", ctx);
  read(root, ctx);
  return ctx.problems;
}

TEST(YamlReaderStrict, FiniteNumberRejectsJunkAndNonFiniteValuesByName) {
  YamlContext ctx;
  MapReader r(YAML::Load("a: +1.5\nb: .nan\nc: inf\nd: 1.5x\ne: 1e999\nf: [1]\n"), "", ctx);
  EXPECT_EQ(r.finiteNumber("a"), 1.5);
  EXPECT_TRUE(std::isnan(r.finiteNumber("b")));
  EXPECT_TRUE(std::isnan(r.finiteNumber("c")));
  EXPECT_TRUE(std::isnan(r.finiteNumber("d")));
  EXPECT_TRUE(std::isnan(r.finiteNumber("e")));
  EXPECT_TRUE(std::isnan(r.finiteNumber("f")));
  ASSERT_EQ(ctx.problems.size(), 5u);
  EXPECT_EQ(ctx.problems[0].key, "b");
  EXPECT_EQ(ctx.problems[0].line, 2);
  EXPECT_EQ(ctx.problems[0].message, "'.nan' is not a finite number");
  EXPECT_EQ(ctx.problems[1].message, "'inf' is not a finite number");
  EXPECT_EQ(ctx.problems[2].message, "expected a number, got '1.5x'");
  EXPECT_EQ(ctx.problems[3].message, "expected a number, got '1e999'");
  EXPECT_EQ(ctx.problems[4].message, "expected a number, got a list");
}

// A value of a hostile file (up to a line's 1 MiB) is echoed in a message as at most 80 bytes.
TEST(YamlReaderStrict, LongValuesAreNotEchoedWhole) {
  YamlContext ctx;
  const std::string junk(500'000, 'x');
  MapReader r(YAML::Load("a: " + junk + "\nb: " + junk + "\nc: " + junk + "\n"), "", ctx);
  (void)r.finiteNumber("a");
  (void)r.number("b");
  (void)r.choice("c", {"flat", "step"});
  ASSERT_EQ(ctx.problems.size(), 3u);
  for (const auto& p : ctx.problems) {
    EXPECT_LT(p.message.size(), 200u) << p.key;
    EXPECT_NE(p.message.find(std::string(80, 'x') + "…"), std::string::npos) << p.key;
  }
}

TEST(YamlReaderStrict, FiniteNumbersCheckTheLengthAndStillReadEveryItem) {
  YamlContext ctx;
  MapReader r(YAML::Load("v:\n  - 1\n  - .inf\n  - 3\n"), "", ctx);
  const auto v = r.finiteNumbers("v", 2);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[2], 3.0);
  ASSERT_EQ(ctx.problems.size(), 2u);
  EXPECT_EQ(ctx.problems[0].key, "v");
  EXPECT_EQ(ctx.problems[0].message, "has 3 entries, expected 2");
  EXPECT_EQ(ctx.problems[1].key, "v[1]");
  EXPECT_EQ(ctx.problems[1].line, 3);
  EXPECT_EQ(ctx.lines.at("v[2]"), 4);  // for problems found after reading
}

TEST(YamlReaderStrict, RowsHaveTheGivenLengthOrTheFirstRowsAndRecordTheirItems) {
  const std::string yaml = "w:\n  - [1, 2]\n  - [3, 4, 5]\n  - 6\n";
  YamlContext ctx;
  MapReader r(YAML::Load(yaml), "", ctx);
  const auto rows = r.finiteRows("w", std::nullopt);  // the first row decides: 2
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1], (std::vector<double>{3, 4, 5}));
  ASSERT_EQ(ctx.problems.size(), 2u);
  EXPECT_EQ(ctx.problems[0].key, "w[1]");
  EXPECT_EQ(ctx.problems[0].line, 3);
  EXPECT_EQ(ctx.problems[0].message, "has 3 entries, expected 2");
  EXPECT_EQ(ctx.problems[1].key, "w[2]");
  EXPECT_EQ(ctx.lineOf("w[1][2]"), 3);

  const auto given = problemsOf(yaml, [](MapReader& m, YamlContext&) {
    static_cast<void>(m.finiteRows("w", 3));
  });
  ASSERT_EQ(given.size(), 2u);
  EXPECT_EQ(given[0].key, "w[0]");
  EXPECT_EQ(given[0].message, "has 2 entries, expected 3");
}

TEST(YamlReaderStrict, MapsKeepTheIndicesOfItemsAfterABadOne) {
  const std::string yaml = "layers:\n  - 7\n  - a: 1\n    b: 2\n";
  YamlContext ctx;
  MapReader root(YAML::Load(yaml), "", ctx);
  auto items = root.maps("layers");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_FALSE(items[0].valid());
  EXPECT_TRUE(items[1].valid());
  EXPECT_EQ(items[1].path(), "layers[1]");
  EXPECT_TRUE(std::isnan(items[0].finiteNumber("a")));  // no second problem for the bad item
  EXPECT_EQ(items[1].finiteNumber("a"), 1.0);
  static_cast<void>(items[1].finiteNumber("c"));
  items[1].rejectUnknownKeys();
  ASSERT_EQ(ctx.problems.size(), 3u);
  EXPECT_EQ(ctx.problems[0].key, "layers[0]");
  EXPECT_EQ(ctx.problems[0].line, 2);
  EXPECT_EQ(ctx.problems[0].message, "expected a map, got a scalar");
  EXPECT_EQ(ctx.problems[1].key, "layers[1].c");
  EXPECT_EQ(ctx.problems[1].line, 3);  // a missing key: at its item's line
  EXPECT_EQ(ctx.problems[2].key, "layers[1].b");
  EXPECT_EQ(ctx.problems[2].line, 4);
}

TEST(YamlReaderStrict, TextsAndOptionalTextMaps) {
  YamlContext ctx;
  MapReader r(YAML::Load("names: [x, [y], z]\nprov:\n  cmd: run\n  seed: [1]\n"), "", ctx);
  EXPECT_EQ(r.texts("names"), (std::vector<std::string>{"x", "", "z"}));
  const auto prov = r.optionalTextMap("prov");
  EXPECT_EQ(prov, (std::map<std::string, std::string>{{"cmd", "run"}}));
  EXPECT_TRUE(r.optionalTextMap("absent").empty());
  r.rejectUnknownKeys();  // the absent optional key is not a problem, nor unknown
  ASSERT_EQ(ctx.problems.size(), 2u);
  EXPECT_EQ(ctx.problems[0].key, "names[1]");
  EXPECT_EQ(ctx.problems[0].message, "expected text, got a list");
  EXPECT_EQ(ctx.problems[1].key, "prov.seed");
  EXPECT_EQ(ctx.problems[1].line, 4);
}

TEST(YamlReaderStrict, ValueIsTestsAWordWithoutReadingTheKey) {
  YamlContext ctx;
  MapReader r(YAML::Load("gamma: none\nbeta: 2\nlist: [none]\n"), "", ctx);
  EXPECT_TRUE(r.valueIs("gamma", "none"));
  EXPECT_FALSE(r.valueIs("beta", "none"));
  EXPECT_FALSE(r.valueIs("list", "none"));
  EXPECT_FALSE(r.valueIs("missing", "none"));
  EXPECT_EQ(r.finiteNumber("beta"), 2.0);
  r.rejectUnknownKeys();  // gamma and list were only tested, not read
  ASSERT_EQ(ctx.problems.size(), 2u);
  EXPECT_EQ(ctx.problems[0].key, "gamma");
  EXPECT_EQ(ctx.problems[1].key, "list");
}

}  // namespace
}  // namespace geaware::io
