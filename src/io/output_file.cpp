// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/output_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "geaware/io/input_file.hpp"

namespace geaware::io {

namespace fs = std::filesystem;

namespace {

std::string inQuotes(const std::string& s) { return "'" + s + "'"; }

[[noreturn]] void refuse(std::string_view option, const std::string& path, const std::string& why) {
  throw OutputError(std::string(option) + " " + inQuotes(path) + ": " + why);
}

/// Creates a unique file next to `target` (mode 0600) and returns its path and open descriptor.
int makeTemporary(const fs::path& target, fs::path& temp) {
  std::string pattern = (target.parent_path() / ("." + target.filename().string() + ".geaware-XXXXXX")).string();
  const int fd = ::mkstemp(pattern.data());
  if (fd >= 0) temp = pattern;
  return fd;
}

/// The temporary files of uncommitted AtomicFiles, for the signal handler: a fixed table (no
/// allocation, lock-free atomics) that a handler may read. state: 0 free, 1 being filled,
/// 2 holds a path to remove.
constexpr int kTempSlots = 64;
constexpr std::size_t kTempPathBytes = 4096;
struct TempSlot {
  std::atomic<int> state{0};
  char path[kTempPathBytes];
};
TempSlot g_temp_slots[kTempSlots];

int registerTemporary(const fs::path& temp) {
  const std::string& p = temp.native();
  if (p.size() >= kTempPathBytes) return -1;
  for (int i = 0; i < kTempSlots; ++i) {
    int expected = 0;
    if (g_temp_slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_temp_slots[i].path, p.c_str(), p.size() + 1);
      g_temp_slots[i].state.store(2);
      return i;
    }
  }
  return -1;  // more than 64 open at once: that one is not removed on a signal
}

void unregisterTemporary(int slot) {
  if (slot >= 0) g_temp_slots[slot].state.store(0);
}

extern "C" void removeTemporariesAndDie(int sig) {
  for (auto& slot : g_temp_slots) {
    if (slot.state.load() == 2) ::unlink(slot.path);
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

/// The permissions a newly created file gets under the process's umask.
mode_t newFileMode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return static_cast<mode_t>(0666 & ~mask);
}

}  // namespace

OutputPath checkOutputPath(std::string_view option, const std::string& path, bool stdout_allowed) {
  OutputPath out{std::string(option), path, {}, false};
  if (path.empty()) refuse(option, path, "empty path; expected a file path or '-' for standard output");
  if (path == "-") {
    if (!stdout_allowed) refuse(option, path, "this output cannot go to standard output; give a file path");
    out.to_stdout = true;
    return out;
  }
  std::error_code ec;
  const fs::path given(path);
  const fs::file_status link = fs::symlink_status(given, ec);
  const fs::file_status st = fs::status(given, ec);
  if (fs::is_symlink(link) && !fs::exists(st)) {
    refuse(option, path, "a symbolic link to a missing file; give the file itself or a new path");
  }
  if (fs::exists(st)) {
    if (fs::is_directory(st)) refuse(option, path, "is a directory; expected a file path");
    if (!fs::is_regular_file(st)) {
      refuse(option, path, "is a device, FIFO or socket, not a regular file; give a regular file path");
    }
    out.target = fs::canonical(given, ec);
    if (ec) refuse(option, path, "cannot resolve the path: " + ec.message());
    if (::access(out.target.c_str(), W_OK) != 0) {
      refuse(option, path, std::string("the existing file is not writable: ") + std::strerror(errno));
    }
  } else {
    out.target = fs::weakly_canonical(fs::absolute(given, ec), ec);
    if (ec) refuse(option, path, "cannot resolve the path: " + ec.message());
    const fs::path dir = out.target.parent_path();
    if (!fs::is_directory(dir, ec)) {
      refuse(option, path, "its directory " + inQuotes(dir.string()) + " does not exist; create it first");
    }
  }
  // The only reliable writability test (read-only mounts, ACLs): create a file there.
  fs::path probe;
  const int fd = makeTemporary(out.target, probe);
  if (fd < 0) {
    refuse(option, path, "cannot create a file in " + inQuotes(out.target.parent_path().string()) + ": " +
                             std::strerror(errno));
  }
  ::close(fd);
  fs::remove(probe, ec);
  return out;
}

OutputPath checkOutputDirectory(std::string_view option, const std::string& path) {
  OutputPath out{std::string(option), path, {}, false};
  if (path.empty()) refuse(option, path, "empty path; expected a directory");
  std::error_code ec;
  const fs::path given(path);
  const fs::file_status st = fs::status(given, ec);
  fs::path existing = fs::absolute(given, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) refuse(option, path, "exists and is not a directory; expected a directory");
    out.target = fs::canonical(given, ec);
    if (ec) refuse(option, path, "cannot resolve the path: " + ec.message());
    existing = out.target;
  } else {
    if (fs::is_symlink(fs::symlink_status(given, ec))) {
      refuse(option, path, "a symbolic link to a missing directory; give the directory itself");
    }
    out.target = fs::weakly_canonical(existing, ec);
    // The nearest ancestor that exists is where the directory will be created.
    while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path()) {
      existing = existing.parent_path();
    }
    if (!fs::is_directory(existing, ec)) {
      refuse(option, path, inQuotes(existing.string()) + " is not a directory; cannot create the directory in it");
    }
  }
  fs::path probe;
  const int fd = makeTemporary(existing / "probe", probe);
  if (fd < 0) {
    refuse(option, path, "cannot create a file in " + inQuotes(existing.string()) + ": " + std::strerror(errno));
  }
  ::close(fd);
  fs::remove(probe, ec);
  return out;
}

void OutputChecks::input(std::string_view option, const std::string& path) {
  if (!path.empty() && path != "-") inputs_.push_back({std::string(option), path});
}

void OutputChecks::output(std::string_view option, const std::string& path, bool stdout_allowed) {
  if (path.empty()) return;
  outputs_.push_back(checkOutputPath(option, path, stdout_allowed));
}

void OutputChecks::directory(std::string_view option, const std::string& path) {
  if (path.empty()) return;
  directories_.push_back(checkOutputDirectory(option, path));
}

namespace {

/// Whether the output `out` is the file `in` (an existing output by identity, a new one by
/// its resolved path).
bool sameFile(const OutputPath& out, const fs::path& in) {
  std::error_code ec;
  if (!fs::exists(in, ec)) return false;
  if (fs::exists(out.target, ec)) return fs::equivalent(out.target, in, ec) && !ec;
  return fs::weakly_canonical(fs::absolute(in, ec), ec) == out.target && !ec;
}

}  // namespace

void OutputChecks::check() const {
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    const OutputPath& out = outputs_[i];
    for (std::size_t j = 0; j < i; ++j) {
      const OutputPath& other = outputs_[j];
      if (out.to_stdout && other.to_stdout) {
        refuse(out.option, out.given, "standard output is already taken by " + other.option +
                                          "; only one output can go to '-'");
      }
      if (!out.to_stdout && !other.to_stdout && out.target == other.target) {
        refuse(out.option, out.given, "is the same file as " + other.option + " " + inQuotes(other.given) +
                                          "; give each output its own path");
      }
    }
    if (out.to_stdout) continue;
    for (const OutputPath& dir : directories_) {
      if (out.target == dir.target) {
        refuse(out.option, out.given, "is the directory of " + dir.option + " " + inQuotes(dir.given) +
                                          "; give each output its own path");
      }
    }
    for (const Input& in : inputs_) {
      if (sameFile(out, in.path)) {
        refuse(out.option, out.given, "is the same file as the input " + in.option + " " + inQuotes(in.path) +
                                          "; writing it would destroy the input — choose another output path");
      }
    }
    for (const InputFileRead& in : inputFilesRead()) {
      if (sameFile(out, in.path)) {
        refuse(out.option, out.given, "is the " + in.noun + " " + inQuotes(in.path.string()) +
                                          " this run reads; writing it would destroy the input — choose "
                                          "another output path");
      }
    }
  }
}

AtomicFile::AtomicFile(const std::string& path, std::string what)
    : out_(checkOutputPath("output", path)), what_(std::move(what)) {
  if (out_.to_stdout) {
    file_ = stdout;
    return;
  }
  const int fd = makeTemporary(out_.target, temp_);
  if (fd < 0) fail("create a temporary file for", errno);
  slot_ = registerTemporary(temp_);
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    const int e = errno;
    ::close(fd);
    fail("open", e);
  }
}

AtomicFile::~AtomicFile() {
  if (out_.to_stdout || committed_) return;
  if (file_ != nullptr) std::fclose(file_);
  std::error_code ec;
  if (!temp_.empty()) fs::remove(temp_, ec);
  unregisterTemporary(slot_);
}

void AtomicFile::write(std::string_view text) {
  if (text.empty()) return;
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) fail("write", errno);
}

void AtomicFile::commit() {
  if (committed_) return;
  if (std::fflush(file_) != 0 || std::ferror(file_) != 0) fail("write", errno);
  if (out_.to_stdout) {
    committed_ = true;
    return;
  }
  if (::fsync(::fileno(file_)) != 0) fail("write", errno);
  struct stat existing {};
  const mode_t mode = ::stat(out_.target.c_str(), &existing) == 0 ? (existing.st_mode & 07777) : newFileMode();
  if (::fchmod(::fileno(file_), mode) != 0) fail("set the permissions of", errno);
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) fail("write", errno);
  // Never rename over anything but a regular file (it may have changed since the check).
  struct stat now {};
  if (::lstat(out_.target.c_str(), &now) == 0 && !S_ISREG(now.st_mode)) {
    throw OutputError("cannot replace " + what_ + " " + inQuotes(out_.given) +
                      ": it is no longer a regular file; nothing was written");
  }
  if (std::rename(temp_.c_str(), out_.target.c_str()) != 0) fail("replace", errno);
  committed_ = true;
  unregisterTemporary(slot_);
}

void AtomicFile::fail(const std::string& action, int error_number) {
  const std::string where = out_.to_stdout ? std::string("standard output") : inQuotes(out_.given);
  throw OutputError("cannot " + action + " " + what_ + " " + where + ": " + std::strerror(error_number) +
                    (out_.to_stdout ? "" : " (the existing file, if any, is unchanged)"));
}

void removeTemporaryFilesOnSignals() {
  struct sigaction action {};
  action.sa_handler = removeTemporariesAndDie;
  sigemptyset(&action.sa_mask);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(sig, &action, nullptr);
}

void writeFileAtomically(const std::string& path, std::string_view text, std::string what) {
  AtomicFile file(path, std::move(what));
  file.write(text);
  file.commit();
}

}  // namespace geaware::io
