// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A parameter schema: one row per parameter of a parameter struct T — its key path in the
// parameter file, its unit, its valid range and an accessor into T — so that the loader
// (io/param_reader.hpp), the range validation, the vehicle-file writer's read-back, merges of
// identified values, cache keys, printed rows and the documentation's parameter list all work
// from the same table instead of each listing the fields by hand.
//
// Generic over T and free of I/O. Three kinds of parameter: a number, a list of numbers (a
// column of a table: the columns sharing `table` are read and checked together, the first one
// being the strictly increasing heights), and a text. A curve may be given in one of two forms,
// by its formula's keys or as a table under "<curve>.table": the form in use is the table when
// any of its columns is non-empty (ParamSchema::tableInUse), and only the form in use is
// validated, visited and merged.

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/model/field_check.hpp"
#include "geaware/model/field_error.hpp"

namespace geaware::model {

enum class ParamKind : std::uint8_t { kNumber, kList, kText };

/// Which form of a curve a parameter belongs to.
enum class ParamForm : std::uint8_t {
  kAlways,   ///< not part of an alternative
  kFormula,  ///< one of the curve's formula keys
  kTable,    ///< a column of the curve's table
};

/// The valid values of a number or of every entry of a list: lo ≤ v (lo < v when `lower` is
/// kExclusive) and v ≤ hi, finite.
struct ParamRange {
  double lo = 0.0;
  double hi = 0.0;
  LowerBound lower = LowerBound::kInclusive;
};

/// One parameter.
template <class T>
struct ParamSpec {
  std::string_view key;    ///< key path in the file, dot separated: "rotor.k_T_N_per_rpm2"
  std::string_view unit;   ///< SI unit as written in the docs ("N/rpm²"); empty: dimensionless
  std::string_view note;   ///< said after the unit in range errors, e.g. "(n² at zero throttle)"
  ParamKind kind = ParamKind::kNumber;
  ParamRange range;        ///< numbers and every entry of a list
  double& (*number)(T&) = nullptr;              ///< kNumber
  std::vector<double>& (*list)(T&) = nullptr;   ///< kList
  std::string& (*text)(T&) = nullptr;           ///< kText
  ParamForm form = ParamForm::kAlways;
  std::string_view curve;  ///< kFormula, kTable: the curve's section ("ground_effect.…")
  std::string_view table;  ///< kList: the table the column belongs to ("drag", "<curve>.table")
  std::size_t min_rows = 1;  ///< first column of a table: the fewest rows allowed
  bool fitted = false;       ///< identification may write it (io::VehicleUpdate)
  /// A number the file may leave out: the struct's default value is then kept.
  bool optional = false;

  /// The unit and note as range errors print them.
  [[nodiscard]] std::string unitText() const {
    std::string s(unit);
    if (!note.empty()) s += (s.empty() ? "" : " ") + std::string(note);
    return s;
  }
  /// What a valid value is, as the docs' parameter list gives it: "(0, 1000]", "[−1e12, 1e12]",
  /// "(0, 100], strictly increasing, ≥ 2 entries" (a table's heights), "[0, 100], one per
  /// height" (its other columns), "text".
  [[nodiscard]] std::string validText(bool first_column) const {
    if (kind == ParamKind::kText) return "text";
    if (optional) return validRange() + ", optional";
    return validRange(first_column);
  }
  /// validText without "optional".
  [[nodiscard]] std::string validRange(bool first_column = false) const {
    auto num = [](double v) {
      std::string s = formatValue(v);
      if (const auto e = s.find("e+"); e != std::string::npos) s.erase(e + 1, 1);
      if (s.front() == '-') s = "−" + s.substr(1);
      return s;
    };
    std::string r = (range.lower == LowerBound::kExclusive ? "(" : "[") + num(range.lo) + ", " +
                    num(range.hi) + "]";
    if (kind == ParamKind::kList) {
      r += first_column ? ", strictly increasing, ≥ " + std::to_string(min_rows) +
                              (min_rows == 1 ? " entry" : " entries")
                        : ", one per height";
    }
    return r;
  }
  [[nodiscard]] double numberOf(const T& t) const { return number(const_cast<T&>(t)); }
  [[nodiscard]] const std::vector<double>& listOf(const T& t) const {
    return list(const_cast<T&>(t));
  }
  [[nodiscard]] const std::string& textOf(const T& t) const { return text(const_cast<T&>(t)); }
};

/// A check across parameters, run by validate() right after the parameter `after` and only when
/// every parameter in `needs` passed its own range check.
template <class T>
struct ParamRule {
  std::string_view after;
  std::vector<std::string_view> needs;
  void (*check)(const T&, FieldChecker&) = nullptr;
};

template <class T>
class ParamSchema {
 public:
  ParamSchema(std::vector<ParamSpec<T>> specs, std::vector<ParamRule<T>> rules)
      : specs_(std::move(specs)), rules_(std::move(rules)) {}

  [[nodiscard]] const std::vector<ParamSpec<T>>& specs() const noexcept { return specs_; }

  /// The parameter at `key`, or null.
  [[nodiscard]] const ParamSpec<T>* find(std::string_view key) const {
    for (const auto& s : specs_) {
      if (s.key == key) return &s;
    }
    return nullptr;
  }

  /// Whether `curve` is given as a table in `t` (any of its table's columns non-empty).
  [[nodiscard]] bool tableInUse(const T& t, std::string_view curve) const {
    for (const auto& s : specs_) {
      if (s.form == ParamForm::kTable && s.curve == curve && !s.listOf(t).empty()) return true;
    }
    return false;
  }

  /// Whether the parameter is in use in `t`: not part of a curve's form that `t` does not use.
  [[nodiscard]] bool inUse(const ParamSpec<T>& s, const T& t) const {
    if (s.form == ParamForm::kAlways) return true;
    return tableInUse(t, s.curve) == (s.form == ParamForm::kTable);
  }

  /// The columns of `table`, first (the heights) first.
  [[nodiscard]] std::vector<const ParamSpec<T>*> columns(std::string_view table) const {
    std::vector<const ParamSpec<T>*> out;
    for (const auto& s : specs_) {
      if (s.kind == ParamKind::kList && s.table == table) out.push_back(&s);
    }
    return out;
  }

  /// Every range, table and cross-parameter check of the parameters in use, in table order.
  void validate(const T& t, FieldChecker& c, std::vector<FieldError>& errors) const;

 private:
  void checkTable(const T& t, std::string_view table, FieldChecker& c) const;

  std::vector<ParamSpec<T>> specs_;
  std::vector<ParamRule<T>> rules_;
};

/// Visits every parameter in use, in table order, as fn(spec, value) with value a double, a
/// const std::vector<double>& or a const std::string&.
template <class T, class Fn>
void visitParameters(const ParamSchema<T>& schema, const T& t, Fn&& fn) {
  for (const auto& s : schema.specs()) {
    if (!schema.inUse(s, t)) continue;
    switch (s.kind) {
      case ParamKind::kNumber: fn(s, s.numberOf(t)); break;
      case ParamKind::kList: fn(s, s.listOf(t)); break;
      case ParamKind::kText: fn(s, s.textOf(t)); break;
    }
  }
}

/// `base` with the parameters at `keys` taken from `update`. A key is a parameter's key or a
/// table's ("drag", "<curve>.table": all its columns). Taking a curve's formula key empties the
/// curve's table in the result (the formula is then in use); taking its table keeps the formula
/// keys, which a table makes unused. Throws std::invalid_argument for an unknown key.
template <class T>
[[nodiscard]] T mergeParameters(const ParamSchema<T>& schema, T base, const T& update,
                                const std::vector<std::string>& keys) {
  auto take = [&](const ParamSpec<T>& s) {
    switch (s.kind) {
      case ParamKind::kNumber: s.number(base) = s.numberOf(update); break;
      case ParamKind::kList: s.list(base) = s.listOf(update); break;
      case ParamKind::kText: s.text(base) = s.textOf(update); break;
    }
  };
  for (const auto& key : keys) {
    const auto cols = schema.columns(key);
    if (!cols.empty()) {
      for (const auto* s : cols) take(*s);
      continue;
    }
    const ParamSpec<T>* s = schema.find(key);
    if (s == nullptr) throw std::invalid_argument("mergeParameters: unknown parameter '" + key + "'");
    take(*s);
    if (s->form == ParamForm::kFormula) {
      for (const auto& other : schema.specs()) {
        if (other.form == ParamForm::kTable && other.curve == s->curve) other.list(base).clear();
      }
    }
  }
  return base;
}

// ------------------------------------------------------------------------------ validation

template <class T>
void ParamSchema<T>::checkTable(const T& t, std::string_view table, FieldChecker& c) const {
  const auto cols = columns(table);
  const ParamSpec<T>& heights = *cols.front();
  const std::vector<double>& h = heights.listOf(t);
  const std::size_t n = h.size();
  const std::string key(table);
  const std::string h_key(heights.key);
  if (n < heights.min_rows) {
    if (n == 0 && heights.min_rows == 1) {
      c.fail(h_key, "[]", "at least one height");
    } else {
      c.fail(h_key, std::to_string(n) + " heights",
             "at least " + std::to_string(heights.min_rows) + " heights");
    }
    return;
  }
  bool same = true;
  for (const auto* col : cols) same = same && col->listOf(t).size() == n;
  if (!same) {
    std::string value;
    std::string names;
    for (std::size_t j = 0; j < cols.size(); ++j) {
      const std::string name(cols[j]->key.substr(key.size() + 1));
      value += (j == 0 ? "" : ", ") + name + ": " + std::to_string(cols[j]->listOf(t).size());
      names += (j == 0 ? "" : j + 1 == cols.size() ? " and " : ", ") + name;
    }
    c.fail(key, value + " entries", "the same number of entries in " + names);
    return;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    bool h_ok = true;
    for (const auto* col : cols) {
      const bool ok = c.range(std::string(col->key) + idx, col->listOf(t)[i], col->range.lo,
                              col->range.hi, col->range.lower, col->unitText());
      if (col == cols.front()) h_ok = ok;
    }
    if (h_ok && i > 0 && !(h[i] > h[i - 1])) {
      c.fail(h_key + idx, formatValue(h[i]),
             "strictly greater than the previous height " + formatValue(h[i - 1]) + " m");
    }
  }
}

template <class T>
void ParamSchema<T>::validate(const T& t, FieldChecker& c, std::vector<FieldError>& errors) const {
  std::vector<std::string_view> failed;
  std::vector<std::string_view> tables_done;
  for (const auto& s : specs_) {
    if (!inUse(s, t)) continue;
    const std::size_t before = errors.size();
    if (s.kind == ParamKind::kNumber) {
      c.range(s.key, s.numberOf(t), s.range.lo, s.range.hi, s.range.lower, s.unitText());
    } else if (s.kind == ParamKind::kList) {
      bool done = false;
      for (const auto tb : tables_done) done = done || tb == s.table;
      if (!done) {
        checkTable(t, s.table, c);
        tables_done.push_back(s.table);
      }
    }
    if (errors.size() != before) failed.push_back(s.key);
    for (const auto& r : rules_) {
      if (r.after != s.key) continue;
      bool ok = true;
      for (const auto need : r.needs) {
        for (const auto f : failed) ok = ok && f != need;
      }
      if (ok) r.check(t, c);
    }
  }
}

}  // namespace geaware::model
