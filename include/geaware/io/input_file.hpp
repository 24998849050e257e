// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading a whole input file (vehicle, truth, scenario, weights) before it is parsed, with the
// errors every reader gives the same way.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace geaware::io {

/// The largest whole-file input (vehicle, truth, scenario, weight and height-map files are
/// kilobytes; the YAML parser holds several copies of what it reads): a larger one is refused
/// before it is read.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{64} << 20;

/// The bytes of `file` (a regular file of at most kMaxInputFileBytes, every line under
/// kMaxLineBytes). Throws std::runtime_error naming the file: "<file>: no such <noun>",
/// "<file>: not a regular file (expected a <kind>)" or "<file>: cannot read <noun>", where
/// `noun` is e.g. "vehicle file" and `kind` "vehicle YAML file".
[[nodiscard]] std::string readInputFile(const std::filesystem::path& file, std::string_view noun,
                                        std::string_view kind);

/// The longest line any text input may hold: a longer one is refused (never read whole, never
/// echoed whole), which bounds the time and memory a file without newlines (/dev/zero, a binary
/// file given as a log) can cost.
inline constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;

/// The message for a line over kMaxLineBytes that begins with `start`, to follow "<file>:<line>: ":
/// "line longer than 1 MiB (starts '<at most 80 characters, non-printable ones as \xNN>…');
/// expected a text file with shorter lines".
[[nodiscard]] std::string lineTooLong(std::string_view start);

/// An input file this process has opened, and what it is (e.g. "vehicle file").
struct InputFileRead {
  std::filesystem::path path;
  std::string noun;
};
/// Records that `file` is read as an input (every reader of io calls it), so that an output
/// check can refuse to overwrite it even when it was named inside another file. Thread-safe.
void noteInputFile(const std::filesystem::path& file, std::string_view noun);
/// Every input file recorded so far, in the order read.
[[nodiscard]] std::vector<InputFileRead> inputFilesRead();

/// While it lives, lists every input file its thread records (noteInputFile), in the order read
/// and repeats included: the files a parse read, however deeply one file names another (a
/// sweep's scenario files, their height maps, vehicles and truths). Collectors nest: an inner
/// one's files are also the outer one's.
class InputFileCollector {
 public:
  InputFileCollector() noexcept;
  ~InputFileCollector();  ///< restores the thread's outer collector, if any
  InputFileCollector(const InputFileCollector&) = delete;
  InputFileCollector& operator=(const InputFileCollector&) = delete;
  [[nodiscard]] const std::vector<std::filesystem::path>& files() const noexcept { return files_; }

 private:
  friend void noteInputFile(const std::filesystem::path& file, std::string_view noun);
  InputFileCollector* outer_;
  std::vector<std::filesystem::path> files_;
};

}  // namespace geaware::io
