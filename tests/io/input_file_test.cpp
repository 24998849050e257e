// SPDX-License-Identifier: BSD-3-Clause
// Reading a whole input file: its bytes, or an error naming the file and what was expected.
#include "geaware/io/input_file.hpp"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace geaware::io {
namespace {

std::filesystem::path tempDir() {
  const auto d = std::filesystem::temp_directory_path() /
                 ("geaware_input_file_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

std::string errorOf(const std::filesystem::path& p) {
  try {
    (void)readInputFile(p, "vehicle file", "vehicle YAML file");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(InputFile, ReturnsTheBytesUnchanged) {
  const auto f = tempDir() / "v.yaml";
  const std::string bytes = std::string("mass_kg: 1.5\r\n\0tail", 20);
  std::ofstream(f, std::ios::binary) << bytes;
  EXPECT_EQ(readInputFile(f, "vehicle file", "vehicle YAML file"), bytes);
}

// A line over 1 MiB is refused with its line number and at most 80 characters of it; a 60 MB
// file without a newline (sparse) fails within a second, without reading it whole.
TEST(InputFile, LinesOverOneMebibyteAreRefusedQuickly) {
  const auto f = tempDir() / "long.yaml";
  std::ofstream(f, std::ios::binary) << "a: 1\nb: 2\nc: " << std::string(kMaxLineBytes, 'x') << "\n";
  const std::string msg = errorOf(f);
  EXPECT_EQ(msg.rfind(f.string() + ":3: line longer than 1 MiB (starts 'c: xxx", 0), 0u) << msg;
  EXPECT_LT(msg.size(), f.string().size() + 200);
  const auto huge = tempDir() / "huge.yaml";
  { std::ofstream(huge) << "a: "; }
  std::filesystem::resize_file(huge, 60'000'000);  // under the 64 MiB of a whole-file input
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NE(errorOf(huge).find(":1: line longer than 1 MiB (starts 'a: \\x00"), std::string::npos);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  std::filesystem::remove(huge);
  // Exactly at the limit is fine.
  std::ofstream(f, std::ios::binary) << std::string(kMaxLineBytes, 'x') << "\n";
  EXPECT_EQ(errorOf(f), "");
}

// A file larger than any input of its kind can be is refused before it is read.
TEST(InputFile, FilesOver64MebibytesAreRefusedUnread) {
  const auto huge = tempDir() / "huge.yaml";
  { std::ofstream(huge) << "a: 1\n"; }
  std::filesystem::resize_file(huge, kMaxInputFileBytes + 1);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(errorOf(huge), huge.string() + ": 67108865 bytes, larger than a vehicle file can be (at most 64 MiB; "
                                           "expected a vehicle YAML file)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(100));
  std::filesystem::remove(huge);
}

TEST(InputFile, MissingFileAndDirectoryAreNamedErrors) {
  const auto d = tempDir();
  EXPECT_EQ(errorOf(d / "absent.yaml"), (d / "absent.yaml").string() + ": no such vehicle file");
  EXPECT_EQ(errorOf(d), d.string() + ": not a regular file (expected a vehicle YAML file)");
}

}  // namespace
}  // namespace geaware::io
