// SPDX-License-Identifier: BSD-3-Clause
// JSON output and provenance: SHA-256 against the FIPS 180-4 examples, the JSON rules every
// command relies on (NaN as null, escaping, unparsable bytes replaced), checked writes.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "geaware/io/json.hpp"
#include "geaware/io/provenance.hpp"

namespace geaware::io {
namespace {

std::string sha(const std::string& s) {
  return sha256Hex({reinterpret_cast<const unsigned char*>(s.data()), s.size()});
}

TEST(Sha256, FipsExamples) {
  EXPECT_EQ(sha(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // 448 bits: the length no longer fits in the first block's padding.
  EXPECT_EQ(sha("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, FileEqualsBytesAcrossReadBlocks) {
  const std::string path = ::testing::TempDir() + "/geaware_sha_test.bin";
  std::string data;
  for (int i = 0; i < 200000; ++i) data += static_cast<char>(i * 31 % 251);
  { std::ofstream(path, std::ios::binary) << data; }
  EXPECT_EQ(fileSha256Hex(path), sha(data));
  std::remove(path.c_str());
  EXPECT_THROW((void)fileSha256Hex(path), std::runtime_error);
}

TEST(Json, NonFiniteNumbersAreNullAndNamesEscaped) {
  Json doc = {{"name", "quad \"x\"\n\\"}, {"rmse", std::numeric_limits<double>::quiet_NaN()},
              {"max", std::numeric_limits<double>::infinity()}, {"ok", 1.5}};
  const std::string text = dumpJson(doc);
  const Json back = Json::parse(text);
  EXPECT_TRUE(back["rmse"].is_null());
  EXPECT_TRUE(back["max"].is_null());
  EXPECT_EQ(back["name"], "quad \"x\"\n\\");
  EXPECT_EQ(back["ok"], 1.5);
  EXPECT_LT(text.find("\"name\""), text.find("\"rmse\""));  // insertion order kept
}

TEST(Json, InvalidUtf8IsReplacedNotThrown) {
  const std::string bad = std::string("v") + static_cast<char>(0xff) + "x";
  std::string text;
  ASSERT_NO_THROW(text = dumpJson(Json{{"name", bad}}));
  EXPECT_EQ(Json::parse(text)["name"], "v\xEF\xBF\xBDx");
  EXPECT_EQ(Json::parse(jsonString(bad)), "v\xEF\xBF\xBDx");
}

TEST(Json, WriteJsonRoundTripsAndReportsAFullDisk) {
  const std::string path = ::testing::TempDir() + "/geaware_json_test.json";
  writeJson(path, Json{{"a", 1}});
  std::ifstream in(path);
  EXPECT_EQ(Json::parse(in)["a"], 1);
  std::remove(path.c_str());
  std::ifstream full("/dev/full");
  if (full.good()) {
    try {
      writeJson("/dev/full", Json{{"a", std::string(1 << 16, 'x')}});
      ADD_FAILURE() << "writing to /dev/full did not fail";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos);
    }
  }
  EXPECT_THROW(writeJson("/nonexistent-dir/x.json", Json{}), std::runtime_error);
}

TEST(Provenance, CarriesVersionCommitCommandSeedsAndHashes) {
  const std::string path = ::testing::TempDir() + "/geaware_prov_input.txt";
  { std::ofstream(path) << "abc"; }
  const Json p = provenanceJson({"geaware fly --seed 3", {3, 4}, {path, "/nonexistent/file"}});
  EXPECT_EQ(p["geaware_version"], std::string(geawareVersion()));
  EXPECT_FALSE(std::string(geawareCommit()).empty());
  EXPECT_EQ(p["command_line"], "geaware fly --seed 3");
  EXPECT_EQ(p["seeds"], Json::array({3, 4}));
  EXPECT_EQ(p["inputs"][0]["sha256"], sha("abc"));
  EXPECT_TRUE(p["inputs"][1]["sha256"].is_null());
  const std::string c = provenanceComment({"a\nb", {7}, {path}});
  EXPECT_NE(c.find("# command_line: a b\n"), std::string::npos);
  EXPECT_NE(c.find("# seeds: 7\n"), std::string::npos);
  EXPECT_NE(c.find(sha("abc")), std::string::npos);
  std::remove(path.c_str());
}

TEST(Provenance, ShellQuotingReadsBackAsTheSameWords) {
  const char* argv[] = {"geaware", "fly", "--name", "it's a test", "", "--x=1"};
  EXPECT_EQ(shellQuotedCommandLine(6, argv), "geaware fly --name 'it'\\''s a test' '' --x=1");
}

}  // namespace
}  // namespace geaware::io
