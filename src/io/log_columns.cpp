// SPDX-License-Identifier: BSD-3-Clause
// readCsv on a log that is not CSV (a MATLAB .mat file, a ULog, DataFlash or Crazyflie uSD log):
// the rig logs' columns (identify rotor, identify platform, identify flight without a map) from
// the fields of one topic. Each column is its --column/--const definition or else the field of
// its own name; the time column, when the log has no such field, is the topic's time.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "geaware/io/column_expression.hpp"
#include "geaware/io/csv_reader.hpp"
#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_map.hpp"
#include "geaware/io/units.hpp"
#include "text.hpp"

namespace geaware::io::detail {
namespace {

std::string logValue(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::string rigTopicName(const Topic& t) { return t.name + "[" + std::to_string(t.instance) + "]"; }

}  // namespace

CsvTable readLogColumns(const std::filesystem::path& file, const CsvReadOptions& options) {
  const LogData log = readLog(file);
  const std::string source = file.string();
  CsvTable out;
  out.source = source;
  out.first_data_line = 1;  // row i is the log's sample i + 1 of the topic
  const Topic* topic = nullptr;
  std::vector<EvaluatedField> values(options.columns.size());
  std::vector<bool> from_time(options.columns.size(), false);
  for (std::size_t k = 0; k < options.columns.size(); ++k) {
    const std::string& name = options.columns[k].name;
    out.names.push_back(name);
    const auto d = std::find_if(options.definitions.begin(), options.definitions.end(),
                                [&](const ColumnDefinition& c) { return c.name == name; });
    const ColumnExpression e = d != options.definitions.end()
                                   ? d->expression
                                   : ColumnExpression::parse("\"" + name + "\"", "column '" + name + "'");
    try {
      values[k] = evaluateOnLog(e, log, "", 0, unitOfColumnName(name), name, true);
    } catch (const MissingFieldError& error) {
      if (d != options.definitions.end()) throw;
      if (name != options.time_column) {
        std::string why = error.what();
        if (why.starts_with(source + ": ")) why.erase(0, source.size() + 2);
        throw LogError(source, "column '" + name + "' is not a field of the log and not defined: --column " + name +
                                   "=EXPR, or --const " + name + "=VALUE (" + why + ")");
      }
      from_time[k] = true;  // the time: the topic's own, when the log has no field of its name
      continue;
    }
    const Topic* t = values[k].topic;
    if (t == nullptr) continue;  // a constant
    if (topic != nullptr && t != topic) {
      throw LogError(source, "column '" + name + "' is in " + rigTopicName(*t) + ", an earlier column in " +
                                 rigTopicName(*topic) + ": a rig log's columns come from one topic (one time axis)");
    }
    topic = t;
  }
  if (topic == nullptr) {
    throw LogError(source, "no column comes from a field of the log: every one is a constant");
  }
  const std::size_t rows = topic->size();
  for (std::size_t k = 0; k < options.columns.size(); ++k) {
    if (from_time[k]) {
      out.columns.push_back(topic->time_s);
    } else if (values[k].topic == nullptr) {
      out.columns.emplace_back(rows, values[k].values.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                             : values[k].values.front());
    } else {
      out.columns.push_back(std::move(values[k].values));
    }
  }
  if (rows < options.min_rows) {
    throw CsvError(source, 0, "", "only " + std::to_string(rows) + " samples in " + rigTopicName(*topic) + ", at least " +
                                      std::to_string(options.min_rows) + " are needed");
  }
  // The checks the CSV reader makes on each cell: finite, in the plausible range, time increasing.
  for (std::size_t k = 0; k < options.columns.size(); ++k) {
    const CsvColumn& col = options.columns[k];
    const auto& v = out.columns[k];
    const bool is_time = col.name == options.time_column;
    for (std::size_t r = 0; r < v.size(); ++r) {
      const std::string at = rigTopicName(*topic) + " sample " + std::to_string(r + 1) + ": ";
      if (!std::isfinite(v[r])) throw CsvError(source, 0, col.name, at + "not finite");
      if (v[r] < col.min || v[r] > col.max) {
        throw CsvError(source, 0, col.name,
                       at + "value " + logValue(v[r]) + " is outside the plausible range [" + logValue(col.min) + ", " +
                           logValue(col.max) + "] for this column (wrong unit?)");
      }
      if (is_time && r > 0 && !(v[r] > v[r - 1])) {
        throw CsvError(source, 0, col.name,
                       at + "time " + logValue(v[r]) + " does not increase (sample " + std::to_string(r) + ": " +
                           logValue(v[r - 1]) + ")");
      }
    }
  }
  return out;
}

}  // namespace geaware::io::detail
