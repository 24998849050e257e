// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Columns defined by the user (issue 11 item 2): `--column NAME=EXPR`, `--const NAME=VALUE` and
// the `fields:` of a log map are small expressions over a log's fields, with units
// (docs/identification.md, "Columns from expressions"):
//
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := '-' unary | postfix
//   postfix := primary ['[' UNIT ']']
//   primary := NUMBER | FIELD | '(' expr ')' | 'delta' '(' expr ')'
//
// A FIELD is a log's field name: letters, digits, '_', '.', ':', '#', '@' and non-ASCII bytes,
// not starting with a digit, with array elements (`esc[2].esc_rpm`, `q[0]`) and inner blanks
// (`Motor Electrical Speed`) allowed; any other name in double quotes (`"ESC-1 (rpm)"`). A
// topic may prefix it: `sensor_combined.gyro_rad[0]`, `IMU[1].GyrX` (instance 1). `[UNIT]` after
// a field, number or parenthesis converts from that unit into SI (mm → m, deg/s → rad/s, g →
// m/s², µs → s, mV → V, rpm → rad/s); `delta(x)` is x minus its previous sample (NaN for the
// first), so `delta(vel.x[m/s]) / delta(t[s])` is an acceleration. A field without a unit takes
// the unit its log declares (a CSV header `z[mm]`, ArduPilot's FMTU) when that is a known unit.
//
// The result is converted from SI into the unit of the column it defines, read from the
// column's name (`h_m` m, `tilt_deg` deg, `n1_rpm` rpm, `a_x_mps2` m/s², `gyro_x_radps` rad/s,
// `vbat_V` V; a name without a unit suffix is dimensionless): a length given for an rpm column
// is an error. An expression with no unit at all (a field the log gives no unit, a bare number)
// is taken to be in the column's unit already (`--const tilt_deg=0`, `--column fz_N=Fz`).
//
// Every error names the option (or the map file and line), the character (1-based, counted in
// the option's value as typed) and what was expected.

#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/io/units.hpp"

namespace geaware::io {

/// A bad expression or definition. what() is "WHERE: character N: MESSAGE".
class ExpressionError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A parsed expression.
class ColumnExpression {
 public:
  /// Parses `text`. `where` names it in messages ("--column 'h_m=z[mm]'", "map.yaml:12:
  /// fields"), `offset` is the position of text[0] in what the user typed (0-based).
  static ColumnExpression parse(std::string_view text, const std::string& where,
                                std::size_t offset = 0);

  [[nodiscard]] const std::string& text() const noexcept { return text_; }
  [[nodiscard]] const std::string& where() const noexcept { return where_; }
  /// The fields it reads, each once, in order of first use.
  [[nodiscard]] const std::vector<std::string>& fields() const noexcept { return fields_; }
  /// Whether a unit is written in it (then its value is SI).
  [[nodiscard]] bool hasUnits() const noexcept;
  /// Whether it is a single field, as written (a plain rename).
  [[nodiscard]] bool isField() const noexcept;
  /// The number of leading samples delta() makes NaN (its deepest nesting; 0 without delta).
  [[nodiscard]] std::size_t lag() const noexcept;
  /// Where field k is first written (0-based character in what the user typed).
  [[nodiscard]] std::size_t fieldOffset(std::size_t k) const noexcept;

  /// One field's samples and the unit its log declares (empty: none).
  struct FieldData {
    std::span<const double> values;
    std::string_view log_unit;
  };
  /// The values of the expression for `rows` samples, in `target`'s unit (nullptr:
  /// dimensionless), from `fields` (one per fields(), each with `rows` values). With
  /// `log_units` false, the units logs declare are not used (the caller scales). Throws
  /// ExpressionError naming the character where the units disagree.
  [[nodiscard]] std::vector<double> evaluate(std::span<const FieldData> fields, std::size_t rows,
                                             const Unit* target, const std::string& target_name,
                                             bool log_units = true) const;

  struct Node {
    enum class Kind : std::uint8_t { kNumber, kField, kNeg, kAdd, kSub, kMul, kDiv, kDelta, kUnit };
    Kind kind = Kind::kNumber;
    int a = -1, b = -1;          ///< operands (node indices)
    double value = 0.0;          ///< kNumber
    int field = -1;              ///< kField: index into fields()
    const Unit* unit = nullptr;  ///< kUnit
    std::size_t offset = 0;      ///< character (0-based, in what the user typed)
  };

 private:
  friend class ExpressionParser;
  std::string text_;
  std::string where_;
  std::vector<std::string> fields_;
  std::vector<Node> nodes_;  ///< the root is the last
};

/// `--column NAME=EXPR` or `--const NAME=VALUE`: a column defined by an expression.
struct ColumnDefinition {
  std::string name;  ///< the column it defines (h_m, n1_rpm, …)
  ColumnExpression expression;
  std::string option;  ///< "--column 'h_m=z[mm]'" for messages
};
/// Parses "NAME=EXPR" given to `option` ("--column"); with `constant`, EXPR must not read a
/// field ("--const"). Throws ExpressionError naming the option and the character.
[[nodiscard]] ColumnDefinition parseColumnDefinition(std::string_view spec, std::string_view option,
                                                     bool constant = false);

}  // namespace geaware::io
