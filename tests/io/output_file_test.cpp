// SPDX-License-Identifier: BSD-3-Clause
// Output files: checked before work, written whole or not at all, inputs never overwritten.
#include "geaware/io/output_file.hpp"
#include "geaware/io/input_file.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using geaware::io::AtomicFile;
using geaware::io::checkOutputDirectory;
using geaware::io::checkOutputPath;
using geaware::io::OutputChecks;
using geaware::io::OutputError;
using geaware::io::writeFileAtomically;

namespace {

class OutputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geaware_output_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static void put(const std::string& p, const std::string& text) { std::ofstream(p) << text; }
  static std::string get(const std::string& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  /// Files in the directory (to see that no temporary file is left behind).
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  template <class F>
  static std::string errorOf(F&& f) {
    try {
      f();
    } catch (const OutputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(OutputFileTest, WritesNewFileWhole) {
  writeFileAtomically(path("a.json"), "{}\n", "the JSON output");
  EXPECT_EQ(get(path("a.json")), "{}\n");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFileTest, ReplacesExistingFileAndKeepsItsPermissions) {
  put(path("a.csv"), "old");
  fs::permissions(path("a.csv"), fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  writeFileAtomically(path("a.csv"), "new", "the log");
  EXPECT_EQ(get(path("a.csv")), "new");
  EXPECT_EQ(fs::status(path("a.csv")).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

TEST_F(OutputFileTest, UncommittedFileLeavesTargetUntouched) {
  put(path("a.csv"), "precious");
  {
    AtomicFile f(path("a.csv"), "the log");
    f.write("half of a refused run");
  }
  EXPECT_EQ(get(path("a.csv")), "precious");
  EXPECT_EQ(entries(), 1u) << "the temporary file must be removed";
}

TEST_F(OutputFileTest, SymlinkIsWrittenThroughToItsTarget) {
  put(path("vehicle.yaml"), "mass: 1");
  fs::create_symlink(path("vehicle.yaml"), path("link.yaml"));
  writeFileAtomically(path("link.yaml"), "mass: 2", "the vehicle file");
  EXPECT_TRUE(fs::is_symlink(path("link.yaml")));
  EXPECT_EQ(get(path("vehicle.yaml")), "mass: 2");
}

TEST_F(OutputFileTest, RefusesDirectoriesSpecialFilesAndDanglingLinks) {
  EXPECT_NE(errorOf([&] { (void)checkOutputPath("--json", dir_.string()); }).find("is a directory"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { (void)checkOutputPath("--out", "/dev/null"); }).find("not a regular file"),
            std::string::npos);
  fs::create_symlink(path("missing"), path("dangling"));
  EXPECT_NE(errorOf([&] { (void)checkOutputPath("--out", path("dangling")); }).find("missing file"),
            std::string::npos);
  const std::string msg = errorOf([&] { (void)checkOutputPath("--report", path("no/such/dir/r.html")); });
  EXPECT_NE(msg.find("--report"), std::string::npos);
  EXPECT_NE(msg.find("does not exist"), std::string::npos);
  EXPECT_NE(errorOf([&] { (void)checkOutputPath("--out", ""); }).find("empty path"), std::string::npos);
}

TEST_F(OutputFileTest, StandardOutputOnlyWhereAllowedAndOnce) {
  EXPECT_TRUE(checkOutputPath("--json", "-").to_stdout);
  EXPECT_NE(errorOf([&] { (void)checkOutputPath("--out", "-", false); }).find("standard output"),
            std::string::npos);
  OutputChecks checks;
  checks.output("--json", "-");
  checks.output("--out", "-");
  EXPECT_NE(errorOf([&] { checks.check(); }).find("only one output"), std::string::npos);
}

TEST_F(OutputFileTest, OutputThatIsAnInputIsRefusedByIdentity) {
  put(path("rotor.csv"), "rpm,thrust_N\n");
  fs::create_hard_link(path("rotor.csv"), path("hard.csv"));
  fs::create_symlink(path("rotor.csv"), path("soft.csv"));
  const std::string other_name = (dir_ / "." / "rotor.csv").string();
  for (const std::string& out : {path("rotor.csv"), path("hard.csv"), path("soft.csv"), other_name}) {
    OutputChecks checks;
    checks.input("log", path("rotor.csv"));
    checks.output("--out", out);
    const std::string msg = errorOf([&] { checks.check(); });
    EXPECT_NE(msg.find("destroy the input"), std::string::npos) << out;
    EXPECT_NE(msg.find("--out '" + out + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("the input log '" + path("rotor.csv") + "'"), std::string::npos) << msg;
  }
  EXPECT_EQ(get(path("rotor.csv")), "rpm,thrust_N\n");
}

TEST_F(OutputFileTest, TwoOutputsOnOneFileAreRefused) {
  OutputChecks checks;
  checks.output("--out", path("x.csv"));
  checks.output("--json", path("x.csv"));
  EXPECT_NE(errorOf([&] { checks.check(); }).find("same file as --out"), std::string::npos);
  OutputChecks fine;
  fine.input("--vehicle", path("absent-input.yaml"));
  fine.output("--out", path("x.csv"));
  fine.output("--json", path("y.json"));
  EXPECT_NO_THROW(fine.check());
}

TEST_F(OutputFileTest, ReadOnlyDirectoryIsRefusedBeforeWork) {
  if (::geteuid() == 0) GTEST_SKIP() << "root can write into a read-only directory";
  fs::permissions(dir_, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_NE(errorOf([&] { (void)checkOutputPath("--json", path("r.json")); }).find("cannot create a file"),
            std::string::npos);
}

// A full disk, made with a file-size limit: the write fails with EFBIG, the error names the file
// and the existing target keeps its content.
TEST_F(OutputFileTest, FullDiskIsAnErrorAndLeavesTargetUntouched) {
  put(path("out.csv"), "precious");
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string msg =
      errorOf([&] { writeFileAtomically(path("out.csv"), std::string(1 << 20, 'x'), "the flight log"); });
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  EXPECT_NE(msg.find("the flight log"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unchanged"), std::string::npos) << msg;
  EXPECT_EQ(get(path("out.csv")), "precious");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFileTest, AFileReadAsInputIsRefusedAsAnOutput) {
  put(path("nested.yaml"), "mass: 1");
  geaware::io::noteInputFile(path("nested.yaml"), "vehicle file");
  OutputChecks checks;
  checks.output("--json", path("nested.yaml"));
  const std::string msg = errorOf([&] { checks.check(); });
  EXPECT_NE(msg.find("is the vehicle file"), std::string::npos) << msg;
  EXPECT_EQ(get(path("nested.yaml")), "mass: 1");
}

TEST_F(OutputFileTest, OutputDirectoriesAreCheckedBeforeWork) {
  put(path("file"), "x");
  EXPECT_NE(errorOf([&] { (void)checkOutputDirectory("--report", path("file")); }).find("not a directory"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { (void)checkOutputDirectory("--report", path("file/sub")); }).find("not a directory"),
            std::string::npos);
  EXPECT_NO_THROW((void)checkOutputDirectory("--report", path("new/deeper")));
  EXPECT_FALSE(fs::exists(path("new"))) << "the check creates nothing";
  EXPECT_EQ(checkOutputDirectory("--report", dir_.string()).target, fs::canonical(dir_));
  OutputChecks checks;
  checks.directory("--report", path("r"));
  checks.output("--out", path("r"));
  EXPECT_NE(errorOf([&] { checks.check(); }).find("is the directory of --report"), std::string::npos);
  if (::geteuid() == 0) return;
  fs::permissions(dir_, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_NE(errorOf([&] { (void)checkOutputDirectory("--cache", path("c")); }).find("cannot create a file"),
            std::string::npos);
}

// Between the check and the commit the target became a FIFO: the rename is refused, the FIFO
// stays.
TEST_F(OutputFileTest, NeverRenamesOverANonRegularFile) {
  AtomicFile f(path("out.csv"), "the log");
  f.write("data");
  ASSERT_EQ(::mkfifo(path("out.csv").c_str(), 0600), 0);
  EXPECT_NE(errorOf([&] { f.commit(); }).find("no longer a regular file"), std::string::npos);
  EXPECT_TRUE(fs::is_fifo(path("out.csv")));
}

}  // namespace
