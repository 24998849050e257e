// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/log_channels.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>

#include "byte_source.hpp"
#include "geaware/io/input_file.hpp"

namespace geaware::io {

static_assert(std::endian::native == std::endian::little,
              "the log readers load little-endian fields with memcpy");

LogError::LogError(std::string file, std::uint64_t offset, const std::string& message)
    : std::runtime_error(file + ": byte " + std::to_string(offset) + ": " + message),
      file_(std::move(file)),
      offset_(offset),
      has_offset_(true) {}

LogError::LogError(std::string file, const std::string& message)
    : std::runtime_error(file + ": " + message), file_(std::move(file)) {}

std::string_view fieldTypeName(FieldType type) noexcept {
  switch (type) {
    case FieldType::kInt8: return "int8_t";
    case FieldType::kUInt8: return "uint8_t";
    case FieldType::kInt16: return "int16_t";
    case FieldType::kUInt16: return "uint16_t";
    case FieldType::kInt32: return "int32_t";
    case FieldType::kUInt32: return "uint32_t";
    case FieldType::kInt64: return "int64_t";
    case FieldType::kUInt64: return "uint64_t";
    case FieldType::kFloat: return "float";
    case FieldType::kDouble: return "double";
    case FieldType::kBool: return "bool";
    case FieldType::kChar: return "char";
    case FieldType::kText: return "text";
  }
  return "?";
}

std::size_t fieldTypeBytes(FieldType type) noexcept {
  switch (type) {
    case FieldType::kInt8: case FieldType::kUInt8: case FieldType::kBool: case FieldType::kChar: return 1;
    case FieldType::kInt16: case FieldType::kUInt16: return 2;
    case FieldType::kInt32: case FieldType::kUInt32: case FieldType::kFloat: return 4;
    case FieldType::kInt64: case FieldType::kUInt64: case FieldType::kDouble: return 8;
    case FieldType::kText: return 0;
  }
  return 0;
}

const Channel* Topic::channel(std::string_view wanted) const noexcept {
  for (const auto& c : channels) {
    if (c.name == wanted) return &c;
  }
  return nullptr;
}

const Topic* LogData::topic(std::string_view wanted, unsigned instance) const noexcept {
  for (const auto& t : topics) {
    if (t.name == wanted && t.instance == instance) return &t;
  }
  return nullptr;
}

namespace detail {

namespace {
constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

std::string sizeText(std::uintmax_t bytes) {
  if (bytes % (std::uintmax_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}
}  // namespace

ByteSource::ByteSource(const std::filesystem::path& file, std::uintmax_t max_bytes, const std::string& noun)
    : source_(file.string()) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw LogError(source_, std::filesystem::exists(file, ec)
                                ? "not a regular file (expected a " + noun + ")"
                                : "no such " + noun);
  }
  noteInputFile(file, noun);
  const std::uintmax_t bytes = std::filesystem::file_size(file, ec);
  if (ec) throw LogError(source_, "cannot read the size of the " + noun + ": " + ec.message());
  if (bytes > max_bytes) {
    throw LogError(source_, std::to_string(bytes) + " bytes, larger than a " + noun + " may be (at most " +
                                sizeText(max_bytes) + "); refused unread");
  }
  file_ = std::fopen(file.c_str(), "rb");
  if (file_ == nullptr) throw LogError(source_, std::string("cannot open: ") + std::strerror(errno));
  size_ = bytes;
  buffer_.resize(kBufferBytes);
}

ByteSource::ByteSource(std::span<const std::byte> bytes, std::string source, std::uintmax_t max_bytes)
    : source_(std::move(source)), memory_(bytes), size_(bytes.size()) {
  if (bytes.size() > max_bytes) {
    throw LogError(source_, std::to_string(bytes.size()) + " bytes, larger than a log may be (at most " +
                                sizeText(max_bytes) + "); refused unread");
  }
}

ByteSource::~ByteSource() {
  if (file_ != nullptr) std::fclose(file_);
}

const std::byte* ByteSource::peek(std::size_t n) {
  if (n > remaining()) return nullptr;
  if (file_ == nullptr) return memory_.data() + pos_;
  const std::uint64_t end = pos_ + n;
  if (pos_ >= buffer_start_ && end <= buffer_start_ + buffer_fill_) {
    return buffer_.data() + (pos_ - buffer_start_);
  }
  // Refill from pos_: keep the unread tail of the buffer, read the rest.
  std::size_t keep = 0;
  if (pos_ >= buffer_start_ && pos_ < buffer_start_ + buffer_fill_) {
    keep = static_cast<std::size_t>(buffer_start_ + buffer_fill_ - pos_);
    std::memmove(buffer_.data(), buffer_.data() + (pos_ - buffer_start_), keep);
  } else if (fseeko(file_, static_cast<off_t>(pos_), SEEK_SET) != 0) {
    fail(pos_, "cannot seek");
  }
  if (n > buffer_.size()) buffer_.resize(n);
  buffer_start_ = pos_;
  buffer_fill_ = keep;
  while (buffer_fill_ < n) {
    const std::size_t got = std::fread(buffer_.data() + buffer_fill_, 1, buffer_.size() - buffer_fill_, file_);
    if (got == 0) {
      fail(buffer_start_ + buffer_fill_, std::ferror(file_) != 0 ? "read error" : "the file shrank while it was read");
    }
    buffer_fill_ += got;
  }
  return buffer_.data();
}

void ByteSource::skip(std::uint64_t n) { pos_ += std::min<std::uint64_t>(n, remaining()); }

void ByteSource::seekForward(std::uint64_t offset) {
  if (offset > pos_) pos_ = std::min(offset, size_);
}

double loadAsDouble(const std::byte* p, FieldType type) noexcept {
  switch (type) {
    case FieldType::kInt8: return load<std::int8_t>(p);
    case FieldType::kUInt8: case FieldType::kBool: return load<std::uint8_t>(p);
    case FieldType::kChar: return static_cast<unsigned char>(load<char>(p));
    case FieldType::kInt16: return load<std::int16_t>(p);
    case FieldType::kUInt16: return load<std::uint16_t>(p);
    case FieldType::kInt32: return load<std::int32_t>(p);
    case FieldType::kUInt32: return load<std::uint32_t>(p);
    case FieldType::kInt64: return static_cast<double>(load<std::int64_t>(p));
    case FieldType::kUInt64: return static_cast<double>(load<std::uint64_t>(p));
    case FieldType::kFloat: return load<float>(p);
    case FieldType::kDouble: return load<double>(p);
    case FieldType::kText: return 0.0;
  }
  return 0.0;
}

std::string printable(std::string_view text) {
  constexpr std::size_t kEcho = 80;
  std::string out;
  for (const char c : text.substr(0, kEcho)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out += c;
    } else {
      constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 0xf];
    }
  }
  if (text.size() > kEcho) out += "…";
  return out;
}

}  // namespace detail
}  // namespace geaware::io
