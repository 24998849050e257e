// SPDX-License-Identifier: BSD-3-Clause
// readCsv with column definitions (`--column NAME=EXPR`, `--const NAME=VALUE`): the fields the
// expressions read are read as hidden columns, then each defined column is computed, checked
// (finite, in its plausible range, a defined time increasing) and handed out under its name.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "geaware/io/column_expression.hpp"
#include "geaware/io/csv_reader.hpp"
#include "geaware/io/log_channels.hpp"
#include "text.hpp"

namespace geaware::io::detail {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

struct Header {
  std::vector<std::string> names, bare, units;

  // The header index of `field` (whole name or name without its unit), or SIZE_MAX.
  [[nodiscard]] std::size_t find(const std::string& field) const {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == field) return i;
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (bare[i] == field) return i;
    }
    return SIZE_MAX;
  }
  [[nodiscard]] std::string list() const {
    std::string s;
    constexpr std::size_t kShown = 40;
    for (std::size_t i = 0; i < std::min(names.size(), kShown); ++i)
      s += (i ? ", " : "") + excerpt(names[i]);
    if (names.size() > kShown) s += ", … (" + std::to_string(names.size() - kShown) + " more)";
    return s;
  }
};

Header readHeader(const std::filesystem::path& file, const CsvReadOptions& options) {
  CsvReadOptions probe;
  probe.delimiter = options.delimiter;
  probe.time_column.clear();
  probe.min_rows = 0;
  probe.buffer_bytes = 1 << 16;
  CsvReader r(file, probe);
  Header h{r.header(), {}, r.units()};
  for (std::size_t i = 0; i < h.names.size(); ++i) {
    h.bare.push_back(h.units[i].empty() ? h.names[i]
                                        : std::string(trimBlanks(h.names[i].substr(
                                              0, h.names[i].find_first_of("[(")))));
  }
  return h;
}

// A definition whose whole text is a header name ("F-z", "Thrust (kgf)") reads that column:
// the names users already had work as they were.
ColumnExpression resolved(const ColumnDefinition& d, const Header& header) {
  const std::string text(trimBlanks(d.expression.text()));
  if (!d.expression.isField() && text.find('"') == std::string::npos &&
      header.find(text) != SIZE_MAX) {
    return ColumnExpression::parse("\"" + text + "\"", d.option);
  }
  return d.expression;
}

}  // namespace

CsvTable readCsvDefined(const std::filesystem::path& file, const CsvReadOptions& options) {
  const Header header = readHeader(file, options);
  std::vector<std::string> requested;
  for (const auto& c : options.columns) requested.push_back(c.name);
  std::vector<const ColumnDefinition*> defined(options.columns.size(), nullptr);
  std::vector<ColumnExpression> expressions(options.columns.size());
  for (const auto& d : options.definitions) {
    const auto it = std::find(requested.begin(), requested.end(), d.name);
    if (it == requested.end()) {
      std::string names;
      for (const auto& n : requested) names += (names.empty() ? "" : ", ") + n;
      throw ExpressionError(d.option + ": character 1: '" + d.name +
                            "' is not a column this command reads (" + names + ")");
    }
    const auto k = static_cast<std::size_t>(it - requested.begin());
    defined[k] = &d;
    expressions[k] = resolved(d, header);
  }
  // The columns to read: the requested ones not defined, then every field an expression reads.
  CsvReadOptions inner = options;
  inner.definitions.clear();
  inner.columns.clear();
  const auto add = [&](const CsvColumn& c) {
    for (const auto& x : inner.columns) {
      if (x.name == c.name) return;
    }
    inner.columns.push_back(c);
  };
  for (std::size_t k = 0; k < options.columns.size(); ++k) {
    if (defined[k] == nullptr) add(options.columns[k]);
  }
  for (std::size_t k = 0; k < options.columns.size(); ++k) {
    if (defined[k] == nullptr) continue;
    const ColumnExpression& e = expressions[k];
    for (std::size_t f = 0; f < e.fields().size(); ++f) {
      if (header.find(e.fields()[f]) == SIZE_MAX) {
        throw ExpressionError(e.where() + ": character " + std::to_string(e.fieldOffset(f) + 1) +
                              ": " + file.string() + " has no column '" + excerpt(e.fields()[f]) +
                              "' (its columns: " + header.list() + ")");
      }
      add({e.fields()[f]});
    }
  }
  // Before the long read: every column there or defined, and every definition's units right
  // (evaluated once on a dummy row with the header's units).
  for (std::size_t k = 0; k < options.columns.size(); ++k) {
    if (defined[k] != nullptr) {
      const ColumnExpression& e = expressions[k];
      const std::vector<double> one(1, 1.0);
      std::vector<ColumnExpression::FieldData> fields;
      for (const auto& f : e.fields()) fields.push_back({one, header.units[header.find(f)]});
      (void)e.evaluate(fields, 1, unitOfColumnName(requested[k]), requested[k]);
    } else if (header.find(requested[k]) == SIZE_MAX) {
      throw CsvError(file.string(), 0, requested[k],
                     "not in the file (its columns: " + header.list() +
                         ") and not defined: --column " + requested[k] + "=EXPR, or --const " +
                         requested[k] + "=VALUE");
    }
  }
  if (inner.columns.empty()) {
    throw ExpressionError(defined.front() != nullptr
                              ? defined.front()->option + ": every column is a constant; " +
                                    file.string() + " gives none"
                              : "readCsv: no column to read");
  }
  const auto time_it = std::find(requested.begin(), requested.end(), options.time_column);
  const bool time_defined =
      time_it != requested.end() && defined[static_cast<std::size_t>(time_it - requested.begin())];
  if (time_defined ||
      std::find_if(inner.columns.begin(), inner.columns.end(), [&](const CsvColumn& c) {
        return c.name == options.time_column;
      }) == inner.columns.end()) {
    inner.time_column.clear();
  }
  CsvTable raw = readCsv(file, inner);
  const std::size_t rows = raw.rows();
  CsvTable out;
  out.source = raw.source;
  out.names = requested;
  out.columns.resize(requested.size());
  std::size_t lag = 0;
  for (std::size_t k = 0; k < requested.size(); ++k) {
    if (defined[k] == nullptr) {
      out.columns[k] = raw.column(requested[k]);
      continue;
    }
    const ColumnExpression& e = expressions[k];
    std::vector<ColumnExpression::FieldData> fields;
    for (const auto& f : e.fields())
      fields.push_back({raw.column(f), header.units[header.find(f)]});
    out.columns[k] = e.evaluate(fields, rows, unitOfColumnName(requested[k]), requested[k]);
    lag = std::max(lag, e.lag());
  }
  lag = std::min(lag, rows);
  for (auto& c : out.columns) c.erase(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(lag));
  out.first_data_line = raw.first_data_line + lag;
  if (out.rows() < options.min_rows) {
    throw CsvError(
        out.source, 0, "",
        "only " + std::to_string(out.rows()) + " data rows" +
            (lag > 0 ? " after the " + std::to_string(lag) + " delta() leaves without a value"
                     : "") +
            ", at least " + std::to_string(options.min_rows) + " needed");
  }
  for (std::size_t k = 0; k < requested.size(); ++k) {
    if (defined[k] == nullptr) continue;
    const CsvColumn& col = options.columns[k];
    const auto& v = out.columns[k];
    const bool is_time = requested[k] == options.time_column;
    for (std::size_t r = 0; r < v.size(); ++r) {
      const std::size_t line = out.first_data_line + r;
      const std::string from = " (" + defined[k]->option + ")";
      if (!std::isfinite(v[r])) throw CsvError(out.source, line, col.name, "not finite" + from);
      if (v[r] < col.min || v[r] > col.max) {
        throw CsvError(out.source, line, col.name,
                       "value " + number(v[r]) + from + " is outside the plausible range [" +
                           number(col.min) + ", " + number(col.max) +
                           "] for this column (wrong unit?)");
      }
      if (is_time && r > 0 && !(v[r] > v[r - 1])) {
        throw CsvError(out.source, line, col.name,
                       "time " + number(v[r]) + from + " does not increase (line " +
                           std::to_string(line - 1) + ": " + number(v[r - 1]) + ")");
      }
    }
  }
  return out;
}

}  // namespace geaware::io::detail

namespace geaware::io {

namespace detail {
// log_columns.cpp: readCsv on a log that is not CSV (.mat, ULog, DataFlash, Crazyflie uSD).
CsvTable readLogColumns(const std::filesystem::path& file, const CsvReadOptions& options);
}  // namespace detail

// The whole-table reader: the columns asked for, row by row through CsvReader (csv_reader.cpp),
// with column definitions (readCsvDefined above), or from a log in another format.
CsvTable readCsv(const std::filesystem::path& file, const CsvReadOptions& options) {
  // A log in another format identify flight reads (a .mat file, say): the same columns from the
  // fields of one of its topics. A file that cannot be opened is the CSV reader's to report.
  if (std::ifstream(file).good() && detectLogFormat(file) != LogFormat::kCsv) return detail::readLogColumns(file, options);
  if (!options.definitions.empty()) return detail::readCsvDefined(file, options);
  CsvReader reader(file, options);
  CsvTable table;
  table.source = reader.source();
  for (const auto& c : options.columns) table.names.push_back(c.name);
  table.columns.resize(options.columns.size());
  // Reserve from the file size once the first rows show the bytes per row: avoids regrowth
  // (and the transient doubling of memory it costs) for large logs.
  std::error_code ec;
  const auto file_bytes = std::filesystem::file_size(file, ec);
  constexpr std::size_t kProbeRows = 4096;
  std::vector<double> row(options.columns.size());
  std::size_t data_start = 0;
  while (reader.next(row)) {
    if (table.columns.front().empty()) {
      table.first_data_line = reader.line();
      data_start = reader.bytesRead();
    }
    if (table.columns.front().size() == kProbeRows && !ec && reader.bytesRead() > data_start) {
      const double per_row = static_cast<double>(reader.bytesRead() - data_start) / (kProbeRows - 1);
      const auto guess = static_cast<std::size_t>(1.02 * static_cast<double>(file_bytes) / per_row) + 16;
      for (auto& c : table.columns) c.reserve(guess);
    }
    for (std::size_t k = 0; k < row.size(); ++k) table.columns[k].push_back(row[k]);
  }
  return table;
}

}  // namespace geaware::io
