// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where a result came from: every JSON output, flight log and report carries the geaware version
// and commit it was made by, the command line, the seeds and the SHA-256 of every input file, so
// that a number found in a file can be traced to the run that made it.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/io/json.hpp"

namespace geaware::io {

/// The release, e.g. "0.1.0" (the CMake project version).
[[nodiscard]] std::string_view geawareVersion() noexcept;
/// The git commit the binary was built from ("unknown" outside a git checkout), with "-dirty"
/// when the work tree had uncommitted changes at build time.
[[nodiscard]] std::string_view geawareCommit() noexcept;

/// What a run was given.
struct RunInfo {
  std::string command_line;               ///< the whole command line, shell-quoted
  std::vector<std::uint64_t> seeds;       ///< every seed the run used
  std::vector<std::string> input_files;   ///< paths of every file the run read
};

/// {"geaware_version", "commit", "command_line", "seeds": [...], "inputs": [{"path", "sha256"}]}.
/// A listed input that cannot be read is given with "sha256": null.
[[nodiscard]] Json provenanceJson(const RunInfo& run);

/// The same facts as comment lines ("# geaware_version: ...") for text formats such as CSV logs.
[[nodiscard]] std::string provenanceComment(const RunInfo& run, std::string_view prefix = "# ");

/// `argv` joined into one line, each argument quoted for a POSIX shell where it needs it.
[[nodiscard]] std::string shellQuotedCommandLine(int argc, const char* const* argv);

/// SHA-256 of `bytes` as 64 lowercase hex digits (FIPS 180-4).
[[nodiscard]] std::string sha256Hex(std::span<const unsigned char> bytes);
/// SHA-256 of a file's contents, read in blocks; throws std::runtime_error naming the path when
/// it cannot be read.
[[nodiscard]] std::string fileSha256Hex(const std::string& path);

}  // namespace geaware::io
