// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/csv_reader.hpp"

#include "geaware/io/input_file.hpp"
#include "text.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>

namespace geaware::io {


namespace {

std::string formatWhat(const std::string& file, std::size_t line, const std::string& column,
                       const std::string& message) {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
  s += ": ";
  if (!column.empty()) s += "column '" + column + "': ";
  return s + message;
}

std::string number(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

// Levenshtein distance, case-insensitive, for "did you mean" hints on misnamed columns.
std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}
}  // namespace

CsvError::CsvError(std::string file, std::size_t line, std::string column,
                   const std::string& message)
    : std::runtime_error(formatWhat(file, line, column, message)),
      file_(std::move(file)),
      line_(line),
      column_(std::move(column)) {}

const std::vector<double>& CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return columns[i];
  }
  throw std::out_of_range("CsvTable: column '" + std::string(name) + "' was not read from " +
                          source);
}

struct CsvReader::Impl {
  std::string source;
  CsvReadOptions options;
  std::FILE* file = nullptr;

  // Read buffer: bytes [begin, end) are read but not yet consumed.
  std::vector<char> buffer;
  std::size_t begin = 0;
  std::size_t end = 0;
  bool eof = false;

  std::vector<std::string> header;
  std::vector<std::string> bare_names;  // header names without their units
  std::vector<std::string> units;       // the unit each header name carries ("" if none)
  char delim = ',';
  std::string pending;                  // first data row read while looking for the header
  bool has_pending = false;
  std::vector<int> slot_of_cell;  // header cell → index in the requested columns, −1: skipped
  int time_slot = -1;
  std::size_t line_no = 0;        // physical line of the last line taken from the buffer
  std::size_t consumed = 0;       // bytes of the lines taken so far
  std::size_t row_line = 0;       // line of the last data row returned
  std::size_t rows = 0;
  std::size_t blank_line = 0;     // first empty line after the data (0: none yet)
  bool finished = false;
  double last_time = 0.0;
  std::size_t last_time_line = 0;

  ~Impl() {
    if (file != nullptr) std::fclose(file);
  }

  [[noreturn]] void fail(std::size_t line, const std::string& column, const std::string& msg) const {
    throw CsvError(source, line, column, msg);
  }

  // The next physical line without its terminator, or nullopt at the end of the file. The view
  // stays valid until the next call.
  std::optional<std::string_view> nextLine() {
    for (;;) {
      if (begin < end) {
        const char* start = buffer.data() + begin;
        const void* nl = std::memchr(start, '\n', end - begin);
        if (nl != nullptr) {
          const auto len = static_cast<std::size_t>(static_cast<const char*>(nl) - start);
          if (len > kMaxLineBytes) fail(line_no + 1, "", lineTooLong(std::string_view(start, len)));
          begin += len + 1;
          consumed += len + 1;
          ++line_no;
          return std::string_view(start, len);
        }
        if (eof) {  // last line without a terminator
          const std::string_view rest(start, end - begin);
          if (rest.size() > kMaxLineBytes) fail(line_no + 1, "", lineTooLong(rest));
          begin = end;
          consumed += rest.size();
          ++line_no;
          return rest;
        }
      } else if (eof) {
        return std::nullopt;
      }
      // Refill: move the partial line to the front, grow the buffer if it is all one line.
      if (begin > 0) {
        std::memmove(buffer.data(), buffer.data() + begin, end - begin);
        end -= begin;
        begin = 0;
      }
      if (end - begin > kMaxLineBytes) {
        fail(line_no + 1, "", lineTooLong(std::string_view(buffer.data() + begin, end - begin)));
      }
      if (end == buffer.size()) buffer.resize(buffer.size() * 2);
      const std::size_t got = std::fread(buffer.data() + end, 1, buffer.size() - end, file);
      if (got == 0) {
        if (std::ferror(file) != 0) fail(line_no + 1, "", "read error");
        eof = true;
      }
      end += got;
    }
  }

  // The cell separator for a file whose header line is `text` (CsvReadOptions::delimiter).
  static char detectDelimiter(std::string_view text) {
    const char candidates[] = {',', ';', '\t'};
    char best = 0;
    std::size_t best_count = 0;
    for (const char c : candidates) {
      const auto n = static_cast<std::size_t>(std::count(text.begin(), text.end(), c));
      if (n > best_count) best = c, best_count = n;
    }
    if (best != 0) return best;
    return text.find_first_of(" \t") != std::string_view::npos ? ' ' : ',';
  }

  // Calls cell(text) for each cell of `text`, split at delim (' ': runs of spaces and tabs).
  template <typename F>
  void splitCells(std::string_view text, F&& cell) const {
    if (delim == ' ') {
      std::size_t pos = text.find_first_not_of(" \t");
      while (pos != std::string_view::npos) {
        const std::size_t stop = text.find_first_of(" \t", pos);
        cell(text.substr(pos, stop == std::string_view::npos ? stop : stop - pos));
        pos = stop == std::string_view::npos ? stop : text.find_first_not_of(" \t", stop);
      }
      return;
    }
    std::size_t pos = 0;
    for (;;) {
      const std::size_t q = text.find(delim, pos);
      cell(text.substr(pos, q == std::string_view::npos ? q : q - pos));
      if (q == std::string_view::npos) break;
      pos = q + 1;
    }
  }

  // Whether every cell of `text` is a number (then a '#' line before it was the header).
  bool isDataRow(std::string_view text) const {
    bool all = true;
    std::size_t cells = 0;
    splitCells(text, [&](std::string_view c) {
      c = detail::trimBlanks(c);
      ++cells;
      if (!c.empty() && c.front() == '+') c.remove_prefix(1);
      double v = 0.0;
      const auto [ptr, ec] = std::from_chars(c.data(), c.data() + c.size(), v);
      if (c.empty() || ptr != c.data() + c.size() || (ec != std::errc() && ec != std::errc::result_out_of_range)) {
        all = false;
      }
    });
    return all && cells > 0;
  }

  void readHeader() {
    std::string hash_header;  // the last '#' line before the first other line
    std::size_t hash_line = 0;
    std::string_view text;
    std::size_t header_line = 0;
    for (;;) {
      const auto line = nextLine();
      if (!line) fail(line_no, "", "no header line (the file is empty)");
      text = detail::trimBlanks(*line);
      if (line_no == 1 && text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // BOM
      if (text.empty()) continue;
      if (text.front() == '#') {
        hash_header = std::string(detail::trimBlanks(text.substr(1)));
        hash_line = line_no;
        continue;
      }
      delim = options.delimiter != 0 ? options.delimiter : detectDelimiter(hash_line > 0 ? hash_header : text);
      if (hash_line > 0 && !hash_header.empty() && isDataRow(text)) {
        pending = std::string(text);  // the first data row, returned by the first next()
        has_pending = true;
        text = hash_header;
        header_line = hash_line;
      } else {
        delim = options.delimiter != 0 ? options.delimiter : detectDelimiter(text);
        header_line = line_no;
      }
      break;
    }
    splitCells(text, [&](std::string_view cell) {
      std::string_view name = detail::trimBlanks(cell);
      if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
      header.emplace_back(name);
      // A unit after the name: z[mm] or z (mm).
      std::string_view bare = name, unit;
      for (const auto& [open, close] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
        const auto at = name.rfind(open);
        if (name.size() > 2 && name.back() == close && at != std::string_view::npos && at > 0) {
          bare = detail::trimBlanks(name.substr(0, at));
          unit = detail::trimBlanks(name.substr(at + 1, name.size() - at - 2));
          break;
        }
      }
      bare_names.emplace_back(bare);
      units.emplace_back(unit);
    });
    for (std::size_t i = 0; i < header.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (header[i] == header[j] && !header[i].empty()) {
          fail(header_line, header[i], "appears twice in the header (cells " +
                                           std::to_string(j + 1) + " and " +
                                           std::to_string(i + 1) + ")");
        }
      }
    }
    slot_of_cell.assign(header.size(), -1);
    std::vector<std::string> missing;
    for (std::size_t k = 0; k < options.columns.size(); ++k) {
      auto it = std::find(header.begin(), header.end(), options.columns[k].name);
      if (it == header.end()) {  // the name without its unit
        const auto b = std::find(bare_names.begin(), bare_names.end(), options.columns[k].name);
        it = header.begin() + (b - bare_names.begin());
      }
      if (it == header.end()) {
        missing.push_back(options.columns[k].name);
      } else {
        slot_of_cell[static_cast<std::size_t>(it - header.begin())] = static_cast<int>(k);
      }
      if (options.columns[k].name == options.time_column) time_slot = static_cast<int>(k);
    }
    if (!missing.empty()) {
      std::string msg = missing.size() == 1 ? "missing column" : "missing columns";
      for (std::size_t i = 0; i < missing.size(); ++i) {
        msg += (i == 0 ? " '" : ", '") + missing[i] + "'";
        // A near miss in the header (differing in case or in about one character in four)
        // that no other requested column claims is most likely the misnamed column.
        std::string best;
        std::size_t best_d = std::min<std::size_t>(2, missing[i].size() / 4) + 1;
        for (std::size_t c = 0; c < header.size(); ++c) {
          if (slot_of_cell[c] >= 0) continue;
          const std::string& h = header[c];
          const std::size_t d = editDistance(missing[i], h);
          if (d < best_d) {
            best_d = d;
            best = h;
          }
        }
        if (!best.empty()) msg += " (did you mean '" + detail::excerpt(best) + "'?)";
      }
      msg += "; found:";
      constexpr std::size_t kShown = 40;  // a hostile header may hold thousands of names
      for (std::size_t i = 0; i < std::min(header.size(), kShown); ++i) {
        msg += (i == 0 ? " " : ", ") + detail::excerpt(header[i]);
      }
      if (header.size() > kShown) msg += ", … (" + std::to_string(header.size() - kShown) + " more)";
      fail(header_line, missing.front(), msg);
    }
    if (!options.time_column.empty() && time_slot < 0) {
      throw std::invalid_argument("CsvReadOptions: time column '" + options.time_column +
                                  "' is not one of the requested columns");
    }
  }

  // The hot path of every cell: a plain decimal in range. Everything else (from_chars, and the
  // messages, which build strings) is in the out-of-line functions below, so that this one and
  // takeCell stay small enough to inline into next().
  double parseCell(std::string_view cell, std::size_t k) const {
    const CsvColumn& col = options.columns[k];
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    if (cell.empty() || blank(cell.front()) || blank(cell.back())) cell = detail::trimBlanks(cell);
    if (cell.empty()) return emptyCell(col);
    const char* first = cell.data();
    const char* last = cell.data() + cell.size();
    if (*first == '+') ++first;
    double v = 0.0;
    if (!detail::parsePlainDecimal(first, last, v)) return parseOther(cell, first, last, col);
    return checkRange(v, cell, col);
  }

  [[gnu::noinline]] double emptyCell(const CsvColumn& col) const {
    if (col.non_finite) return std::numeric_limits<double>::quiet_NaN();
    fail(line_no, col.name, "empty cell, expected a number");
  }

  // A cell parsePlainDecimal does not take: std::from_chars.
  [[gnu::noinline]] double parseOther(std::string_view cell, const char* first, const char* last,
                                      const CsvColumn& col) const {
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec == std::errc::result_out_of_range) {
      fail(line_no, col.name, "'" + detail::excerpt(cell) + "' is out of the range of a double");
    }
    if (ec != std::errc() || ptr != last) {
      fail(line_no, col.name, "expected a number, got '" + detail::excerpt(cell) + "'");
    }
    if (!std::isfinite(v)) {
      if (col.non_finite) return v;
      fail(line_no, col.name, "'" + detail::excerpt(cell) + "' is not finite");
    }
    return checkRange(v, cell, col);
  }

  double checkRange(double v, std::string_view cell, const CsvColumn& col) const {
    if (v < col.min || v > col.max) [[unlikely]] outOfRange(cell, col);
    return v;
  }

  [[noreturn, gnu::noinline, gnu::cold]] void outOfRange(std::string_view cell, const CsvColumn& col) const {
    fail(line_no, col.name, "value " + detail::excerpt(cell) + " is outside the plausible range [" +
                                number(col.min) + ", " + number(col.max) +
                                "] for this column (wrong unit?)");
  }

  void takeCell(std::string_view text, std::size_t cell, std::span<double> values) const {
    if (cell >= slot_of_cell.size()) [[unlikely]] tooManyCells();
    const int slot = slot_of_cell[cell];
    if (slot >= 0) values[static_cast<std::size_t>(slot)] = parseCell(text, static_cast<std::size_t>(slot));
  }

  [[noreturn, gnu::noinline, gnu::cold]] void tooManyCells() const {
    fail(line_no, "", "row has more cells than the header's " + std::to_string(header.size()));
  }

  bool next(std::span<double> values) {
    if (finished) return false;
    if (values.size() != options.columns.size()) {
      throw std::invalid_argument("CsvReader::next: expected " +
                                  std::to_string(options.columns.size()) + " values");
    }
    for (;;) {
      std::optional<std::string_view> line;
      if (has_pending) {
        has_pending = false;
        line = std::string_view(pending);
      } else {
        line = nextLine();
      }
      if (!line) {
        finished = true;
        if (rows < options.min_rows) {
          fail(line_no, "", "only " + std::to_string(rows) + " data rows, at least " +
                                std::to_string(options.min_rows) + " are needed");
        }
        return false;
      }
      std::string_view text = *line;
      if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
      if (detail::trimBlanks(text).empty()) {
        if (blank_line == 0) blank_line = line_no;
        continue;
      }
      if (blank_line != 0) {
        fail(blank_line, "", "empty line inside the data (rows follow on line " +
                                 std::to_string(line_no) + ")");
      }
      // Split and parse only the requested cells.
      std::size_t cell = 0;
      if (delim == ' ') {
        splitCells(text, [&](std::string_view c) { takeCell(c, cell++, values); });
      } else {
        const char* p = text.data();
        const char* const stop = text.data() + text.size();
        for (;;) {
          // Cells are short: a plain scan beats a call to memchr for each.
          const char* q = p;
          while (q != stop && *q != delim) ++q;
          takeCell(std::string_view(p, static_cast<std::size_t>(q - p)), cell++, values);
          if (q == stop) break;
          p = q + 1;
        }
      }
      if (cell != header.size()) {
        fail(line_no, header[cell], "row has " + std::to_string(cell) + " cells, the header " +
                                        std::to_string(header.size()) + " (this column is missing)");
      }
      if (time_slot >= 0) {
        const double t = values[static_cast<std::size_t>(time_slot)];
        if (rows > 0 && !(t > last_time)) {
          const std::string& name = options.columns[static_cast<std::size_t>(time_slot)].name;
          if (t == last_time) {
            fail(line_no, name, "duplicated timestamp " + number(t) + " (also on line " +
                                    std::to_string(last_time_line) + ")");
          }
          fail(line_no, name, "timestamp " + number(t) + " is earlier than " + number(last_time) +
                                  " on line " + std::to_string(last_time_line) +
                                  " (timestamps must increase)");
        }
        last_time = t;
        last_time_line = line_no;
      }
      ++rows;
      row_line = line_no;
      return true;
    }
  }
};

CsvReader::CsvReader(const std::filesystem::path& file, CsvReadOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->source = file.string();
  impl_->options = std::move(options);
  noteInputFile(file, "CSV file");
  impl_->file = std::fopen(file.c_str(), "rb");
  if (impl_->file == nullptr) {
    throw CsvError(impl_->source, 0, "", std::string("cannot open: ") + std::strerror(errno));
  }
  impl_->buffer.resize(std::max<std::size_t>(impl_->options.buffer_bytes, 64));
  impl_->readHeader();
}

CsvReader::CsvReader(std::string_view text, const std::string& source, CsvReadOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->source = source;
  impl_->options = std::move(options);
  // fmemopen refuses a zero-length buffer: an empty text reads as /dev/null does.
  impl_->file = text.empty() ? std::fopen("/dev/null", "rb")
                             : fmemopen(const_cast<char*>(text.data()), text.size(), "rb");
  if (impl_->file == nullptr) {
    throw CsvError(impl_->source, 0, "", std::string("cannot read from memory: ") + std::strerror(errno));
  }
  impl_->buffer.resize(std::max<std::size_t>(impl_->options.buffer_bytes, 64));
  impl_->readHeader();
}

CsvReader::~CsvReader() = default;
CsvReader::CsvReader(CsvReader&&) noexcept = default;
CsvReader& CsvReader::operator=(CsvReader&&) noexcept = default;

bool CsvReader::next(std::span<double> values) { return impl_->next(values); }
std::size_t CsvReader::columnCount() const noexcept { return impl_->options.columns.size(); }
std::size_t CsvReader::rowsRead() const noexcept { return impl_->rows; }
std::size_t CsvReader::line() const noexcept { return impl_->row_line; }
std::size_t CsvReader::bytesRead() const noexcept { return impl_->consumed; }
const std::string& CsvReader::source() const noexcept { return impl_->source; }
const std::vector<std::string>& CsvReader::header() const noexcept { return impl_->header; }
const std::vector<std::string>& CsvReader::units() const noexcept { return impl_->units; }
char CsvReader::delimiter() const noexcept { return impl_->delim; }

}  // namespace geaware::io
