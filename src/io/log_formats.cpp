// SPDX-License-Identifier: BSD-3-Clause
// Which reader a log needs (its first bytes), and a CSV log as the channel model.

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>

#include "geaware/io/csv_reader.hpp"
#include "geaware/io/log_channels.hpp"
#include "text.hpp"

namespace geaware::io {
namespace {

std::string trimmedCopy(std::string_view s) { return std::string(detail::trimBlanks(s)); }

std::string lowerCase(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Seconds per unit of a time column called `name` with header unit `unit`; 0: not a time column.
double timeScale(std::string_view name, std::string_view unit) {
  const std::string n = lowerCase(name);
  const std::string u = lowerCase(unit);
  if (n == "timeus" || n == "time_us" || n == "t_us" || (n == "timestamp" && u.empty())) return 1e-6;
  if (n == "timems" || n == "time_ms" || n == "t_ms") return 1e-3;
  if (n != "t" && n != "t_s" && n != "time" && n != "time_s" && n != "timestamp") return 0.0;
  if (u.empty() || u == "s") return 1.0;
  if (u == "ms") return 1e-3;
  if (u == "us" || u == "µs") return 1e-6;
  return 0.0;
}

LogData readCsvLog(const std::filesystem::path& file) {
  CsvReadOptions probe;
  probe.time_column.clear();
  probe.min_rows = 0;
  probe.buffer_bytes = 1 << 16;
  std::vector<std::string> names, units;
  {
    CsvReader r(file, probe);
    names = r.header();
    units = r.units();
  }
  CsvReadOptions o;
  o.time_column.clear();
  o.min_rows = 1;
  std::size_t time_column = names.size();
  double scale = 0.0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    o.columns.push_back({names[i]});
    // The bare name: "z[mm]" → "z".
    const std::string bare = units[i].empty() ? names[i] : names[i].substr(0, names[i].find_first_of("[("));
    const double s = timeScale(trimmedCopy(bare), units[i]);
    if (s > 0.0 && time_column == names.size()) time_column = i, scale = s;
  }
  // A column may hold NaN, ±inf or gaps (an export that merges topics logged at different rates,
  // a flight log's unbounded limit): mapFlight drops the rows where a field it uses has one, and
  // counts them; `logs inspect` shows them in the channel's health.
  for (std::size_t i = 0; i < o.columns.size(); ++i) o.columns[i].non_finite = i != time_column;
  if (time_column < names.size()) o.time_column = names[time_column];
  const CsvTable table = readCsv(file, o);
  LogData log;
  log.source = table.source;
  log.format = "csv";
  Topic topic;
  topic.name = "csv";
  for (std::size_t i = 0; i < names.size(); ++i) {
    Channel c;
    c.name = units[i].empty() ? names[i] : trimmedCopy(names[i].substr(0, names[i].find_first_of("[(")));
    c.unit = units[i];
    c.type = FieldType::kDouble;
    c.values = table.columns[i];
    topic.channels.push_back(std::move(c));
  }
  const std::size_t rows = table.rows();
  topic.time_s.resize(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    topic.time_s[r] = time_column < names.size() ? table.columns[time_column][r] * scale : static_cast<double>(r);
  }
  if (time_column == names.size()) {
    log.warnings.push_back("no time column (t, t_s, time, timestamp, TimeUS): the row number stands for the time");
  }
  log.topics.push_back(std::move(topic));
  return log;
}

}  // namespace

LogFormat detectLogFormat(const std::filesystem::path& file) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (f == nullptr) throw LogError(file.string(), std::string("cannot open: ") + std::strerror(errno));
  std::array<unsigned char, 256> head{};
  const std::size_t n = std::fread(head.data(), 1, head.size(), f.get());
  constexpr std::array<unsigned char, 7> kULog = {0x55, 0x4c, 0x6f, 0x67, 0x01, 0x12, 0x35};
  if (n >= kULog.size() && std::equal(kULog.begin(), kULog.end(), head.begin())) return LogFormat::kULog;
  if (n >= 3 && head[0] == 0xa3 && head[1] == 0x95 && head[2] == 0x80) return LogFormat::kDataFlash;
  if (looksLikeMat(std::as_bytes(std::span(head.data(), n)))) return LogFormat::kMat;
  if (looksLikeCrazyflieUsd(std::as_bytes(std::span(head.data(), n)))) return LogFormat::kCrazyflieUsd;
  return LogFormat::kCsv;
}

LogData readLog(const std::filesystem::path& file, const LogReadOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw LogError(file.string(), std::filesystem::exists(file, ec) ? "not a regular file (expected a flight log)"
                                                                    : "no such log file");
  }
  switch (detectLogFormat(file)) {
    case LogFormat::kULog: return readULog(file, options);
    case LogFormat::kDataFlash: return readDataFlash(file, options);
    case LogFormat::kCrazyflieUsd: return readCrazyflieUsd(file, options);
    case LogFormat::kMat: return readMat(file, options);
    case LogFormat::kCsv: break;
  }
  return readCsvLog(file);
}

}  // namespace geaware::io
