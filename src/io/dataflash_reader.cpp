// SPDX-License-Identifier: BSD-3-Clause
// ArduPilot DataFlash (.bin) reader, written from the format as ArduPilot documents it
// (AP_Logger/LogStructure.h, "Format characters"). A log describes itself: every message is
// A3 95, a type id and the type's fields packed little-endian; FMT (id 128) defines a type
// (id, total length, name char[4], format char[16], column labels char[64]); FMTU gives each
// field of a type a unit id and a multiplier id, which UNIT (id → label) and MULT (id → factor)
// define. Format characters: b int8, B uint8, h int16, H uint16, i int32, I uint32, f float,
// d double, n char[4], N char[16], Z char[64], c int16·100, C uint16·100, e int32·100,
// E uint32·100, L int32 latitude/longitude [1e-7 deg], M uint8 flight mode, q int64, Q uint64,
// a int16[32].
//
// Scaling: a field's FMTU multiplier, when FMTU gives one ('-' and '?' give none), converts the
// stored integer to the unit (ATT's centidegree `c` fields carry 'B', 1e-2, and the unit 'd'):
// it replaces the ·100 (c C e E) or 1e-7 (L) the format character implies, which applies when
// FMTU says nothing. A multiplier below 1 divides by its reciprocal (1e-2 → ÷100), as
// pymavlink does, which is exact where the multiplication is not. Text fields (n N Z) are not
// channels; PARM messages become parameters, MSG messages logged text. A field whose FMTU unit
// is '#' (instance) splits the type into topic instances (IMU[0], IMU[1], …).
// Tested against a file built field by field from this description (no ArduPilot log is in the
// repository): tests/io/dataflash_reader_test.cpp.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "byte_source.hpp"
#include "geaware/io/log_channels.hpp"
#include "geaware/model/field_check.hpp"

namespace geaware::io {
namespace {

using detail::ByteSource;
using detail::load;

constexpr std::byte kHead1{0xa3};
constexpr std::byte kHead2{0x95};
constexpr unsigned kFmtId = 128;
constexpr std::size_t kFmtBytes = 89;
constexpr std::size_t kMaxDataFlashWarnings = 20;

struct FormatChar {
  FieldType type;
  std::size_t bytes;
  double scale;     // implied by the character (c C e E: 1/100, L: 1e-7)
  bool text;
};

bool formatChar(char c, FormatChar& out) {
  switch (c) {
    case 'b': out = {FieldType::kInt8, 1, 1.0, false}; return true;
    case 'B': case 'M': out = {FieldType::kUInt8, 1, 1.0, false}; return true;
    case 'h': out = {FieldType::kInt16, 2, 1.0, false}; return true;
    case 'H': out = {FieldType::kUInt16, 2, 1.0, false}; return true;
    case 'i': out = {FieldType::kInt32, 4, 1.0, false}; return true;
    case 'I': out = {FieldType::kUInt32, 4, 1.0, false}; return true;
    case 'f': out = {FieldType::kFloat, 4, 1.0, false}; return true;
    case 'd': out = {FieldType::kDouble, 8, 1.0, false}; return true;
    case 'n': out = {FieldType::kText, 4, 1.0, true}; return true;
    case 'N': out = {FieldType::kText, 16, 1.0, true}; return true;
    case 'Z': out = {FieldType::kText, 64, 1.0, true}; return true;
    case 'c': out = {FieldType::kInt16, 2, 0.01, false}; return true;
    case 'C': out = {FieldType::kUInt16, 2, 0.01, false}; return true;
    case 'e': out = {FieldType::kInt32, 4, 0.01, false}; return true;
    case 'E': out = {FieldType::kUInt32, 4, 0.01, false}; return true;
    case 'L': out = {FieldType::kInt32, 4, 1e-7, false}; return true;
    case 'q': out = {FieldType::kInt64, 8, 1.0, false}; return true;
    case 'Q': out = {FieldType::kUInt64, 8, 1.0, false}; return true;
    case 'a': out = {FieldType::kInt16, 64, 1.0, false}; return true;  // int16[32]
    default: return false;
  }
}

std::string cString(const std::byte* p, std::size_t n) {
  std::string s(reinterpret_cast<const char*>(p), n);
  if (const auto nul = s.find('\0'); nul != std::string::npos) s.resize(nul);
  return s;
}

struct Field {
  std::string label;
  char format = 0;
  std::size_t offset = 0;  // after the 3-byte header
  FormatChar fc{};
  int first_channel = -1;  // -1: a text field
};

struct MessageType {
  std::string name;
  std::size_t length = 0;  // whole message, header included
  std::string formats;
  std::vector<Field> fields;
  std::size_t topic = SIZE_MAX;  // SIZE_MAX: not decoded
  int time_field = -1;
  double time_scale = 1e-6;
  std::string unit_ids, mult_ids;  // from FMTU
};

class DataFlashParser {
 public:
  DataFlashParser(ByteSource& src, const LogReadOptions& options) : src_(src), options_(options) {
    log_.source = src.source();
    log_.format = "dataflash";
  }

  LogData run() {
    const std::byte* first = src_.peek(3);
    if (first == nullptr || first[0] != kHead1 || first[1] != kHead2 || static_cast<unsigned>(first[2]) != kFmtId) {
      src_.fail(0, "not a DataFlash log (expected an FMT message, bytes A3 95 80, at the start)");
    }
    std::uint64_t skipped = 0, skip_start = 0;
    while (src_.remaining() >= 3) {
      const std::uint64_t at = src_.offset();
      const std::byte* h = src_.peek(3);
      const auto id = static_cast<unsigned>(h[2]);
      const auto it = types_.find(id);
      if (h[0] != kHead1 || h[1] != kHead2 || (id != kFmtId && it == types_.end())) {
        if (skipped == 0) skip_start = at;
        // Junk: move to the next 0xA3 at once (a long run is scanned by memchr, not byte by byte).
        const std::size_t window = static_cast<std::size_t>(std::min<std::uint64_t>(src_.remaining(), 4096));
        const std::byte* w = src_.peek(window);
        const void* next = std::memchr(w + 1, 0xa3, window - 1);
        const std::size_t step = next == nullptr ? window - 1 : static_cast<std::size_t>(static_cast<const std::byte*>(next) - w);
        skipped += step;
        src_.skip(step);
        continue;
      }
      if (skipped > 0) {
        warn(skip_start, std::to_string(skipped) + " bytes that start no known message: skipped");
        skipped = 0;
      }
      const std::size_t length = id == kFmtId ? kFmtBytes : it->second.length;
      const std::byte* m = src_.take(length);
      if (m == nullptr) {
        warn(at, "the last message (" + (id == kFmtId ? std::string("FMT") : it->second.name) + ", " +
                     std::to_string(length) + " bytes) is cut off: the file ends " +
                     std::to_string(src_.remaining()) + " bytes into it; read up to there");
        src_.skip(src_.remaining());
        break;
      }
      if (id == kFmtId) {
        defineType(m + 3, at);
      } else {
        message(it->second, m + 3, at);
      }
    }
    if (skipped > 0) warn(skip_start, std::to_string(skipped) + " bytes at the end that start no message");
    if (src_.remaining() > 0 && src_.remaining() < 3) warn(src_.offset(), "a cut-off message header at the end");
    finish();
    if (dropped_warnings_ > 0) {
      log_.warnings.push_back(std::to_string(dropped_warnings_) + " more problems of the same kinds");
    }
    return std::move(log_);
  }

 private:
  ByteSource& src_;
  const LogReadOptions& options_;
  LogData log_;
  std::map<unsigned, MessageType> types_;
  std::map<char, std::string> units_;
  std::map<char, double> mults_;
  double last_time_s_ = 0.0;
  std::size_t dropped_warnings_ = 0;

  void warn(std::uint64_t at, const std::string& message) {
    if (log_.warnings.size() >= kMaxDataFlashWarnings) {
      ++dropped_warnings_;
      return;
    }
    log_.warnings.push_back("byte " + std::to_string(at) + ": " + message);
  }

  void defineType(const std::byte* p, std::uint64_t at) {
    const auto id = static_cast<unsigned>(p[0]);
    MessageType t;
    t.length = static_cast<std::size_t>(p[1]);
    t.name = cString(p + 2, 4);
    t.formats = cString(p + 6, 16);
    const std::string labels = cString(p + 22, 64);
    const std::string what = "FMT for '" + detail::printable(t.name) + "' (type " + std::to_string(id) + ")";
    if (id == kFmtId) {
      if (t.length != kFmtBytes || t.formats != "BBnNZ") {
        src_.fail(at, what + ": FMT must be 89 bytes 'BBnNZ', got " + std::to_string(t.length) + " bytes '" +
                          detail::printable(t.formats) + "'");
      }
      return;
    }
    std::vector<std::string> names;
    for (std::size_t pos = 0;;) {
      const auto comma = labels.find(',', pos);
      names.push_back(labels.substr(pos, comma == std::string::npos ? comma : comma - pos));
      if (comma == std::string::npos) break;
      pos = comma + 1;
    }
    if (t.formats.empty()) names.clear();
    if (names.size() != t.formats.size()) {
      src_.fail(at, what + ": " + std::to_string(t.formats.size()) + " format characters '" +
                        detail::printable(t.formats) + "' but " + std::to_string(names.size()) + " labels '" +
                        detail::printable(labels) + "'");
    }
    std::size_t offset = 0;
    for (std::size_t i = 0; i < names.size(); ++i) {
      Field f;
      f.label = names[i];
      f.format = t.formats[i];
      if (!formatChar(f.format, f.fc)) {
        src_.fail(at, what + ": unknown format character '" + detail::printable(std::string(1, f.format)) +
                          "' for '" + detail::printable(f.label) + "' (expected one of bBhHiIfdnNZcCeELMqQa)");
      }
      f.offset = offset;
      offset += f.fc.bytes;
      if ((f.label == "TimeUS" || f.label == "TimeMS") && !f.fc.text && f.format != 'a') {
        t.time_field = static_cast<int>(i);
        t.time_scale = f.label == "TimeUS" ? 1e-6 : 1e-3;
      }
      t.fields.push_back(std::move(f));
    }
    if (offset + 3 != t.length) {
      src_.fail(at, what + ": its format '" + t.formats + "' takes " + std::to_string(offset + 3) +
                        " bytes with the header, its length says " + std::to_string(t.length));
    }
    if (const auto old = types_.find(id); old != types_.end()) {
      if (old->second.name == t.name && old->second.formats == t.formats) return;  // repeated FMT
      warn(at, what + " redefines type " + std::to_string(id) + " ('" + old->second.name + "')");
    }
    if (options_.topics.empty() ||
        std::find(options_.topics.begin(), options_.topics.end(), t.name) != options_.topics.end()) {
      Topic topic;
      topic.name = t.name;
      for (auto& f : t.fields) {
        if (f.fc.text) continue;
        f.first_channel = static_cast<int>(topic.channels.size());
        const std::size_t n = f.format == 'a' ? 32 : 1;
        for (std::size_t k = 0; k < n; ++k) {
          Channel c;
          c.name = n == 1 ? f.label : f.label + "[" + std::to_string(k) + "]";
          c.type = f.fc.type;
          topic.channels.push_back(std::move(c));
        }
      }
      t.topic = log_.topics.size();
      log_.topics.push_back(std::move(topic));
    }
    types_[id] = std::move(t);
  }

  const Field* field(const MessageType& t, std::string_view label) const {
    for (const auto& f : t.fields) {
      if (f.label == label) return &f;
    }
    return nullptr;
  }

  void message(const MessageType& t, const std::byte* p, std::uint64_t at) {
    if (t.time_field >= 0) {
      const Field& f = t.fields[static_cast<std::size_t>(t.time_field)];
      last_time_s_ = detail::loadAsDouble(p + f.offset, f.fc.type) * t.time_scale;
    }
    metadata(t, p, at);
    if (t.topic == SIZE_MAX) return;
    Topic& topic = log_.topics[t.topic];
    topic.time_s.push_back(last_time_s_);
    for (const auto& f : t.fields) {
      if (f.first_channel < 0) continue;
      const std::size_t n = f.format == 'a' ? 32 : 1;
      for (std::size_t k = 0; k < n; ++k) {
        topic.channels[static_cast<std::size_t>(f.first_channel) + k].values.push_back(
            detail::loadAsDouble(p + f.offset + 2 * k, f.fc.type));
      }
    }
  }

  // FMTU, UNIT, MULT, PARM, MSG: what the log says about itself.
  void metadata(const MessageType& t, const std::byte* p, std::uint64_t at) {
    const auto text = [&](const char* label) -> std::string {
      const Field* f = field(t, label);
      return f != nullptr && f->fc.text ? cString(p + f->offset, f->fc.bytes) : std::string();
    };
    const auto number = [&](const char* label, double& out) {
      const Field* f = field(t, label);
      if (f == nullptr || f->fc.text || f->format == 'a') return false;
      out = detail::loadAsDouble(p + f->offset, f->fc.type);
      return true;
    };
    // A message id or a unit/multiplier letter is one byte; any other value (a corrupt or hostile
    // log can hold 8e18 or NaN there) names nothing, and converting it to an integer would be
    // undefined behaviour.
    const auto byteValue = [](double x) { return x >= 0.0 && x < 256.0 && std::floor(x) == x; };
    double v = 0.0;
    if (t.name == "FMTU" && number("FmtType", v)) {
      const auto it = byteValue(v) ? types_.find(static_cast<unsigned>(v)) : types_.end();
      if (it == types_.end()) {
        warn(at, "FMTU for type " + model::formatValue(v) + ", which no FMT defines");
        return;
      }
      it->second.unit_ids = text("UnitIds");
      it->second.mult_ids = text("MultIds");
    } else if (t.name == "UNIT" && number("Id", v)) {
      if (!byteValue(v)) return warn(at, "UNIT with id " + model::formatValue(v) + " (expected one character): ignored");
      units_[static_cast<char>(static_cast<unsigned char>(v))] = text("Label");
    } else if (t.name == "MULT" && number("Id", v)) {
      if (!byteValue(v)) return warn(at, "MULT with id " + model::formatValue(v) + " (expected one character): ignored");
      double m = 0.0;
      if (number("Mult", m)) mults_[static_cast<char>(static_cast<unsigned char>(v))] = m;
    } else if (t.name == "PARM" && number("Value", v)) {
      log_.parameters[text("Name")] = v;
    } else if (t.name == "MSG") {
      log_.messages.push_back({last_time_s_, 6, text("Message")});
    }
  }

  // Scales, units and instances once every FMTU, UNIT and MULT has been seen.
  void finish() {
    for (auto& [id, t] : types_) {
      if (t.topic == SIZE_MAX) continue;
      Topic& topic = log_.topics[t.topic];
      int instance_channel = -1;
      for (std::size_t i = 0; i < t.fields.size(); ++i) {
        const Field& f = t.fields[i];
        if (f.first_channel < 0) continue;
        const char unit_id = i < t.unit_ids.size() ? t.unit_ids[i] : '-';
        const char mult_id = i < t.mult_ids.size() ? t.mult_ids[i] : '-';
        double scale = f.fc.scale;
        if (mult_id != '-' && mult_id != '?') {
          if (const auto m = mults_.find(mult_id); m != mults_.end()) {
            scale = m->second;
          } else {
            warn(0, t.name + "." + f.label + ": multiplier id '" + detail::printable(std::string(1, mult_id)) +
                        "' that no MULT message defines: the format's scale is used");
          }
        }
        std::string unit;
        if (unit_id != '-' && unit_id != '?') {
          const auto u = units_.find(unit_id);
          unit = u != units_.end() ? u->second : std::string();
          if (unit_id == '#') instance_channel = f.first_channel;
        }
        const std::size_t n = f.format == 'a' ? 32 : 1;
        for (std::size_t k = 0; k < n; ++k) {
          Channel& c = topic.channels[static_cast<std::size_t>(f.first_channel) + k];
          c.unit = unit;
          applyScale(c.values, scale);
        }
      }
      if (instance_channel >= 0) splitInstances(topic, static_cast<std::size_t>(instance_channel));
    }
  }

  static void applyScale(std::vector<double>& values, double scale) {
    if (scale == 1.0) return;
    const double inverse = 1.0 / scale;
    if (scale > 0.0 && scale < 1.0 && std::abs(inverse - std::round(inverse)) < 1e-9 * inverse) {
      const double divisor = std::round(inverse);
      for (auto& v : values) v /= divisor;
    } else {
      for (auto& v : values) v *= scale;
    }
  }

  // Messages of one type whose instance field differs become separate topic instances.
  void splitInstances(Topic& topic, std::size_t channel) {
    const std::vector<double> ids = topic.channels[channel].values;
    if (std::any_of(ids.begin(), ids.end(), [](double v) { return std::isnan(v); })) {
      warn(0, topic.name + "." + topic.channels[channel].name + ": a NaN instance number: not split into instances");
      return;
    }
    std::vector<double> distinct = ids;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    if (distinct.size() <= 1) {
      topic.instance = distinct.size() == 1 && distinct[0] >= 0.0 && distinct[0] < 256.0 ? static_cast<unsigned>(distinct[0]) : 0u;
      return;
    }
    // ArduPilot numbers instances 0, 1, 2, …: anything else (or more than 16) is not split.
    constexpr std::size_t kMaxInstances = 16;
    const bool small = distinct.size() <= kMaxInstances &&
                       std::all_of(distinct.begin(), distinct.end(), [](double v) { return v >= 0.0 && v < 256.0 && std::floor(v) == v; });
    if (!small) {
      warn(0, topic.name + "." + topic.channels[channel].name + ": " + std::to_string(distinct.size()) +
                  " distinct instance numbers (expected at most 16 whole numbers in [0, 255]): not split into instances");
      return;
    }
    const Topic whole = std::move(topic);
    std::vector<Topic> parts;
    for (const double id : distinct) {
      Topic part;
      part.name = whole.name;
      part.instance = id >= 0.0 && id < 256.0 ? static_cast<unsigned>(id) : 0u;
      for (const auto& c : whole.channels) part.channels.push_back({c.name, c.unit, c.type, {}});
      for (std::size_t r = 0; r < ids.size(); ++r) {
        if (ids[r] != id) continue;
        part.time_s.push_back(whole.time_s[r]);
        for (std::size_t k = 0; k < whole.channels.size(); ++k) part.channels[k].values.push_back(whole.channels[k].values[r]);
      }
      parts.push_back(std::move(part));
    }
    topic = std::move(parts.front());
    for (std::size_t i = 1; i < parts.size(); ++i) log_.topics.push_back(std::move(parts[i]));
  }
};

}  // namespace

LogData readDataFlash(const std::filesystem::path& file, const LogReadOptions& options) {
  ByteSource src(file, options.max_bytes, "DataFlash log");
  return DataFlashParser(src, options).run();
}

LogData readDataFlash(std::span<const std::byte> bytes, const std::string& source, const LogReadOptions& options) {
  ByteSource src(bytes, source, options.max_bytes);
  return DataFlashParser(src, options).run();
}

}  // namespace geaware::io
