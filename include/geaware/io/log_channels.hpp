// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The channel model every flight-log reader fills (docs/identification.md, "Log formats"):
// a log is a set of topics (PX4 uORB topics, ArduPilot message types), each possibly logged as
// several instances (two IMUs, six ESCs); a topic instance holds one time axis [s] and its
// channels, one per scalar field (array elements and nested fields flattened to names such as
// `esc[0].esc_rpm`), each with a unit (empty when the log does not say), the field's type in the
// file and its values as doubles. Integers above 2^53 (none that a flight log holds in a
// physical field) lose their lowest bits in a double.
//
// Readers stream: they hold one read buffer, never the whole file, and refuse a file larger than
// LogReadOptions::max_bytes before reading it. Every reader also reads from memory (for tests
// and fuzzing), with `source` naming the buffer in messages.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace geaware::io {

/// The largest binary log a reader accepts [bytes] (1 GiB): the decoded channels take up to
/// eight times the bytes of the fields they come from.
inline constexpr std::uintmax_t kMaxLogFileBytes = std::uintmax_t{1} << 30;

/// A bad or unreadable log. what() is "FILE: byte OFFSET: MESSAGE" (the offset is left out when
/// it does not apply; for text logs it is "FILE:LINE: MESSAGE").
class LogError : public std::runtime_error {
 public:
  LogError(std::string file, std::uint64_t offset, const std::string& message);
  LogError(std::string file, const std::string& message);
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] bool hasOffset() const noexcept { return has_offset_; }
  [[nodiscard]] std::uint64_t offset() const noexcept { return offset_; }  ///< byte offset

 private:
  std::string file_;
  std::uint64_t offset_ = 0;
  bool has_offset_ = false;
};

/// The type a field has in the file.
enum class FieldType : std::uint8_t {
  kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kInt64, kUInt64,
  kFloat, kDouble, kBool, kChar, kText,
};
/// "int8_t", …, "float", "double", "bool", "char", "text".
[[nodiscard]] std::string_view fieldTypeName(FieldType type) noexcept;
/// The size of one value of `type` in bytes (0 for kText).
[[nodiscard]] std::size_t fieldTypeBytes(FieldType type) noexcept;

/// One scalar field of a topic instance.
struct Channel {
  std::string name;            ///< flattened field name, e.g. "q[0]", "esc[2].esc_rpm"
  std::string unit;            ///< e.g. "m", "rad/s"; empty: the log does not say
  FieldType type = FieldType::kDouble;  ///< the field's type in the file
  std::vector<double> values;  ///< one per message, scaled as the log's metadata says
};

/// One instance of a topic: its messages as channels over one time axis.
struct Topic {
  std::string name;             ///< e.g. "sensor_combined", "IMU"
  unsigned instance = 0;        ///< PX4 multi_id, ArduPilot instance field; 0 otherwise
  std::vector<double> time_s;   ///< time of each message [s] (log clock)
  std::vector<Channel> channels;

  [[nodiscard]] std::size_t size() const noexcept { return time_s.size(); }
  /// The channel called `name`, or nullptr.
  [[nodiscard]] const Channel* channel(std::string_view name) const noexcept;
};

/// A text message the vehicle logged (PX4 logging messages, ArduPilot MSG).
struct LogMessage {
  double time_s = 0.0;
  int level = 6;                ///< syslog level: 0 emergency … 7 debug
  std::string text;
};

/// A stretch the logger lost (PX4 dropout messages).
struct Dropout {
  double time_s = 0.0;          ///< log time of the last message before it [s]
  double duration_s = 0.0;
};

/// Everything a reader found in one log.
struct LogData {
  std::string source;                          ///< the file (or buffer name) it came from
  std::string format;                          ///< "ulog", "dataflash", "crazyflie_usd", "mat", "csv"
  std::vector<Topic> topics;                   ///< in the order first seen
  std::map<std::string, std::string> info;     ///< key → value as text (ULog info messages)
  std::map<std::string, double> parameters;    ///< vehicle parameters, last value logged
  std::vector<LogMessage> messages;
  std::vector<Dropout> dropouts;
  std::vector<std::string> warnings;           ///< problems read past (each names the offset)

  /// The topic instance, or nullptr.
  [[nodiscard]] const Topic* topic(std::string_view name, unsigned instance = 0) const noexcept;
};

struct LogReadOptions {
  std::uintmax_t max_bytes = kMaxLogFileBytes;  ///< a larger file is refused unread
  /// Topics to decode (empty: all); the others are skipped but still checked for framing.
  std::vector<std::string> topics;
};

/// PX4 ULog (https://docs.px4.io/main/en/dev_log/ulog_file_format.html). Throws LogError.
[[nodiscard]] LogData readULog(const std::filesystem::path& file, const LogReadOptions& options = {});
[[nodiscard]] LogData readULog(std::span<const std::byte> bytes, const std::string& source,
                               const LogReadOptions& options = {});

/// ArduPilot DataFlash (.bin): FMT, FMTU, UNIT, MULT, PARM and MSG understood; values scaled
/// by FMTU's multipliers. Throws LogError.
[[nodiscard]] LogData readDataFlash(const std::filesystem::path& file, const LogReadOptions& options = {});
[[nodiscard]] LogData readDataFlash(std::span<const std::byte> bytes, const std::string& source,
                                    const LogReadOptions& options = {});

/// Crazyflie uSD-card log (the usd deck's event-based format, versions 1 and 2, and the older
/// fixed-frequency format; src/io/cfusd_reader.cpp). Each event type is a topic
/// ("fixedFrequency" for the older format). Throws LogError.
[[nodiscard]] LogData readCrazyflieUsd(const std::filesystem::path& file, const LogReadOptions& options = {});
[[nodiscard]] LogData readCrazyflieUsd(std::span<const std::byte> bytes, const std::string& source,
                                       const LogReadOptions& options = {});
/// Whether `head` (a file's first bytes, 256 or all) starts like a Crazyflie uSD log: 0xBC and
/// version 1 or 2, or a variable count followed by "name(T)," entries.
[[nodiscard]] bool looksLikeCrazyflieUsd(std::span<const std::byte> head) noexcept;

/// MATLAB .mat (v5, v7, v7.3) through libmatio (src/io/mat_reader.cpp): numeric vectors,
/// matrix columns (`name[j]`) and struct fields as channels, top-level vectors in topic "mat", a
/// struct's fields in a topic named after it, scalars as parameters; each variable's size is
/// checked before its data is read. Throws LogError.
[[nodiscard]] LogData readMat(const std::filesystem::path& file, const LogReadOptions& options = {});
/// Whether `head` starts like a MATLAB v5/v7/v7.3 file ("MATLAB " in its text header).
[[nodiscard]] bool looksLikeMat(std::span<const std::byte> head) noexcept;

/// The formats readLog knows.
enum class LogFormat : std::uint8_t { kULog, kDataFlash, kCrazyflieUsd, kMat, kCsv };
/// The format of `file` from its first bytes (ULog magic, DataFlash A3 95 80 header, a
/// Crazyflie uSD header; anything else is taken for CSV). Throws LogError when the file cannot
/// be opened.
[[nodiscard]] LogFormat detectLogFormat(const std::filesystem::path& file);
/// Reads `file` with the reader of its format (a CSV log becomes one topic "csv" with every
/// numeric column; the time is the first column whose name says seconds, t/time/t_s, or the
/// row number). Throws LogError (and CsvError for CSV).
[[nodiscard]] LogData readLog(const std::filesystem::path& file, const LogReadOptions& options = {});

}  // namespace geaware::io
