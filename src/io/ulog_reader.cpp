// SPDX-License-Identifier: BSD-3-Clause
// PX4 ULog reader (https://docs.px4.io/main/en/dev_log/ulog_file_format.html), written from the
// format's specification; its output is checked value for value against what PX4's own reader
// (pyulog) reads from two real logs (tests/io/ulog_reader_test.cpp).
//
// File: a 16-byte header ("ULog" 01 12 35, version, uint64 start time [µs]), then messages of
// {uint16 size, uint8 type, payload[size]}. Definitions: B flag bits (first), F formats
// ("name:type field;…", nested types and arrays), I/M info, P/Q parameters. Data: A subscribes a
// topic instance (multi_id) to a message id, R removes it, D carries one sample (packed fields,
// a uint64 `timestamp` [µs] among them, trailing padding not written), L/C logged text, O a
// dropout, S a sync marker. As pyulog does, nested fields flatten to "parent.child", arrays of
// more than one element to "name[i]", and top-level `_padding` fields are no channels (trailing
// ones are not even logged); padding inside nested types stays, as pyulog keeps it.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "byte_source.hpp"
#include "geaware/io/log_channels.hpp"

namespace geaware::io {
namespace {

using detail::ByteSource;
using detail::load;

constexpr std::array<unsigned char, 7> kMagic = {0x55, 0x4c, 0x6f, 0x67, 0x01, 0x12, 0x35};
constexpr std::array<unsigned char, 8> kSyncMagic = {0x2f, 0x73, 0x13, 0x20, 0x25, 0x0c, 0xbb, 0x12};
constexpr std::size_t kHeaderBytes = 16;
constexpr std::size_t kMessageHeaderBytes = 3;
constexpr int kMaxNesting = 16;          // nested type depth (a cycle would recurse forever)
constexpr std::size_t kMaxULogWarnings = 20; // further problems are counted, not listed

struct BasicType {
  std::string_view name;
  FieldType type;
};
constexpr std::array<BasicType, 12> kBasicTypes = {{
    {"int8_t", FieldType::kInt8}, {"uint8_t", FieldType::kUInt8}, {"int16_t", FieldType::kInt16},
    {"uint16_t", FieldType::kUInt16}, {"int32_t", FieldType::kInt32}, {"uint32_t", FieldType::kUInt32},
    {"int64_t", FieldType::kInt64}, {"uint64_t", FieldType::kUInt64}, {"float", FieldType::kFloat},
    {"double", FieldType::kDouble}, {"bool", FieldType::kBool}, {"char", FieldType::kChar},
}};

const BasicType* basicType(std::string_view name) {
  for (const auto& b : kBasicTypes) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

struct FieldDef {
  std::string type;
  std::size_t count = 1;
  bool is_array = false;
  std::string name;
};

struct Leaf {
  std::uint32_t offset;
  FieldType type;
};

struct Subscription {
  std::size_t topic = SIZE_MAX;  // index in LogData::topics; SIZE_MAX: not decoded
  std::string name;
  std::vector<Leaf> leaves;      // one per channel, in channel order
  std::size_t bytes = 0;         // payload after the msg_id, trailing padding excluded
  std::size_t timestamp_offset = 0;
};

std::string_view asText(const std::byte* p, std::size_t n) { return {reinterpret_cast<const char*>(p), n}; }

class ULogParser {
 public:
  ULogParser(ByteSource& src, const LogReadOptions& options) : src_(src), options_(options) {
    log_.source = src.source();
    log_.format = "ulog";
  }

  LogData run() {
    readHeader();
    bool first = true;
    while (src_.remaining() > 0) {
      const std::uint64_t at = src_.offset();
      if (nextAppended_ < appended_.size() && at >= appended_[nextAppended_]) ++nextAppended_;
      const std::byte* h = src_.peek(kMessageHeaderBytes);
      if (h == nullptr) {
        warn(at, "the file ends inside a message header (" + std::to_string(src_.remaining()) +
                     " bytes left); read up to there");
        break;
      }
      const auto size = load<std::uint16_t>(h);
      const auto type = static_cast<char>(h[2]);
      const std::uint64_t end = at + kMessageHeaderBytes + size;
      if (nextAppended_ < appended_.size() && end > appended_[nextAppended_]) {
        // The message before appended data may be cut short by the logger: resume there.
        warn(at, "message cut short by the appended data at byte " + std::to_string(appended_[nextAppended_]));
        src_.seekForward(appended_[nextAppended_]);
        continue;
      }
      if (size > src_.remaining() - kMessageHeaderBytes) {
        warn(at, std::string("the last message (type '") + detail::printable(std::string_view(&type, 1)) +
                     "', " + std::to_string(size) + " bytes) is cut off: the file ends " +
                     std::to_string(src_.remaining() - kMessageHeaderBytes) + " bytes into it; read up to there");
        break;
      }
      (void)src_.take(kMessageHeaderBytes);
      const std::byte* payload = src_.take(size);
      if (!dispatch(type, payload, size, at, first)) {
        resync(at);
        continue;
      }
      first = false;
    }
    if (dropped_warnings_ > 0) {
      log_.warnings.push_back(std::to_string(dropped_warnings_) + " more problems of the same kinds");
    }
    return std::move(log_);
  }

 private:
  ByteSource& src_;
  const LogReadOptions& options_;
  LogData log_;
  std::unordered_map<std::string, std::vector<FieldDef>> formats_;
  std::unordered_map<std::uint16_t, Subscription> subs_;
  std::vector<std::uint64_t> appended_;
  std::size_t nextAppended_ = 0;
  std::uint64_t last_timestamp_us_ = 0;
  std::size_t dropped_warnings_ = 0;
  std::size_t flatten_steps_ = 0;  // per subscription
  static constexpr std::size_t kMaxFlattenSteps = 0x10000;
  std::size_t fields_subscribed_ = 0;
  static constexpr std::size_t kMaxFieldsSubscribed = std::size_t{1} << 20;

  void warn(std::uint64_t at, const std::string& message) {
    if (log_.warnings.size() >= kMaxULogWarnings) {
      ++dropped_warnings_;
      return;
    }
    log_.warnings.push_back("byte " + std::to_string(at) + ": " + message);
  }

  void readHeader() {
    const std::byte* h = src_.take(kHeaderBytes);
    if (h == nullptr || std::memcmp(h, kMagic.data(), kMagic.size()) != 0) {
      src_.fail(0, "not a ULog file (expected the 16-byte header starting 'ULog' 01 12 35)");
    }
    const auto version = static_cast<unsigned>(h[7]);
    if (version > 1) warn(7, "ULog version " + std::to_string(version) + ", newer than 1 (read as version 1)");
    log_.info["start_time_us"] = std::to_string(load<std::uint64_t>(h + 8));
  }

  // Returns false for a message type this reader does not know (the caller resynchronises).
  bool dispatch(char type, const std::byte* p, std::size_t n, std::uint64_t at, bool first) {
    switch (type) {
      case 'D': data(p, n, at); return true;
      case 'B': flags(p, n, at, first); return true;
      case 'F': format(p, n, at); return true;
      case 'A': subscribe(p, n, at); return true;
      case 'R':
        need(n, 2, at, "remove-subscription");
        subs_.erase(load<std::uint16_t>(p));
        return true;
      case 'I': case 'M': case 'P': case 'Q': info(type, p, n, at); return true;
      case 'L': case 'C': logged(type, p, n, at); return true;
      case 'O':
        need(n, 2, at, "dropout");
        log_.dropouts.push_back({static_cast<double>(last_timestamp_us_) * 1e-6, load<std::uint16_t>(p) * 1e-3});
        return true;
      case 'S': return true;
      default: return false;
    }
  }

  void need(std::size_t n, std::size_t at_least, std::uint64_t at, const char* what) const {
    if (n < at_least) {
      src_.fail(at, std::string(what) + " message of " + std::to_string(n) + " bytes, expected at least " +
                        std::to_string(at_least));
    }
  }

  // Unknown message type: the file is corrupt from `at`; continue after the next sync marker.
  void resync(std::uint64_t at) {
    src_.seekForward(at + 1);
    constexpr std::size_t kWindow = 4096;
    while (src_.remaining() >= kSyncMagic.size()) {
      const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(kWindow, src_.remaining()));
      const std::byte* w = src_.peek(n);
      for (std::size_t i = 0; i + kSyncMagic.size() <= n; ++i) {
        if (std::memcmp(w + i, kSyncMagic.data(), kSyncMagic.size()) == 0) {
          warn(at, "unknown message type (corrupt data): skipped " + std::to_string(src_.offset() + i - at) +
                       " bytes to the next sync marker");
          src_.skip(i + kSyncMagic.size());
          return;
        }
      }
      src_.skip(n - kSyncMagic.size() + 1);
    }
    warn(at, "unknown message type (corrupt data) and no sync marker after it: the rest of the file (" +
                 std::to_string(src_.size() - at) + " bytes) is not read");
    src_.skip(src_.remaining());
  }

  void flags(const std::byte* p, std::size_t n, std::uint64_t at, bool first) {
    if (!first) {
      warn(at, "flag-bits message after the first message: ignored");
      return;
    }
    need(n, 40, at, "flag-bits");
    // incompat_flags[0] bit 0: data appended at the offsets given; any other bit: a format
    // this reader cannot read.
    for (std::size_t i = 0; i < 8; ++i) {
      const auto bits = static_cast<unsigned>(p[8 + i]) & (i == 0 ? 0xfeu : 0xffu);
      if (bits != 0) {
        src_.fail(at, "incompatible flag bits set (byte " + std::to_string(i) + " = " +
                          std::to_string(static_cast<unsigned>(p[8 + i])) +
                          "): written by a logger with features this reader does not know");
      }
    }
    if ((static_cast<unsigned>(p[8]) & 1u) != 0) {
      for (std::size_t i = 0; i < 3; ++i) {
        const auto off = load<std::uint64_t>(p + 16 + 8 * i);
        if (off != 0) appended_.push_back(off);
      }
      std::sort(appended_.begin(), appended_.end());
    }
  }

  void format(const std::byte* p, std::size_t n, std::uint64_t at) {
    const std::string_view def = asText(p, n);
    const auto colon = def.find(':');
    if (colon == std::string_view::npos || colon == 0) {
      src_.fail(at, "format message '" + detail::printable(def) + "': expected 'name:type field;…'");
    }
    std::vector<FieldDef> fields;
    std::string_view rest = def.substr(colon + 1);
    while (!rest.empty()) {
      const auto semi = rest.find(';');
      const std::string_view item = rest.substr(0, semi);
      rest = semi == std::string_view::npos ? std::string_view{} : rest.substr(semi + 1);
      if (item.empty()) continue;
      const auto space = item.find(' ');
      if (space == std::string_view::npos || space == 0 || space + 1 == item.size()) {
        src_.fail(at, "format '" + detail::printable(def.substr(0, colon)) + "': field '" + detail::printable(item) +
                          "' is not 'type name'");
      }
      FieldDef f;
      std::string_view type = item.substr(0, space);
      f.name = std::string(item.substr(space + 1));
      if (const auto br = type.find('['); br != std::string_view::npos) {
        const auto close = type.find(']', br);
        std::size_t count = 0;
        bool ok = close == type.size() - 1 && close > br + 1;
        for (std::size_t i = br + 1; ok && i < close; ++i) {
          ok = type[i] >= '0' && type[i] <= '9' && count < 100000;
          count = count * 10 + static_cast<std::size_t>(type[i] - '0');
        }
        if (!ok || count == 0) {
          src_.fail(at, "format '" + detail::printable(def.substr(0, colon)) + "': field '" + f.name +
                            "' has a bad array size in '" + detail::printable(type) + "'");
        }
        f.count = count;
        f.is_array = true;
        type = type.substr(0, br);
      }
      f.type = std::string(type);
      fields.push_back(std::move(f));
    }
    formats_[std::string(def.substr(0, colon))] = std::move(fields);
  }

  // Flattens `type` at `offset` into channels (names prefixed) and leaves; returns the end offset.
  std::size_t flatten(const std::string& type, const std::string& prefix, std::size_t offset, int depth,
                      std::vector<Channel>& channels, std::vector<Leaf>& leaves, std::uint64_t at) {
    const auto it = formats_.find(type);
    if (it == formats_.end()) src_.fail(at, "no format message defines the type '" + detail::printable(type) + "'");
    if (depth > kMaxNesting) src_.fail(at, "type '" + type + "' is nested more than 16 deep (a cycle?)");
    for (const auto& f : it->second) {
      const BasicType* basic = basicType(f.type);
      for (std::size_t i = 0; i < f.count; ++i) {
        // Bounded work: a hostile format (arrays of empty types) would flatten for ever.
        if (++flatten_steps_ > kMaxFlattenSteps) {
          src_.fail(at, "type '" + type + "': more than 65535 fields after flattening nested types");
        }
        const std::string name = prefix + f.name + (f.count > 1 ? "[" + std::to_string(i) + "]" : "");
        if (basic != nullptr) {
          Channel c;
          c.name = name;
          c.type = basic->type;
          if (prefix.empty() && (f.name == "timestamp" || f.name.ends_with("timestamp_sample"))) c.unit = "us";
          channels.push_back(std::move(c));
          leaves.push_back({static_cast<std::uint32_t>(offset), basic->type});
          offset += fieldTypeBytes(basic->type);
        } else {
          offset = flatten(f.type, name + ".", offset, depth + 1, channels, leaves, at);
        }
        if (offset > 0xffff) {
          src_.fail(at, "topic '" + type + "': its fields take more than the 65535 bytes a message can hold");
        }
      }
    }
    return offset;
  }

  bool wanted(const std::string& topic) const {
    return options_.topics.empty() ||
           std::find(options_.topics.begin(), options_.topics.end(), topic) != options_.topics.end();
  }

  void subscribe(const std::byte* p, std::size_t n, std::uint64_t at) {
    need(n, 4, at, "subscription");
    const auto multi_id = static_cast<unsigned>(p[0]);
    const auto msg_id = load<std::uint16_t>(p + 1);
    Subscription s;
    s.name = std::string(asText(p + 3, n - 3));
    std::vector<Channel> channels;
    flatten_steps_ = 0;
    // Bounded memory: a 4-byte subscription may flatten to 65,535 fields, so a hostile file of
    // subscriptions would multiply its size by ~10^5; real logs hold about 10^4 fields in all.
    if (fields_subscribed_ > kMaxFieldsSubscribed) {
      src_.fail(at, "more than " + std::to_string(kMaxFieldsSubscribed) + " fields subscribed in all (a real log holds "
                    "about 10^4): refused");
    }
    s.bytes = flatten(s.name, "", 0, 0, channels, s.leaves, at);
    fields_subscribed_ += s.leaves.size();
    // Trailing padding is not logged (and pyulog drops it).
    while (!channels.empty() && channels.back().name.starts_with("_padding")) {
      s.bytes = s.leaves.back().offset;
      channels.pop_back();
      s.leaves.pop_back();
    }
    // Padding elsewhere at the top level takes its bytes but is no channel (as in pyulog).
    for (std::size_t i = channels.size(); i-- > 0;) {
      if (channels[i].name.starts_with("_padding")) {
        channels.erase(channels.begin() + static_cast<std::ptrdiff_t>(i));
        s.leaves.erase(s.leaves.begin() + static_cast<std::ptrdiff_t>(i));
      }
    }
    const auto ts = std::find_if(channels.begin(), channels.end(), [](const Channel& c) { return c.name == "timestamp"; });
    if (ts == channels.end() || ts->type != FieldType::kUInt64) {
      src_.fail(at, "topic '" + detail::printable(s.name) + "' has no uint64_t timestamp field");
    }
    s.timestamp_offset = s.leaves[static_cast<std::size_t>(ts - channels.begin())].offset;
    if (wanted(s.name)) {
      auto t = std::find_if(log_.topics.begin(), log_.topics.end(),
                            [&](const Topic& x) { return x.name == s.name && x.instance == multi_id; });
      if (t == log_.topics.end()) {
        log_.topics.push_back({s.name, multi_id, {}, std::move(channels)});
        t = log_.topics.end() - 1;
      } else if (t->channels.size() != channels.size()) {
        src_.fail(at, "topic '" + s.name + "' instance " + std::to_string(multi_id) +
                          " subscribed again with another format");
      }
      s.topic = static_cast<std::size_t>(t - log_.topics.begin());
    }
    subs_[msg_id] = std::move(s);
  }

  void data(const std::byte* p, std::size_t n, std::uint64_t at) {
    need(n, 2, at, "data");
    const auto msg_id = load<std::uint16_t>(p);
    const auto it = subs_.find(msg_id);
    if (it == subs_.end()) {
      warn(at, "data message for message id " + std::to_string(msg_id) + ", which no subscription defines: skipped");
      return;
    }
    const Subscription& s = it->second;
    if (n - 2 != s.bytes) {
      src_.fail(at, "data message of '" + s.name + "' holds " + std::to_string(n - 2) +
                        " bytes, its format " + std::to_string(s.bytes));
    }
    const std::byte* fields = p + 2;
    const auto t_us = load<std::uint64_t>(fields + s.timestamp_offset);
    if (t_us > last_timestamp_us_) last_timestamp_us_ = t_us;
    if (s.topic == SIZE_MAX) return;
    Topic& topic = log_.topics[s.topic];
    topic.time_s.push_back(static_cast<double>(t_us) * 1e-6);
    for (std::size_t k = 0; k < s.leaves.size(); ++k) {
      topic.channels[k].values.push_back(detail::loadAsDouble(fields + s.leaves[k].offset, s.leaves[k].type));
    }
  }

  // I, M, P, Q: [M: is_continued] [Q: default_types] key_len, key "type name", value.
  void info(char type, const std::byte* p, std::size_t n, std::uint64_t at) {
    const std::size_t skip = (type == 'M' || type == 'Q') ? 1 : 0;
    need(n, skip + 1, at, "info");
    const auto key_len = static_cast<std::size_t>(p[skip]);
    if (skip + 1 + key_len > n) src_.fail(at, "info message: its key runs past the message");
    const std::string_view key = asText(p + skip + 1, key_len);
    const std::byte* value = p + skip + 1 + key_len;
    const std::size_t value_len = n - skip - 1 - key_len;
    const auto space = key.find(' ');
    if (space == std::string_view::npos) {
      src_.fail(at, "info message key '" + detail::printable(key) + "': expected 'type name'");
    }
    const std::string_view vtype = key.substr(0, space);
    const std::string name(key.substr(space + 1));
    if (type == 'Q') return;  // defaults of parameters: not needed
    const BasicType* basic = basicType(vtype);
    if (basic != nullptr && basic->type != FieldType::kChar) {
      if (value_len != fieldTypeBytes(basic->type)) {
        src_.fail(at, "info '" + detail::printable(name) + "': " + std::to_string(value_len) + " bytes for a " +
                          std::string(vtype));
      }
      const double v = detail::loadAsDouble(value, basic->type);
      if (type == 'P') {
        log_.parameters[name] = v;
      } else {
        log_.info[name] = std::floor(v) == v && std::abs(v) < 9e15 ? std::to_string(static_cast<long long>(v))
                                                                    : std::to_string(v);
      }
      return;
    }
    if (type == 'P') src_.fail(at, "parameter '" + detail::printable(name) + "' of type '" + std::string(vtype) + "'");
    std::string value_text(asText(value, value_len));
    if (const auto nul = value_text.find('\0'); nul != std::string::npos) value_text.resize(nul);
    std::string& slot = log_.info[name];
    if (type == 'M' && static_cast<unsigned>(p[0]) != 0) {
      slot += value_text;
    } else {
      slot = std::move(value_text);
    }
  }

  void logged(char type, const std::byte* p, std::size_t n, std::uint64_t at) {
    const std::size_t head = type == 'C' ? 11 : 9;
    need(n, head, at, "logging");
    LogMessage m;
    const auto level = static_cast<int>(p[0]);
    m.level = level >= '0' && level <= '7' ? level - '0' : level;
    m.time_s = static_cast<double>(load<std::uint64_t>(p + head - 8)) * 1e-6;
    m.text = std::string(asText(p + head, n - head));
    log_.messages.push_back(std::move(m));
  }
};

}  // namespace

LogData readULog(const std::filesystem::path& file, const LogReadOptions& options) {
  ByteSource src(file, options.max_bytes, "ULog file");
  return ULogParser(src, options).run();
}

LogData readULog(std::span<const std::byte> bytes, const std::string& source, const LogReadOptions& options) {
  ByteSource src(bytes, source, options.max_bytes);
  return ULogParser(src, options).run();
}

}  // namespace geaware::io
