// Reading a whole input file: its bytes, or an error naming the file and what was expected.
#include "geaware/io/input_file.hpp"

#include <unistd.h>

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

TEST(InputFile, MissingFileAndDirectoryAreNamedErrors) {
  const auto d = tempDir();
  EXPECT_EQ(errorOf(d / "absent.yaml"), (d / "absent.yaml").string() + ": no such vehicle file");
  EXPECT_EQ(errorOf(d), d.string() + ": not a regular file (expected a vehicle YAML file)");
}

}  // namespace
}  // namespace geaware::io
