// SPDX-License-Identifier: BSD-3-Clause
// Column expressions (io/column_expression.hpp): a recursive-descent parser, units and a
// vectorised evaluator.

#include "geaware/io/column_expression.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>

#include "text.hpp"

namespace geaware::io {
namespace {

std::string quoted(std::string_view s) { return "'" + detail::excerpt(s) + "'"; }

}  // namespace

// ------------------------------------------------------------------------------ parser

class ExpressionParser {
 public:
  ExpressionParser(ColumnExpression& e, std::string_view text, std::size_t offset)
      : e_(e), text_(text), offset_(offset) {}

  void run() {
    skipBlanks();
    if (pos_ == text_.size())
      fail(pos_, "expected an expression (a field, a number or a parenthesis), found nothing");
    (void)expr();
    skipBlanks();
    if (pos_ < text_.size()) {
      fail(pos_, "expected an operator (+ - * /) or the end, found " + found());
    }
  }

 private:
  using Kind = ColumnExpression::Node::Kind;

  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    throw ExpressionError(e_.where_ + ": character " + std::to_string(offset_ + at + 1) + ": " +
                          message);
  }
  std::string found() const {
    if (pos_ >= text_.size()) return "the end";
    return "'" + std::string(1, text_[pos_]) + "'";
  }
  void skipBlanks() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }
  int add(ColumnExpression::Node n) {
    if (e_.nodes_.size() >= 10000) fail(n.offset, "expression too long (at most 10000 terms)");
    e_.nodes_.push_back(n);
    return static_cast<int>(e_.nodes_.size() - 1);
  }
  static bool nameStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_' ||
           static_cast<unsigned char>(c) >= 0x80;
  }
  static bool nameChar(char c) {
    return nameStart(c) || std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '.' ||
           c == ':' || c == '#' || c == '@';
  }

  int expr() {
    int left = term();
    for (;;) {
      skipBlanks();
      if (pos_ >= text_.size() || (text_[pos_] != '+' && text_[pos_] != '-')) return left;
      const std::size_t at = pos_;
      const Kind k = text_[pos_++] == '+' ? Kind::kAdd : Kind::kSub;
      const int right = term();
      left = add({k, left, right, 0.0, -1, nullptr, offset_ + at});
    }
  }
  int term() {
    int left = unary();
    for (;;) {
      skipBlanks();
      if (pos_ >= text_.size() || (text_[pos_] != '*' && text_[pos_] != '/')) return left;
      const std::size_t at = pos_;
      const Kind k = text_[pos_++] == '*' ? Kind::kMul : Kind::kDiv;
      const int right = unary();
      left = add({k, left, right, 0.0, -1, nullptr, offset_ + at});
    }
  }
  int unary() {
    skipBlanks();
    if (pos_ < text_.size() && text_[pos_] == '-') {
      const std::size_t at = pos_++;
      if (++depth_ > 200) fail(at, "too deeply nested (at most 200 levels)");
      const int a = unary();
      --depth_;
      return add({Kind::kNeg, a, -1, 0.0, -1, nullptr, offset_ + at});
    }
    if (pos_ < text_.size() && text_[pos_] == '+') ++pos_;
    return postfix();
  }
  int postfix() {
    const int a = primary();
    skipBlanks();
    if (pos_ >= text_.size() || text_[pos_] != '[') return a;
    const std::size_t open = pos_++;
    const std::size_t close = text_.find(']', pos_);
    if (close == std::string_view::npos)
      fail(open, "expected ']' closing the unit that starts here");
    const std::string_view name = detail::trimBlanks(text_.substr(pos_, close - pos_));
    const Unit* u = findUnit(name);
    if (u == nullptr) {
      fail(pos_, "unknown unit " + quoted(name) + " (expected one of: " + knownUnitNames() + ")");
    }
    pos_ = close + 1;
    return add({Kind::kUnit, a, -1, 0.0, -1, u, offset_ + open});
  }
  int primary() {
    skipBlanks();
    if (pos_ >= text_.size()) fail(pos_, "expected a field, a number or '(', found the end");
    const char c = text_[pos_];
    const std::size_t at = pos_;
    if (c == '(') {
      ++pos_;
      if (++depth_ > 200) fail(at, "too deeply nested (at most 200 levels)");
      const int a = expr();
      --depth_;
      skipBlanks();
      if (pos_ >= text_.size() || text_[pos_] != ')')
        fail(pos_, "expected ')' closing the '(' at character " + std::to_string(offset_ + at + 1) +
                       ", found " + found());
      ++pos_;
      return a;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '.') return number();
    if (c == '"') return quotedField();
    if (nameStart(c)) return nameOrCall();
    fail(pos_, "expected a field, a number or '(', found " + found());
  }
  int number() {
    const std::size_t at = pos_;
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(text_.data() + pos_, text_.data() + text_.size(), v);
    if (ec != std::errc() || !std::isfinite(v))
      fail(at, "expected a finite number, found " + found());
    pos_ = static_cast<std::size_t>(ptr - text_.data());
    if (pos_ < text_.size() && nameStart(text_[pos_])) {
      fail(pos_, "expected an operator after the number, found " + found() +
                     " (a unit goes in brackets, e.g. 5[mm]; a field starting with a digit in "
                     "double quotes)");
    }
    return add({Kind::kNumber, -1, -1, v, -1, nullptr, offset_ + at});
  }
  int field(std::string name, std::size_t at) {
    int index = -1;
    for (std::size_t i = 0; i < e_.fields_.size(); ++i) {
      if (e_.fields_[i] == name) index = static_cast<int>(i);
    }
    if (index < 0) {
      e_.fields_.push_back(std::move(name));
      index = static_cast<int>(e_.fields_.size() - 1);
    }
    return add({Kind::kField, -1, -1, 0.0, index, nullptr, offset_ + at});
  }
  int quotedField() {
    const std::size_t at = pos_++;
    const std::size_t close = text_.find('"', pos_);
    if (close == std::string_view::npos)
      fail(at, "expected '\"' closing the field name that starts here");
    if (close == pos_) fail(at, "expected a field name between the double quotes, found none");
    const std::string name(text_.substr(pos_, close - pos_));
    pos_ = close + 1;
    return field(name, at);
  }
  // A name: name characters, array elements `[digits]`, and blanks between words.
  int nameOrCall() {
    const std::size_t at = pos_;
    std::size_t end = pos_;
    bool plain = true;  // letters, digits and '_' only (a function name)
    for (;;) {
      while (end < text_.size() && nameChar(text_[end])) {
        plain = plain && text_[end] != '.' && text_[end] != ':' && text_[end] != '#' &&
                text_[end] != '@';
        ++end;
      }
      if (end < text_.size() && text_[end] == '[') {
        std::size_t k = end + 1;
        while (k < text_.size() && std::isdigit(static_cast<unsigned char>(text_[k])) != 0) ++k;
        if (k > end + 1 && k < text_.size() && text_[k] == ']') {
          end = k + 1, plain = false;
          continue;
        }
        break;  // a unit
      }
      std::size_t next = end;
      while (next < text_.size() && (text_[next] == ' ' || text_[next] == '\t')) ++next;
      if (next > end && next < text_.size() && nameStart(text_[next])) {
        end = next, plain = false;
        continue;
      }
      break;
    }
    const std::string name(detail::trimBlanks(text_.substr(at, end - at)));
    pos_ = end;
    skipBlanks();
    if (pos_ < text_.size() && text_[pos_] == '(') {
      if (!plain || name != "delta") {
        fail(pos_, "'" + detail::excerpt(name) +
                       "' followed by '(': the only function is delta(…); a unit goes in "
                       "brackets, e.g. thrust[kgf]");
      }
      const std::size_t open = pos_++;
      if (++depth_ > 200) fail(at, "too deeply nested (at most 200 levels)");
      const int a = expr();
      --depth_;
      skipBlanks();
      if (pos_ >= text_.size() || text_[pos_] != ')') {
        fail(pos_, "expected ')' closing delta( at character " +
                       std::to_string(offset_ + open + 1) + ", found " + found());
      }
      ++pos_;
      return add({Kind::kDelta, a, -1, 0.0, -1, nullptr, offset_ + at});
    }
    return field(name, at);
  }

  ColumnExpression& e_;
  std::string_view text_;
  std::size_t offset_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

ColumnExpression ColumnExpression::parse(std::string_view text, const std::string& where,
                                         std::size_t offset) {
  ColumnExpression e;
  e.text_ = std::string(text);
  e.where_ = where;
  ExpressionParser(e, text, offset).run();
  return e;
}

bool ColumnExpression::hasUnits() const noexcept {
  for (const auto& n : nodes_) {
    if (n.kind == Node::Kind::kUnit) return true;
  }
  return false;
}

bool ColumnExpression::isField() const noexcept {
  return nodes_.size() == 1 && nodes_.front().kind == Node::Kind::kField;
}

std::size_t ColumnExpression::lag() const noexcept {
  // Nodes are stored children first: one pass computes each node's depth of delta.
  std::vector<std::size_t> depth(nodes_.size(), 0);
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    std::size_t d = 0;
    if (n.a >= 0) d = depth[static_cast<std::size_t>(n.a)];
    if (n.b >= 0) d = std::max(d, depth[static_cast<std::size_t>(n.b)]);
    depth[i] = d + (n.kind == Node::Kind::kDelta ? 1 : 0);
  }
  return depth.empty() ? 0 : depth.back();
}

std::size_t ColumnExpression::fieldOffset(std::size_t k) const noexcept {
  for (const auto& n : nodes_) {
    if (n.kind == Node::Kind::kField && static_cast<std::size_t>(n.field) == k) return n.offset;
  }
  return 0;
}

// ---------------------------------------------------------------------------- evaluation

namespace {

// What is known of a value's unit: a dimension (its values are SI), none (a bare number,
// dimensionless and adopting), or unknown (a field without a unit: in the column's unit).
struct Quantity {
  enum class Kind : std::uint8_t { kKnown, kNumber, kUnknown } kind = Kind::kNumber;
  Dimension dimension;
};

class Evaluator {
 public:
  using Node = ColumnExpression::Node;
  using Kind = Node::Kind;
  Evaluator(const ColumnExpression& e, std::span<const ColumnExpression::FieldData> fields,
            std::size_t rows, bool log_units, const std::vector<Node>& nodes)
      : e_(e), fields_(fields), rows_(rows), log_units_(log_units), nodes_(nodes) {}

  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    throw ExpressionError(e_.where() + ": character " + std::to_string(at + 1) + ": " + message);
  }

  // The values of node `i` (SI where its quantity is known) and its quantity.
  std::vector<double> eval(int i, Quantity& q) {
    const Node& n = nodes_[static_cast<std::size_t>(i)];
    switch (n.kind) {
      case Kind::kNumber:
        q = {};
        return std::vector<double>(rows_, n.value);
      case Kind::kField:
        return field(n, q);
      case Kind::kUnit: {
        auto v = eval(n.a, q);
        if (q.kind == Quantity::Kind::kKnown) {
          fail(n.offset,
               "a unit for a value that has one already (" + dimensionName(q.dimension) + ")");
        }
        for (auto& x : v) x *= n.unit->to_si;
        q = {Quantity::Kind::kKnown, n.unit->dimension};
        return v;
      }
      case Kind::kNeg: {
        auto v = eval(n.a, q);
        for (auto& x : v) x = -x;
        return v;
      }
      case Kind::kDelta: {
        auto v = eval(n.a, q);
        for (std::size_t k = v.size(); k-- > 1;) v[k] -= v[k - 1];
        if (!v.empty()) v[0] = std::numeric_limits<double>::quiet_NaN();
        return v;
      }
      case Kind::kAdd:
      case Kind::kSub:
      case Kind::kMul:
      case Kind::kDiv:
        return binary(n, q);
    }
    return {};
  }

 private:
  std::vector<double> field(const Node& n, Quantity& q) {
    const auto& f = fields_[static_cast<std::size_t>(n.field)];
    q = {Quantity::Kind::kUnknown, {}};
    std::vector<double> v(f.values.begin(), f.values.end());
    const Unit* u = log_units_ ? findUnit(detail::trimBlanks(f.log_unit)) : nullptr;
    // A field read with a unit written after it takes that one, not the log's.
    const bool overridden = parentIsUnit(n);
    if (u != nullptr && !overridden) {
      for (auto& x : v) x *= u->to_si;
      q = {Quantity::Kind::kKnown, u->dimension};
    }
    return v;
  }
  bool parentIsUnit(const Node& child) const {
    for (const auto& p : nodes_) {
      if (p.kind == Kind::kUnit && &nodes_[static_cast<std::size_t>(p.a)] == &child) return true;
    }
    return false;
  }
  std::vector<double> binary(const Node& n, Quantity& q) {
    Quantity qa, qb;
    auto a = eval(n.a, qa);
    const auto b = eval(n.b, qb);
    using QK = Quantity::Kind;
    if (n.kind == Kind::kAdd || n.kind == Kind::kSub) {
      if (qa.kind == QK::kKnown && qb.kind == QK::kKnown && !(qa.dimension == qb.dimension)) {
        fail(n.offset, "cannot " + std::string(n.kind == Kind::kAdd ? "add" : "subtract") +
                           ": the left side is " + dimensionName(qa.dimension) +
                           ", the right side " + dimensionName(qb.dimension));
      }
      if ((qa.kind == QK::kKnown) != (qb.kind == QK::kKnown)) {
        const Quantity& known = qa.kind == QK::kKnown ? qa : qb;
        if (!(known.dimension == Dimension{})) {
          fail(n.offset, "one side is " + dimensionName(known.dimension) +
                             ", the other has no unit: give it one, e.g. 5[mm] or field[m]");
        }
      }
      q = qa.kind == QK::kKnown   ? qa
          : qb.kind == QK::kKnown ? qb
                                  : (qa.kind == QK::kUnknown ? qa : qb);
      const double sign = n.kind == Kind::kAdd ? 1.0 : -1.0;
      for (std::size_t k = 0; k < a.size(); ++k) a[k] += sign * b[k];
      return a;
    }
    const bool mul = n.kind == Kind::kMul;
    if (qa.kind == QK::kUnknown || qb.kind == QK::kUnknown) {
      const Quantity& other = qa.kind == QK::kUnknown ? qb : qa;
      if (other.kind == QK::kKnown && !(other.dimension == Dimension{})) {
        fail(n.offset, "one side is " + dimensionName(other.dimension) +
                           ", the other a field without a unit: give it one, e.g. field[m]");
      }
      q = {QK::kUnknown, {}};
    } else if (qa.kind == QK::kKnown || qb.kind == QK::kKnown) {
      Dimension d = qa.kind == QK::kKnown ? qa.dimension : Dimension{};
      const Dimension db = qb.kind == QK::kKnown ? qb.dimension : Dimension{};
      for (std::size_t k = 0; k < d.e.size(); ++k)
        d.e[k] = static_cast<std::int8_t>(d.e[k] + (mul ? db.e[k] : -db.e[k]));
      q = {QK::kKnown, d};
    } else {
      q = {};
    }
    for (std::size_t k = 0; k < a.size(); ++k) a[k] = mul ? a[k] * b[k] : a[k] / b[k];
    return a;
  }

  const ColumnExpression& e_;
  std::span<const ColumnExpression::FieldData> fields_;
  std::size_t rows_;
  bool log_units_;
  const std::vector<Node>& nodes_;
};

}  // namespace

std::vector<double> ColumnExpression::evaluate(std::span<const FieldData> fields, std::size_t rows,
                                               const Unit* target, const std::string& target_name,
                                               bool log_units) const {
  if (fields.size() != fields_.size()) {
    throw std::logic_error("ColumnExpression::evaluate: " + std::to_string(fields.size()) +
                           " fields given for " + std::to_string(fields_.size()));
  }
  for (const auto& f : fields) {
    if (f.values.size() != rows)
      throw std::logic_error("ColumnExpression::evaluate: a field's length is not rows");
  }
  Evaluator ev(*this, fields, rows, log_units, nodes_);
  Quantity q;
  auto v = ev.eval(static_cast<int>(nodes_.size() - 1), q);
  if (q.kind != Quantity::Kind::kKnown) return v;  // in the column's unit already
  const Dimension want = target != nullptr ? target->dimension : Dimension{};
  if (!(q.dimension == want)) {
    ev.fail(nodes_.back().offset, "the expression gives " + dimensionName(q.dimension) +
                                      ", column '" + target_name + "' " +
                                      (target != nullptr ? "holds " + dimensionName(want) + " [" +
                                                               std::string(target->name) + "]"
                                                         : std::string("is dimensionless")));
  }
  if (target != nullptr && target->to_si != 1.0) {
    for (auto& x : v) x /= target->to_si;
  }
  return v;
}

ColumnDefinition parseColumnDefinition(std::string_view spec, std::string_view option,
                                       bool constant) {
  const std::string where = std::string(option) + " '" + detail::excerpt(spec) + "'";
  const auto eq = spec.find('=');
  if (eq == std::string_view::npos) {
    throw ExpressionError(
        where + ": character " + std::to_string(spec.size() + 1) +
        ": expected NAME=" + (constant ? "VALUE, e.g. tilt_deg=0" : "EXPR, e.g. h_m=z[mm]"));
  }
  const std::string name(detail::trimBlanks(spec.substr(0, eq)));
  if (name.empty())
    throw ExpressionError(where + ": character 1: expected a column name before '='");
  for (std::size_t i = 0; i < eq; ++i) {
    const char c = spec[i];
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '_' && c != ' ') {
      throw ExpressionError(
          where + ": character " + std::to_string(i + 1) +
          ": expected a column name of letters, digits and '_' before '=', found '" +
          std::string(1, c) + "'");
    }
  }
  ColumnDefinition d{name, ColumnExpression::parse(spec.substr(eq + 1), where, eq + 1), where};
  if (constant && !d.expression.fields().empty()) {
    throw ExpressionError(where + ": character " + std::to_string(eq + 2) +
                          ": expected a number (with a unit, e.g. "
                          "120[mm]), found the field '" +
                          d.expression.fields().front() + "'");
  }
  return d;
}

}  // namespace geaware::io
