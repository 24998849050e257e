// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/report/chromium.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "geaware/report/page.hpp"

extern char** environ;  // NOLINT: POSIX, passed on to Chromium unchanged

namespace geaware::report {
namespace {

namespace fs = std::filesystem;

// Generous: a cold Chromium start on a loaded 2-core machine takes a few seconds, and the
// virtual-time budget is not wall time.
constexpr std::chrono::seconds kTimeout{120};

// A fresh directory under the system temp dir, removed with everything in it at scope exit.
// Chromium gets its own empty profile each run (no first-run state, no lock shared with
// another instance), as the machine notes require.
class TempDir {
 public:
  TempDir() {
    std::string templ = (fs::temp_directory_path() / "geaware-chromium-XXXXXX").string();
    if (mkdtemp(templ.data()) == nullptr) {
      throw std::runtime_error("report: cannot create a temporary directory '" + templ +
                               "': " + std::strerror(errno));
    }
    path_ = templ;
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);  // best effort: a leftover temp dir is not worth an exception
  }
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string tail(const std::string& text, std::size_t n) {
  return text.size() <= n ? text : "…" + text.substr(text.size() - n);
}

bool isExecutable(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && access(p.c_str(), X_OK) == 0;
}

// file:// URL of an absolute path, percent-encoding everything but unreserved characters and '/'
// (RFC 3986), so that spaces or '#' in a path do not change the URL's meaning.
std::string fileUrl(const fs::path& file) {
  static constexpr std::string_view kHex = "0123456789ABCDEF";
  std::string url = "file://";
  for (const char c : fs::absolute(file).lexically_normal().string()) {
    const auto u = static_cast<unsigned char>(c);
    const bool plain = (u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z') || (u >= '0' && u <= '9') ||
                       c == '-' || c == '.' || c == '_' || c == '~' || c == '/';
    if (plain) {
      url += c;
    } else {
      url += '%';
      url += kHex[u >> 4U];
      url += kHex[u & 0xFU];
    }
  }
  return url;
}

struct RunResult {
  int exit_code;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs Chromium headless on `url` with `extra` flags and returns its exit code and output.
// Spawned without a shell (arguments are never re-parsed), in its own process group so that on
// timeout the browser and its helper processes are killed together.
RunResult runChromium(const std::vector<std::string>& extra, const std::string& url) {
  const auto chromium = findChromium();
  if (!chromium) {
    throw std::runtime_error(
        "report: Chromium not found (looked at $GEAWARE_CHROMIUM, /usr/bin/chromium, "
        "/usr/bin/chromium-browser and PATH); install Debian's package: apt-get install chromium");
  }
  const TempDir tmp;
  const fs::path out_file = tmp.path() / "stdout.txt";
  const fs::path err_file = tmp.path() / "stderr.txt";

  // The flags the machine notes give for a headless run without network: no sandbox (we run as
  // root in a container and load only our own file), no GPU, and none of the background
  // services whose connections a closed network refuses.
  std::vector<std::string> args = {chromium->string(),
                                   "--headless",
                                   "--no-sandbox",
                                   "--disable-gpu",
                                   "--disable-quic",
                                   "--no-first-run",
                                   "--no-default-browser-check",
                                   "--disable-background-networking",
                                   "--disable-component-update",
                                   "--disable-sync",
                                   "--disable-extensions",
                                   "--hide-scrollbars",
                                   "--mute-audio",
                                   "--user-data-dir=" + (tmp.path() / "profile").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back(url);
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attr;
  posix_spawn_file_actions_init(&actions);
  posix_spawnattr_init(&attr);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_file.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    throw std::runtime_error("report: cannot start '" + args[0] + "': " + std::strerror(rc));
  }

  // Poll rather than block, so that a hung browser is killed after kTimeout. WNOWAIT leaves
  // the exited browser a zombie, so its process-group id cannot be reused before the group's
  // helper processes (renderer, zygote) are killed below.
  const auto deadline = std::chrono::steady_clock::now() + kTimeout;
  bool timed_out = false;
  for (;;) {
    siginfo_t info{};
    const int w = waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT);
    if (w == 0 && info.si_pid == pid) break;
    if (w < 0 && errno != EINTR) {
      throw std::runtime_error(std::string("report: waiting for Chromium failed: ") +
                               std::strerror(errno));
    }
    if (std::chrono::steady_clock::now() > deadline) {
      timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(-pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  if (timed_out) {
    throw std::runtime_error("report: Chromium did not finish within " +
                             std::to_string(kTimeout.count()) + " s on " + url);
  }

  RunResult result{-1, slurp(out_file), slurp(err_file)};
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  return result;
}

void requireFile(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    throw std::runtime_error("report: no such page '" + file.string() + "'");
  }
}

}  // namespace

std::optional<fs::path> findChromium() {
  if (const char* env = std::getenv("GEAWARE_CHROMIUM"); env != nullptr && *env != '\0') {
    // An explicit choice that does not work is an error, not a reason to look elsewhere.
    if (isExecutable(env)) return fs::path(env);
    return std::nullopt;
  }
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (isExecutable(p)) return fs::path(p);
  }
  if (const char* path = std::getenv("PATH"); path != nullptr) {
    const std::string_view dirs = path;
    for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
      std::size_t begin = 0;
      while (begin <= dirs.size()) {
        const std::size_t end = std::min(dirs.find(':', begin), dirs.size());
        const fs::path candidate = fs::path(dirs.substr(begin, end - begin)) / name;
        if (end > begin && isExecutable(candidate)) return candidate;
        begin = end + 1;
      }
    }
  }
  return std::nullopt;
}

std::string dumpDom(const fs::path& html_file, int virtual_time_ms) {
  requireFile(html_file);
  const RunResult r =
      runChromium({"--virtual-time-budget=" + std::to_string(virtual_time_ms), "--dump-dom"},
                  fileUrl(html_file));
  if (r.exit_code != 0 || r.out.empty()) {
    throw std::runtime_error("report: Chromium --dump-dom of '" + html_file.string() +
                             "' failed (exit code " + std::to_string(r.exit_code) +
                             "): " + tail(r.err, 2000));
  }
  return r.out;
}

void exportPng(const fs::path& html_file, const fs::path& png_file, int width_px, int height_px) {
  if (width_px < 16 || height_px < 16 || width_px > 10000 || height_px > 10000) {
    throw std::runtime_error("report: PNG size " + std::to_string(width_px) + "x" +
                             std::to_string(height_px) + " px is outside 16…10000 px");
  }
  requireFile(html_file);
  const fs::path png = fs::absolute(png_file);
  std::error_code ec;
  fs::remove(png, ec);  // so that a stale file cannot pass for this render
  // The virtual-time budget lets plotly's scripts and layout run to completion before the
  // screenshot; --run-all-compositor-stages-before-draw makes the frame complete.
  const RunResult r =
      runChromium({"--virtual-time-budget=5000", "--run-all-compositor-stages-before-draw",
                   "--window-size=" + std::to_string(width_px) + "," + std::to_string(height_px),
                   "--screenshot=" + png.string()},
                  fileUrl(html_file));
  const bool written = fs::is_regular_file(png, ec) && fs::file_size(png, ec) > 0 &&
                       slurp(png).compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
  if (r.exit_code != 0 || !written) {
    throw std::runtime_error("report: Chromium could not render '" + html_file.string() + "' to '" +
                             png.string() + "' (exit code " + std::to_string(r.exit_code) +
                             (written ? "" : ", no PNG file written") + "): " + tail(r.err, 2000));
  }
}

void exportPagePng(const fs::path& html_file, const fs::path& png_file, int width_px) {
  // The page measures itself once its scripts ran (data-geaware-height on <html>); the second
  // run renders a window that tall, so the PNG holds the whole page, not its first screen.
  const std::string dom = dumpDom(html_file);
  constexpr std::string_view kKey = "data-geaware-height=\"";
  const auto at = dom.find(kKey);
  int height_px = 0;
  if (at != std::string::npos) {
    const char* begin = dom.data() + at + kKey.size();
    (void)std::from_chars(begin, dom.data() + dom.size(), height_px);
  }
  if (height_px <= 0) {
    throw std::runtime_error("report: '" + html_file.string() +
                             "' did not report its height (not a geaware page?)");
  }
  exportPng(html_file, png_file, width_px, std::clamp(height_px + 16, 16, 10000));
}

}  // namespace geaware::report
