// SPDX-License-Identifier: BSD-3-Clause
// Crazyflie uSD-card logs (the usd deck's log files), written from the format as the firmware
// writes it and its reference decoder reads it (bitcraze/crazyflie-firmware:
// src/deck/drivers/src/usddeck.c, tools/usdlog/cfusdlog.py and, for the older format,
// tools/usdlog/CF_functions.py). Two versions, both little-endian and packed:
//
// Event-based (current firmware): 0xBC, uint16 version (1 or 2), uint16 number of event types;
// per type uint16 id, its name NUL-terminated, uint16 number of variables, each variable
// "group.name(T)" NUL-terminated, T a Python struct code (b B h H i I f, e half float; q Q d
// accepted). Then events: uint16 id, a timestamp (version 1: uint32 ms; version 2: uint64 µs)
// and the type's variables. The last 4 bytes are the CRC-32 (zlib's) of all bytes before them.
//
// Fixed-frequency (older firmware): uint8 number of variables, then each "group.name(T),"
// (the first "tick(I)," the time in ms), then a CRC; then blocks: uint8 number of records, the
// records (all variables, packed), a CRC of the block's count and records. These CRCs are the
// CRC-32 register without its final inversion: the zlib CRC-32 of the bytes and the stored CRC
// together is 0xFFFFFFFF.
//
// Each event type (or the fixed-frequency records, as "fixedFrequency") is a topic; its time in
// seconds. A CRC that does not match, and a file cut inside an event or block, are warnings (the
// values read are kept, as the reference decoder keeps them); anything that breaks the framing
// before any data is an error naming the byte.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "byte_source.hpp"
#include "geaware/io/log_channels.hpp"

namespace geaware::io {
namespace {

using detail::ByteSource;
using detail::load;

constexpr std::size_t kMaxNameBytes = 1024;
constexpr std::size_t kMaxUsdWarnings = 20;
constexpr std::uint8_t kEventMagic = 0xBC;

// CRC-32 (reflected, polynomial 0xEDB88320, zlib's): update() on the register, value() with the
// final inversion.
class Crc32 {
 public:
  void update(const std::byte* p, std::size_t n) noexcept {
    static const std::array<std::uint32_t, 256> table = [] {
      std::array<std::uint32_t, 256> t{};
      for (std::uint32_t i = 0; i < 256; ++i) {
        std::uint32_t c = i;
        for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1) : c >> 1;
        t[i] = c;
      }
      return t;
    }();
    for (std::size_t i = 0; i < n; ++i) {
      reg_ = table[(reg_ ^ static_cast<std::uint32_t>(p[i])) & 0xffU] ^ (reg_ >> 8);
    }
  }
  [[nodiscard]] std::uint32_t value() const noexcept { return reg_ ^ 0xFFFFFFFFU; }
  [[nodiscard]] std::uint32_t registerValue() const noexcept { return reg_; }

 private:
  std::uint32_t reg_ = 0xFFFFFFFFU;
};

struct Variable {
  std::string name;
  FieldType type = FieldType::kFloat;
  std::size_t bytes = 4;
  bool half = false;  // 'e': IEEE half precision, stored as float
};

bool typeCode(char c, Variable& v) {
  switch (c) {
    case 'b':
      v.type = FieldType::kInt8, v.bytes = 1;
      return true;
    case 'B':
      v.type = FieldType::kUInt8, v.bytes = 1;
      return true;
    case 'h':
      v.type = FieldType::kInt16, v.bytes = 2;
      return true;
    case 'H':
      v.type = FieldType::kUInt16, v.bytes = 2;
      return true;
    case 'i':
      v.type = FieldType::kInt32, v.bytes = 4;
      return true;
    case 'I':
      v.type = FieldType::kUInt32, v.bytes = 4;
      return true;
    case 'q':
      v.type = FieldType::kInt64, v.bytes = 8;
      return true;
    case 'Q':
      v.type = FieldType::kUInt64, v.bytes = 8;
      return true;
    case 'f':
      v.type = FieldType::kFloat, v.bytes = 4;
      return true;
    case 'd':
      v.type = FieldType::kDouble, v.bytes = 8;
      return true;
    case 'e':
      v.type = FieldType::kFloat, v.bytes = 2, v.half = true;
      return true;
    default:
      return false;
  }
}

double halfToDouble(std::uint16_t h) {
  const int exponent = (h >> 10) & 0x1f;
  const double mantissa = h & 0x3ff;
  const double sign = (h & 0x8000) != 0 ? -1.0 : 1.0;
  if (exponent == 0) return sign * std::ldexp(mantissa, -24);
  if (exponent == 31) return mantissa == 0.0 ? sign * HUGE_VAL : std::nan("");
  return sign * std::ldexp(1024.0 + mantissa, exponent - 25);
}

struct Layout {
  std::string name;
  std::vector<Variable> variables;
  std::size_t bytes = 0;
  std::size_t topic = SIZE_MAX;  // index in LogData::topics; SIZE_MAX: not decoded
};

class UsdParser {
 public:
  UsdParser(ByteSource& src, const LogReadOptions& options) : src_(src), options_(options) {
    log_.source = src.source();
    log_.format = "crazyflie_usd";
  }

  LogData run() {
    const std::byte* head = src_.peek(3);
    if (head == nullptr)
      src_.fail(0, "too short for a Crazyflie uSD log (" + std::to_string(src_.size()) + " bytes)");
    const auto version = load<std::uint16_t>(head + 1);
    if (static_cast<std::uint8_t>(head[0]) == kEventMagic && (version == 1 || version == 2)) {
      events();
    } else {
      fixedFrequency();
    }
    if (dropped_ > 0)
      log_.warnings.push_back(std::to_string(dropped_) + " more problems of the same kinds");
    // Event types never logged are left out, as the reference decoder leaves them out.
    std::erase_if(log_.topics, [](const Topic& t) { return t.time_s.empty(); });
    return std::move(log_);
  }

 private:
  void warn(std::uint64_t at, const std::string& message) {
    if (log_.warnings.size() >= kMaxUsdWarnings) {
      ++dropped_;
      return;
    }
    log_.warnings.push_back("byte " + std::to_string(at) + ": " + message);
  }
  const std::byte* take(std::size_t n, const char* what) {
    const std::uint64_t at = src_.offset();
    const std::byte* p = src_.take(n);
    if (p == nullptr) src_.fail(at, std::string("the file ends inside ") + what);
    crc_.update(p, n);
    return p;
  }
  // A name ending at `end` (NUL or ','), at most kMaxNameBytes.
  std::string name(char end, const char* what) {
    const std::uint64_t at = src_.offset();
    std::string s;
    for (;;) {
      const char c = static_cast<char>(*take(1, what));
      if (c == end) return s;
      if (s.size() == kMaxNameBytes) src_.fail(at, std::string(what) + " longer than 1024 bytes");
      s += c;
    }
  }
  // "group.name(T)" → a variable.
  Variable variable(const std::string& text, std::uint64_t at) {
    Variable v;
    const std::size_t n = text.size();
    if (n < 4 || text[n - 3] != '(' || text[n - 1] != ')' || !typeCode(text[n - 2], v)) {
      src_.fail(at, "variable '" + detail::printable(text) +
                        "': expected NAME(T), T one of b B h H i I q Q f d e");
    }
    v.name = text.substr(0, n - 3);
    return v;
  }
  bool wanted(const std::string& topic) const {
    if (options_.topics.empty()) return true;
    return std::find(options_.topics.begin(), options_.topics.end(), topic) !=
           options_.topics.end();
  }
  void addTopic(Layout& l) {
    for (const auto& v : l.variables) l.bytes += v.bytes;
    if (!wanted(l.name)) return;
    Topic t;
    t.name = l.name;
    for (const auto& v : l.variables) t.channels.push_back({v.name, "", v.type, {}});
    l.topic = log_.topics.size();
    log_.topics.push_back(std::move(t));
  }
  void decode(const Layout& l, const std::byte* p, double time_s) {
    if (l.topic == SIZE_MAX) return;
    Topic& t = log_.topics[l.topic];
    t.time_s.push_back(time_s);
    for (std::size_t k = 0; k < l.variables.size(); ++k) {
      const Variable& v = l.variables[k];
      t.channels[k].values.push_back(v.half ? halfToDouble(load<std::uint16_t>(p))
                                            : detail::loadAsDouble(p, v.type));
      p += v.bytes;
    }
  }

  void events() {
    const std::byte* head = take(5, "the header");
    const auto version = load<std::uint16_t>(head + 1);
    const auto types = load<std::uint16_t>(head + 3);
    std::map<std::uint16_t, Layout> layouts;
    for (unsigned k = 0; k < types; ++k) {
      const std::uint64_t at = src_.offset();
      const auto id = load<std::uint16_t>(take(2, "an event type"));
      Layout l;
      l.name = name('\0', "an event type's name");
      const auto count = load<std::uint16_t>(take(2, "an event type"));
      for (unsigned v = 0; v < count; ++v) {
        const std::uint64_t vat = src_.offset();
        l.variables.push_back(variable(name('\0', "a variable's name"), vat));
      }
      if (layouts.count(id) != 0)
        src_.fail(at, "event type id " + std::to_string(id) + " defined twice");
      addTopic(l);
      layouts.emplace(id, std::move(l));
    }
    const std::size_t stamp = version == 1 ? 4 : 8;
    const double tick_s = version == 1 ? 1e-3 : 1e-6;
    const std::uint64_t end = src_.size() >= 4 ? src_.size() - 4 : 0;  // the CRC
    while (src_.offset() < end) {
      const std::uint64_t at = src_.offset();
      if (end - at < 2 + stamp) {
        warn(at, "the log ends inside an event's header (a cut file)");
        break;
      }
      const std::byte* h = src_.peek(2 + stamp);
      const auto id = load<std::uint16_t>(h);
      const auto it = layouts.find(id);
      if (it == layouts.end()) {
        warn(at, "unknown event type id " + std::to_string(id) + ": the " +
                     std::to_string(src_.size() - at) +
                     " bytes from here are not read (a damaged file)");
        break;
      }
      if (end - at < 2 + stamp + it->second.bytes) {
        warn(at, "the log ends inside a '" + it->second.name + "' event (a cut file)");
        break;
      }
      const std::byte* e = take(2 + stamp + it->second.bytes, "an event");
      const double t = version == 1 ? static_cast<double>(load<std::uint32_t>(e + 2)) * tick_s
                                    : static_cast<double>(load<std::uint64_t>(e + 2)) * tick_s;
      decode(it->second, e + 2 + stamp, t);
    }
    if (src_.offset() == end && src_.remaining() == 4) {
      const std::uint32_t computed = crc_.value();
      const auto stored = load<std::uint32_t>(src_.take(4));
      if (stored != computed) {
        warn(end, "CRC-32 of the bytes before it is " + hex(computed) + ", the file says " +
                      hex(stored) + ": the file is damaged or was cut; its values may be wrong");
      }
    } else {
      warn(src_.offset(), "no CRC read: the log does not end on an event");
    }
  }

  void fixedFrequency() {
    const std::byte* w = take(1, "the header");
    const unsigned width = static_cast<unsigned>(static_cast<std::uint8_t>(w[0]));
    if (width == 0)
      src_.fail(0,
                "not a Crazyflie uSD log: 0 variables (first byte 0; event logs start with 0xBC)");
    Layout l;
    l.name = "fixedFrequency";
    for (unsigned k = 0; k < width; ++k) {
      const std::uint64_t at = src_.offset();
      l.variables.push_back(variable(name(',', "a variable's name"), at));
    }
    const std::uint64_t crc_at = src_.offset();
    checkRegister(crc_at, "header");
    addTopic(l);
    std::size_t time_index = SIZE_MAX;
    for (std::size_t k = 0; k < l.variables.size(); ++k) {
      if (l.variables[k].name == "tick") time_index = k;
    }
    if (time_index == SIZE_MAX)
      warn(crc_at, "no 'tick' variable: the record number stands for the time [s]");
    std::size_t record = 0;
    while (src_.remaining() > 0) {
      const std::uint64_t at = src_.offset();
      crc_ = Crc32();
      const unsigned n = static_cast<unsigned>(static_cast<std::uint8_t>(*take(1, "a block")));
      if (src_.remaining() < static_cast<std::uint64_t>(n) * l.bytes + 4) {
        const auto whole = static_cast<unsigned>(src_.remaining() / l.bytes);
        warn(at, "the log ends inside a block of " + std::to_string(n) + " records (a cut file): " +
                     std::to_string(std::min(whole, n)) + " whole records read, unchecked");
        for (unsigned k = 0; k < std::min(whole, n); ++k)
          record = fixedRecord(l, time_index, record);
        break;
      }
      for (unsigned k = 0; k < n; ++k) record = fixedRecord(l, time_index, record);
      checkRegister(src_.offset(), "block at byte " + std::to_string(at));
    }
  }
  std::size_t fixedRecord(const Layout& l, std::size_t time_index, std::size_t record) {
    const std::byte* p = take(l.bytes, "a record");
    double t = static_cast<double>(record);
    if (time_index != SIZE_MAX) {
      const std::byte* q = p;
      for (std::size_t k = 0; k < time_index; ++k) q += l.variables[k].bytes;
      t = detail::loadAsDouble(q, l.variables[time_index].type) * 1e-3;
    }
    decode(l, p, t);
    return record + 1;
  }
  // The stored CRC of the fixed-frequency format: the register without its final inversion.
  void checkRegister(std::uint64_t at, const std::string& what) {
    const std::uint32_t expected = crc_.registerValue();
    const std::byte* p = src_.take(4);
    if (p == nullptr) {
      warn(at, "the log ends before the " + what + "'s CRC (a cut file)");
      return;
    }
    const auto stored = load<std::uint32_t>(p);
    if (stored != expected) {
      warn(at, "the " + what + "'s CRC is " + hex(stored) + ", its bytes give " + hex(expected) +
                   ": damaged; its values may be wrong");
    }
  }
  static std::string hex(std::uint32_t v) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%08x", v);
    return text;
  }

  ByteSource& src_;
  const LogReadOptions& options_;
  LogData log_;
  Crc32 crc_;
  std::size_t dropped_ = 0;
};

}  // namespace

bool looksLikeCrazyflieUsd(std::span<const std::byte> head) noexcept {
  if (head.size() >= 3 && static_cast<std::uint8_t>(head[0]) == kEventMagic) {
    const auto version = load<std::uint16_t>(head.data() + 1);
    if (version == 1 || version == 2) return true;
  }
  // Fixed-frequency: a variable count, then "name(T)," entries (as many as fit in `head`).
  if (head.empty() || head[0] == std::byte{0}) return false;
  const unsigned width = static_cast<unsigned>(static_cast<std::uint8_t>(head[0]));
  unsigned seen = 0;
  std::size_t start = 1;
  for (std::size_t i = 1; i < head.size() && seen < width; ++i) {
    const char c = static_cast<char>(head[i]);
    if (c != ',') {
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f)
        return false;
      continue;
    }
    const std::size_t n = i - start;
    Variable v;
    if (n < 4 || static_cast<char>(head[i - 3]) != '(' || static_cast<char>(head[i - 1]) != ')' ||
        !typeCode(static_cast<char>(head[i - 2]), v)) {
      return false;
    }
    ++seen, start = i + 1;
  }
  return seen > 0;
}

LogData readCrazyflieUsd(const std::filesystem::path& file, const LogReadOptions& options) {
  ByteSource src(file, options.max_bytes, "Crazyflie uSD log");
  return UsdParser(src, options).run();
}

LogData readCrazyflieUsd(std::span<const std::byte> bytes, const std::string& source,
                         const LogReadOptions& options) {
  ByteSource src(bytes, source, options.max_bytes);
  return UsdParser(src, options).run();
}

}  // namespace geaware::io
