// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/csv_writer.hpp"

#include "geaware/io/output_file.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cerrno>
#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace geaware::io {
namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 18;
// Room for one cell: a separator and the longest shortest-round-trip double (24 characters).
constexpr std::size_t kCellReserve = 64;

}  // namespace

CsvWriter::CsvWriter(const std::filesystem::path& file, std::span<const std::string_view> columns)
    : name_(file.string()), atomic_(std::make_unique<AtomicFile>(file.string(), "the CSV file")), owned_(true) {
  file_ = atomic_->stream();
  writeHeader(columns);
}

CsvWriter::CsvWriter(std::FILE* stream, std::string name, std::span<const std::string_view> columns)
    : name_(std::move(name)), file_(stream), owned_(false) {
  if (file_ == nullptr) throw std::runtime_error(name_ + ": no stream to write to");
  writeHeader(columns);
}

CsvWriter::~CsvWriter() {
  if (file_ == nullptr || owned_) return;  // an owned, unclosed file is discarded by atomic_
  flush();
}

void CsvWriter::writeHeader(std::span<const std::string_view> columns) {
  columns_ = columns.size();
  std::string header;
  for (std::string_view c : columns) {
    if (!header.empty()) header += ',';
    header += c;
  }
  header += '\n';
  buffer_.resize(std::max(kBufferBytes, header.size() + kCellReserve));
  std::memcpy(buffer_.data(), header.data(), header.size());
  used_ = header.size();
}

void CsvWriter::flush() noexcept {
  if (used_ == 0 || file_ == nullptr) return;
  if (std::fwrite(buffer_.data(), 1, used_, file_) != used_ && !failed_) {
    failed_ = true;
    errno_ = errno;
  }
  used_ = 0;
}

char* CsvWriter::cell() noexcept {
  if (buffer_.size() - used_ < kCellReserve) flush();
  char* p = buffer_.data() + used_;
  if (cells_in_row_++ > 0) *p++ = ',';
  return p;
}

void CsvWriter::exact(double v) noexcept {
  if (file_ == nullptr) return;  // closed
  char* p = cell();
  used_ = static_cast<std::size_t>(fmt::format_to(p, FMT_COMPILE("{}"), v) - buffer_.data());
}

void CsvWriter::single(double v) noexcept {
  if (file_ == nullptr) return;
  char* p = cell();
  used_ = static_cast<std::size_t>(fmt::format_to(p, FMT_COMPILE("{}"), static_cast<float>(v)) -
                                   buffer_.data());
}

void CsvWriter::integer(std::uint64_t v) noexcept {
  if (file_ == nullptr) return;
  char* p = cell();
  used_ = static_cast<std::size_t>(fmt::format_to(p, FMT_COMPILE("{}"), v) - buffer_.data());
}

void CsvWriter::endRow() noexcept {
  if (file_ == nullptr) return;
  if (buffer_.size() - used_ < 1) flush();
  buffer_[used_++] = '\n';
  cells_in_row_ = 0;
  ++rows_;
}

void CsvWriter::close() {
  if (file_ == nullptr) {
    if (failed_) throw std::runtime_error(name_ + ": cannot write: " + std::strerror(errno_));
    return;
  }
  flush();
  std::FILE* stream = file_;
  file_ = nullptr;
  bool bad = failed_ || std::ferror(stream) != 0;
  if (bad && errno_ == 0) errno_ = errno != 0 ? errno : EIO;
  if (owned_) {
    if (bad) {
      throw std::runtime_error(name_ + ": cannot write: " + std::strerror(errno_) +
                               " (the existing file, if any, is unchanged)");
    }
    atomic_->commit();  // throws OutputError naming the file on a write, flush or rename failure
    return;
  }
  if (std::fflush(stream) != 0 && !failed_) errno_ = errno;
  if (bad || errno_ != 0) throw std::runtime_error(name_ + ": cannot write: " + std::strerror(errno_));
}

}  // namespace geaware::io
