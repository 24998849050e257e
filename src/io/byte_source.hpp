// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Private to io/: the bytes of a binary log, streamed from a file through one bounded buffer
// or taken from memory, with the byte offset every error names.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "geaware/io/log_channels.hpp"

namespace geaware::io::detail {

class ByteSource {
 public:
  /// Opens `file` (a regular file of at most `max_bytes`; noted as an input). Throws LogError
  /// naming the file: no such file, not a regular file, too large, cannot open.
  ByteSource(const std::filesystem::path& file, std::uintmax_t max_bytes, const std::string& noun);
  /// Reads from memory (not copied: `bytes` must outlive the source).
  ByteSource(std::span<const std::byte> bytes, std::string source, std::uintmax_t max_bytes);
  ~ByteSource();
  ByteSource(const ByteSource&) = delete;
  ByteSource& operator=(const ByteSource&) = delete;

  /// The next `n` bytes without consuming them, or nullptr when fewer remain. Valid until the
  /// next call.
  [[nodiscard]] const std::byte* peek(std::size_t n);
  /// The next `n` bytes, consumed; nullptr (nothing consumed) when fewer remain.
  [[nodiscard]] const std::byte* take(std::size_t n) {
    const std::byte* p = peek(n);
    if (p != nullptr) pos_ += n;
    return p;
  }
  /// Skips up to `n` bytes (fewer at the end).
  void skip(std::uint64_t n);
  /// Moves to the absolute offset `offset` (forward only in a file; at most the size).
  void seekForward(std::uint64_t offset);
  [[nodiscard]] std::uint64_t offset() const noexcept { return pos_; }
  [[nodiscard]] std::uint64_t size() const noexcept { return size_; }
  [[nodiscard]] std::uint64_t remaining() const noexcept { return size_ - pos_; }
  [[nodiscard]] const std::string& source() const noexcept { return source_; }

  [[noreturn]] void fail(std::uint64_t at, const std::string& message) const {
    throw LogError(source_, at, message);
  }

 private:
  std::string source_;
  std::FILE* file_ = nullptr;
  std::span<const std::byte> memory_;
  std::vector<std::byte> buffer_;
  std::uint64_t buffer_start_ = 0;  // file offset of buffer_[0]
  std::size_t buffer_fill_ = 0;
  std::uint64_t pos_ = 0;
  std::uint64_t size_ = 0;
};

/// Little-endian loads from unaligned bytes.
template <typename T>
[[nodiscard]] inline T load(const std::byte* p) noexcept {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Appends `p[0 .. size)` of `type` as a double to `out`.
double loadAsDouble(const std::byte* p, FieldType type) noexcept;

/// `text` with non-printable bytes as \xNN, at most 80 characters.
[[nodiscard]] std::string printable(std::string_view text);

}  // namespace geaware::io::detail
