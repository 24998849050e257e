// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Output files that never lose what the user gave. Every output path of a command is checked
// before any long work starts (`OutputChecks`), and every file is written through a temporary
// file in the same directory that is renamed over the target only once all of it is written
// (`AtomicFile`): a refused or failed run leaves existing files as they were, a full disk is an
// error, and the user's inputs cannot be overwritten by naming them as an output.

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace geaware::io {

/// A bad output path: the message names the option, the path and what was expected.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where a checked output goes. "-" is standard output; otherwise `target` is the regular file
/// that will be replaced or created (a symlink is followed to its target, which is written).
struct OutputPath {
  std::string option;             ///< the option that named it, e.g. "--json"
  std::string given;              ///< the path as the user gave it
  std::filesystem::path target;   ///< the file that is written (absolute, symlinks resolved)
  bool to_stdout = false;         ///< "-": standard output
};

/// Checks `path` (named by `option`) as an output before any work:
/// - "-" is standard output (when `stdout_allowed`);
/// - it is not a directory, a device, a FIFO or a socket, nor a symlink to a missing file;
/// - its directory exists and a file can be created in it (read-only or missing → error).
/// Throws OutputError naming the option and the path.
[[nodiscard]] OutputPath checkOutputPath(std::string_view option, const std::string& path,
                                         bool stdout_allowed = true);

/// The outputs and inputs of one command, checked together before any work: each output as in
/// checkOutputPath, no output the same file as an input (compared by file identity, so another
/// name, a hard link or a symlink of an input is caught), no two outputs the same file, and at
/// most one output on standard output.
class OutputChecks {
 public:
  /// Records an input file named by `option` (e.g. "--vehicle"); an empty path, "-" or a file
  /// that does not exist is ignored (its reader reports it).
  void input(std::string_view option, const std::string& path);
  /// Records and checks an output; an empty path means "not requested" and is skipped.
  void output(std::string_view option, const std::string& path, bool stdout_allowed = true);
  /// Records and checks an output directory (--report, --cache): see checkOutputDirectory.
  void directory(std::string_view option, const std::string& path);
  /// Throws OutputError for the first conflict between the recorded outputs and inputs, and
  /// between the outputs and every file read so far (io::inputFilesRead(): the files a scenario
  /// or truth file names).
  void check() const;

 private:
  struct Input {
    std::string option, path;
  };
  std::vector<Input> inputs_;
  std::vector<OutputPath> outputs_;
  std::vector<OutputPath> directories_;
};

/// Checks `path` (named by `option`) as an output directory before any work: an existing one
/// must be a directory in which a file can be created; a missing one must be creatable (its
/// nearest existing ancestor a writable directory). Throws OutputError naming option and path.
[[nodiscard]] OutputPath checkOutputDirectory(std::string_view option, const std::string& path);

/// A file written as a whole or not at all: the text goes to a temporary file next to the
/// target; `commit()` checks every write, flushes it to disk and renames it over the target
/// (keeping an existing target's permissions). Destroying an uncommitted AtomicFile removes the
/// temporary file and leaves the target untouched. For "-" the text goes straight to stdout.
class AtomicFile {
 public:
  /// Opens the temporary file for `path` (checked with checkOutputPath). `what` names the
  /// content in errors, e.g. "the flight log".
  AtomicFile(const std::string& path, std::string what);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// The stream to write to (the temporary file, or stdout).
  [[nodiscard]] std::FILE* stream() const { return file_; }
  /// Appends `text`; a failed write is remembered and reported by commit().
  void write(std::string_view text);
  /// Completes the file: throws OutputError on any write, flush or rename failure (the target is
  /// then untouched).
  void commit();

 private:
  [[noreturn]] void fail(const std::string& action, int error_number);

  OutputPath out_;
  std::string what_;
  std::filesystem::path temp_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
  int slot_ = -1;  // in the registry of temporary files removed on a signal
};

/// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the temporary files of every
/// uncommitted AtomicFile and then end the process by the same signal (its targets are then
/// untouched and nothing is left beside them). The CLI's main calls it once.
void removeTemporaryFilesOnSignals();

/// Writes `text` to `path` ("-": stdout) as one AtomicFile.
void writeFileAtomically(const std::string& path, std::string_view text, std::string what);

}  // namespace geaware::io
