// SPDX-License-Identifier: BSD-3-Clause
// The layout of v5/v7 .mat files (src/io/mat_layout.hpp), walked by geaware before libmatio
// reads a file: MATLAB's "MAT-File Format" (a 128-byte header, then data elements, each a tag and
// its bytes; matrices hold elements; compressed elements hold a zlib stream of one element).

#include "mat_layout.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <string_view>

#include "geaware/io/log_channels.hpp"

namespace geaware::io::detail {
namespace {

// A v5/v7 file's data elements, walked before libmatio reads it: libmatio reads a cut file's
// last struct with the fields it still finds and says nothing, and allocates what an inner
// element's header says (a hostile size asks for gigabytes). Each element is a tag (uint32 type,
// uint32 bytes; a small element packs both in 8 bytes) and its bytes, padded to 8 (compressed
// elements are not padded); a matrix (type 14) holds elements, each of which must fit in it; a
// compressed element (type 15) is inflated as it is walked (at most max_bytes), never held.
class ElementSource {
 public:
  virtual ~ElementSource() = default;
  virtual bool read(unsigned char* p, std::size_t n) = 0;  // false at the end
  virtual bool skip(std::uintmax_t n) = 0;
  /// Whether the last read failed only because a compressed stream ended cleanly before it (a
  /// compressed matrix may declare more bytes than it holds: libmatio writes char arrays so).
  [[nodiscard]] virtual bool endedCleanly() const noexcept { return false; }
};

class FileSource final : public ElementSource {
 public:
  explicit FileSource(std::ifstream& in) : in_(in) {}
  bool read(unsigned char* p, std::size_t n) override {
    in_.read(reinterpret_cast<char*>(p), static_cast<std::streamsize>(n));
    return static_cast<bool>(in_);
  }
  bool skip(std::uintmax_t n) override {
    in_.seekg(static_cast<std::streamoff>(n), std::ios::cur);
    return static_cast<bool>(in_);
  }

 private:
  std::ifstream& in_;
};

// The inflated bytes of `compressed` bytes of `in` (zlib), at most `limit` of them.
class InflateSource final : public ElementSource {
 public:
  InflateSource(std::ifstream& in, std::uintmax_t compressed, std::uintmax_t limit)
      : in_(in), left_(compressed), limit_(limit) {
    ok_ = inflateInit(&z_) == Z_OK;
  }
  ~InflateSource() override { inflateEnd(&z_); }
  InflateSource(const InflateSource&) = delete;
  InflateSource& operator=(const InflateSource&) = delete;
  bool read(unsigned char* p, std::size_t n) override { return produce(p, n); }
  bool skip(std::uintmax_t n) override {
    unsigned char sink[4096];
    while (n > 0) {
      const std::size_t k = static_cast<std::size_t>(std::min<std::uintmax_t>(n, sizeof sink));
      if (!produce(sink, k)) return false;
      n -= k;
    }
    return true;
  }
  [[nodiscard]] bool overLimit() const noexcept { return produced_ > limit_; }
  [[nodiscard]] std::uintmax_t produced() const noexcept { return produced_; }
  [[nodiscard]] bool endedCleanly() const noexcept override { return clean_end_; }

 private:
  bool produce(unsigned char* p, std::size_t n) {
    if (!ok_) return false;
    z_.next_out = p;
    z_.avail_out = static_cast<uInt>(n);
    while (z_.avail_out > 0) {
      if (z_.avail_in == 0 && left_ > 0) {
        const std::size_t k =
            static_cast<std::size_t>(std::min<std::uintmax_t>(left_, sizeof buffer_));
        in_.read(reinterpret_cast<char*>(buffer_), static_cast<std::streamsize>(k));
        if (!in_) return false;
        left_ -= k;
        z_.next_in = buffer_;
        z_.avail_in = static_cast<uInt>(k);
      }
      const uInt before = z_.avail_out;
      const int r = inflate(&z_, Z_NO_FLUSH);
      produced_ += before - z_.avail_out;
      if (produced_ > limit_) return false;
      if (r == Z_STREAM_END) {
        clean_end_ = z_.avail_out == n;  // nothing of this read was left
        return z_.avail_out == 0;
      }
      if (r != Z_OK || (before == z_.avail_out && z_.avail_in == 0 && left_ == 0)) return false;
    }
    return true;
  }

  std::ifstream& in_;
  std::uintmax_t left_;
  std::uintmax_t limit_;
  std::uintmax_t produced_ = 0;
  bool clean_end_ = false;
  z_stream z_{};
  unsigned char buffer_[16384];
  bool ok_ = false;
};

class V5Layout {
 public:
  V5Layout(const std::filesystem::path& file, std::uintmax_t size, std::uintmax_t limit)
      : file_(file), in_(file, std::ios::binary), size_(size), limit_(limit) {}

  /// The bytes of the variables' elements (compressed ones inflated): every stored number takes
  /// at least one, so no variable holds more numbers. 0 for a v7.3 (HDF5) file, not walked.
  std::uintmax_t check() {
    char header[128] = {};
    in_.read(header, sizeof header);
    if (!in_) {
      throw LogError(file_.string(), "not a MATLAB .mat file libmatio can open (v5, v7 or v7.3 expected): " +
                                         std::to_string(size_) + " bytes, shorter than the 128-byte header");
    }
    // libmatio decides the format as here (mat.c, Mat_Open): the endian indicator (bytes 126–127,
    // "IM" or "MI") and the version field (bytes 124–125: 0x0100 v5/v7, 0x0200 v7.3), never the
    // header's text. Anything else it reads as a MATLAB v4 file, whose headers (name length,
    // rows × columns) it allocates by unchecked: refused here, geaware does not read v4 files.
    // (fuzz_mat: a "MATLAB 7.3" text over a v5 version field skipped this walk, and libmatio
    // then allocated 4 GiB from an unchecked element.)
    const auto byte = [&](int i) { return static_cast<unsigned>(static_cast<unsigned char>(header[i])); };
    if (!((byte(126) == 'I' && byte(127) == 'M') || (byte(126) == 'M' && byte(127) == 'I'))) {
      fail(126, "the header's endian indicator is " + hex(byte(126) << 8 | byte(127)) +
                    ", expected 'IM' or 'MI' (a v5, v7 or v7.3 .mat file; MATLAB v4 files are not read)");
    }
    swap_ = byte(126) == 'M';
    const unsigned version = swap_ ? byte(124) << 8 | byte(125) : byte(125) << 8 | byte(124);
    if (version == 0x0200) return 0;  // v7.3: HDF5, opened by libhdf5
    if (version != 0x0100) {
      fail(124, "the header's version field is " + hex(version) +
                    ", expected 0x0100 (v5, v7) or 0x0200 (v7.3) (MATLAB v4 files are not read)");
    }
    std::uintmax_t walked = size_;
    std::uintmax_t at = 128;
    while (at < size_) {
      unsigned char tag[8];
      in_.seekg(static_cast<std::streamoff>(at));
      if (size_ - at < 8 || !in_.read(reinterpret_cast<char*>(tag), 8)) {
        fail(at, "the .mat file ends inside a variable's tag (a cut or damaged file)");
      }
      const std::uint32_t type = u32(tag), bytes = u32(tag + 4);
      const std::uintmax_t next = at + 8 +
                                  ((type >> 16) != 0 ? 0
                                   : type == 15      ? bytes
                                                : (static_cast<std::uintmax_t>(bytes) + 7) / 8 * 8);
      if ((type >> 16) == 0 && (type == 0 || type > 18)) {
        fail(at, "not a .mat data element (type " + std::to_string(type) + ")");
      }
      if (next > size_) {
        fail(at, "a variable of " + std::to_string(next - at) +
                     " bytes runs past the file's end at byte " + std::to_string(size_) +
                     ": a cut or damaged .mat file");
      }
      if (type == 14) {
        FileSource src(in_);
        walk(src, bytes, 1, at);
      } else if (type == 15) {
        InflateSource src(in_, bytes, limit_);
        unsigned char inner[8];
        if (!src.read(inner, 8))
          fail(at, "a compressed variable that does not inflate to a whole element");
        const std::uint32_t inner_type = u32(inner), inner_bytes = u32(inner + 4);
        try {
          if (inner_type == 14) walk(src, inner_bytes, 1, at);
          walked += src.produced();
        } catch (const LogError&) {
          if (!src.overLimit()) throw;
        }
        if (src.overLimit()) {
          fail(at, "a compressed variable that inflates to more than " + std::to_string(limit_) +
                       " bytes (the most a log may have)");
        }
      }
      at = next;
    }
    return walked;
  }

 private:
  std::uint32_t u32(const unsigned char* p) const {
    const std::uint32_t v =
        static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
        static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
    return swap_ ? __builtin_bswap32(v) : v;
  }
  static std::string hex(unsigned v) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%04x", v);
    return text;
  }
  [[noreturn]] void fail(std::uintmax_t at, const std::string& message) const {
    throw LogError(file_.string(), at, message);
  }
  // The `length` bytes of a matrix's elements from `src`; `at`: the variable's byte, for messages.
  void walk(ElementSource& src, std::uintmax_t length, int depth, std::uintmax_t at) {
    if (depth > 16) fail(at, "variables nested deeper than 16");
    std::uintmax_t pos = 0;
    bool sparse = false;
    std::uint32_t cls = 0, name_length = 0;
    std::uintmax_t elements = 1;
    for (int element = 0; pos < length; ++element) {
      unsigned char tag[8];
      if (length - pos < 8 || !src.read(tag, 8)) {
        if (src.endedCleanly()) return;
        fail(at, "an element inside this variable runs past its end (a cut or damaged .mat file)");
      }
      pos += 8;
      const std::uint32_t type = u32(tag), bytes = u32(tag + 4);
      // libmatio reads a matrix's first two elements by position, as the array flags and the
      // dimensions, and then its name tag right after the dimensions it understood: with any
      // other type there, it and this walk disagree on where the name is (fuzz_mat: a dimensions
      // element of type 8 made libmatio take the next 8 bytes as a name tag of 1.4 GB).
      // A type MAT-File Format does not define: libmatio reads such an element's bytes as it
      // guesses, and then the tags that follow from where it stopped, not where this walk does
      // (fuzz_mat: a sparse matrix's index element of type 101 made libmatio take doubles for a
      // tag of 1 GB).
      const std::uint32_t data_type = (type >> 16) != 0 ? type & 0xffffU : type;
      if (data_type == 0 || data_type == 8 || data_type == 10 || data_type == 11 || data_type > 18) {
        fail(at, "an element of type " + std::to_string(data_type) + " inside this variable, expected a MAT-File data "
                 "type (1–7, 9, 12–18): a damaged .mat file");
      }
      const bool too_long = (type >> 16) == 0 && bytes > length - pos;  // failed below, by its size
      if (element == 0 && (type != 6 || bytes != 8) && !too_long) {
        fail(at, "a matrix whose first element (its array flags) has type " + std::to_string(type & 0xffffU) +
                     " of " + std::to_string((type >> 16) != 0 ? type >> 16 : bytes) +
                     " bytes, expected type 6 (miUINT32) of 8 bytes: a damaged .mat file");
      }
      if (element == 1 && type != 5) {
        fail(at, "a matrix whose second element (its dimensions) has type " + std::to_string(type & 0xffffU) +
                     ((type >> 16) != 0 ? " in a small element" : "") +
                     ", expected type 5 (miINT32) in a full tag: a damaged .mat file");
      }
      if ((type >> 16) != 0) {  // a small element: its data was in the 8 bytes read
        if (element == 3 && (cls == 2 || cls == 3))
          name_length = u32(tag + 4);  // a struct's field-name length
        continue;
      }
      if (element == 0 && !too_long) {  // the array flags (type 6, 8 bytes): the class in the low byte
        unsigned char flags[8];
        if (!src.read(flags, 8)) fail(at, "the variable ends inside its flags");
        cls = u32(flags) & 0xffU;
        sparse = cls == 5;  // mxSPARSE_CLASS: dims are not its storage
        pos += 8;
        continue;
      }
      // libmatio reads bytes/4 dimensions, then the name tag right after them (4 more bytes
      // skipped for an odd count): dimensions of 2 bytes made it read a name tag of 2.9 GB from
      // bytes this walk skipped as padding (fuzz_mat). MAT-File Format writes at least two.
      if (element == 1 && !too_long && (bytes < 8 || bytes % 4 != 0)) {
        fail(at, "a matrix whose dimensions element has " + std::to_string(bytes) +
                     " bytes, expected two or more int32 (a multiple of 4 bytes, at least 8): a damaged .mat file");
      }
      if (element == 1 && !sparse && !too_long) {  // the dimensions (type 5), read before libmatio allocates by them
        if (bytes > 4 * 32) fail(at, "a variable of more than 32 dimensions");
        unsigned char dims[4 * 32];
        if (!src.read(dims, bytes)) fail(at, "the variable ends inside its dimensions");
        elements = checkDims(dims, bytes / 4, length, at);
        const std::uintmax_t rest =
            std::min((static_cast<std::uintmax_t>(bytes) + 7) / 8 * 8, length - pos) - bytes;
        if (!src.skip(rest)) fail(at, "the variable ends inside its dimensions");
        pos += bytes + rest;
        continue;
      }
      if (element == 4 &&
          (cls == 2 || cls == 3)) {  // a struct's field names: fields × elements matrices follow
        if (name_length == 0) fail(at, "a struct whose field names have length 0");
        const std::uintmax_t fields = bytes / name_length;
        if (fields != 0 && elements > length / 8 / fields) {
          fail(at, "a struct of " + std::to_string(elements) + " elements × " +
                       std::to_string(fields) + " fields in " + std::to_string(length) +
                       " bytes: a damaged .mat file");
        }
      }
      const std::uintmax_t padded = (static_cast<std::uintmax_t>(bytes) + 7) / 8 * 8;
      if (bytes > length - pos) {
        fail(at, "an element of " + std::to_string(bytes) +
                     " bytes inside this variable runs past its end (" +
                     std::to_string(length - pos) + " bytes left): a damaged .mat file");
      }
      if (type == 14) {
        walk(src, bytes, depth + 1, at);
        if (!src.skip(std::min(padded, length - pos) - bytes) && !src.endedCleanly()) {
          fail(at, "the variable ends inside an element");
        }
      } else if (!src.skip(std::min(padded, length - pos))) {
        if (src.endedCleanly()) return;
        fail(at, "the variable ends inside an element");
      }
      pos += std::min(padded, length - pos);
    }
  }

  // The product of `n` int32 dimensions: at most limit_ / 8 elements, and at most the matrix's
  // `length` in bytes (every element stores at least one byte; a struct array's or cell's
  // elements are allocated by the product before any is read).
  std::uintmax_t checkDims(const unsigned char* p, std::uint32_t n, std::uintmax_t length,
                           std::uintmax_t at) const {
    std::uintmax_t product = 1;
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t d = u32(p + 4 * k);
      if (d != 0 && product > limit_ / 8 / d) {
        fail(at, "a variable whose dimensions claim more than " + std::to_string(limit_ / 8) +
                     " elements (doubles in the bytes a log may have): refused before reading");
      }
      product *= d;
    }
    if (product > length) {
      fail(at, "a variable whose dimensions claim " + std::to_string(product) + " elements in " +
                   std::to_string(length) + " bytes: a damaged .mat file");
    }
    return product;
  }

  std::filesystem::path file_;
  std::ifstream in_;
  std::uintmax_t size_;
  std::uintmax_t limit_;
  bool swap_ = false;
};

}  // namespace

std::uintmax_t checkMatLayout(const std::filesystem::path& file, std::uintmax_t size,
                              std::uintmax_t limit) {
  return V5Layout(file, size, limit).check();
}

}  // namespace geaware::io::detail
