// SPDX-License-Identifier: BSD-3-Clause
#include "vehicle_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "geaware/model/vehicle_schema.hpp"

namespace geaware::io::detail {
namespace {

const VehicleUpdate::Entry* entryFor(const VehicleUpdate& u, const std::string& key, bool table) {
  for (const auto& e : u.entries()) {
    if (e.key == key && e.table == table) return &e;
  }
  return nullptr;
}

std::string joinKeys(const std::vector<std::string>& keys) {
  std::string s;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    s += (i == 0 ? "" : i + 1 == keys.size() ? " and " : ", ") + keys[i];
  }
  return s;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

std::size_t indentOf(const std::string& line) {
  const std::size_t i = line.find_first_not_of(' ');
  return i == std::string::npos ? line.size() : i;
}

/// The last line any node under `node` starts on.
int lastLine(const YAML::Node& node) {
  int last = node.Mark().line;
  if (node.IsMap()) {
    for (const auto& kv : node) last = std::max({last, lastLine(kv.first), lastLine(kv.second)});
  } else if (node.IsSequence()) {
    for (const auto& item : node) last = std::max(last, lastLine(item));
  }
  return last;
}

/// `code` followed by `comment`, which starts at `column` where that leaves a space (two
/// spaces after the code without a column, as replaceInLine does).
std::string withComment(const std::string& code, std::size_t column, const std::string& c) {
  std::size_t pad = 2;
  if (column != std::string::npos) pad = code.size() + 1 < column ? column - code.size() : 1;
  return code + std::string(pad, ' ') + c;
}

}  // namespace

/// The shortest text that reads back as exactly `v` (std::to_chars, general style without a
/// precision: 0.0009, 3.998392720256027e-08): what the file says is the fitted double, bit for bit.
std::string formatNumber(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general);
  return std::string(buf, res.ptr);
}

std::string formatList(const std::vector<double>& v, int digits) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    std::string x = formatNumber(v[i]);
    if (digits > 0) {
      char buf[64];
      const auto res =
          std::to_chars(buf, buf + sizeof buf, v[i], std::chars_format::general, digits);
      x.assign(buf, res.ptr);
    }
    s += (i == 0 ? "" : ", ") + x;
  }
  return s + "]";
}

std::vector<std::string> splitPath(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t dot = key.find('.', pos);
    parts.push_back(key.substr(pos, dot == std::string::npos ? dot : dot - pos));
    if (dot == std::string::npos) return parts;
    pos = dot + 1;
  }
}

const std::array<CurveSection, 2>& curveSections() {
  // The keys come from the schema; the comments are the writer's.
  static const std::array<CurveSection, 2> sections = [] {
    std::array<CurveSection, 2> out = {{
        {"ground_effect.additional_thrust", "additional_thrust", {}, {},
         "# F_G table: PCHIP between the knots, 1/h² above (docs/vehicle-file.md)",
         "# F_G(h) = g2/(h² + g1)"},
        {"ground_effect.leveling_torque", "leveling_torque", {}, {},
         "# M_G table [m]: PCHIP between the knots, 1/h² above (docs/vehicle-file.md)",
         "# M_G(h) = scale·h/(h² + g3·h + g4)², in N·m per N per sin δ"},
    }};
    for (auto& c : out) {
      for (const auto& spec : model::vehicleSchema().specs()) {
        if (spec.curve != c.path) continue;
        const std::string leaf(spec.key.substr(spec.key.rfind('.') + 1));
        if (spec.form == model::ParamForm::kFormula) c.formula_keys.push_back(leaf);
        if (spec.form == model::ParamForm::kTable && leaf != "heights_m") c.values_key = leaf;
      }
    }
    return out;
  }();
  return sections;
}

const CurveSection* sectionByPath(const std::string& path) {
  for (const auto& s : curveSections()) {
    if (s.path == path) return &s;
  }
  return nullptr;
}

/// The curve section a formula key path belongs to, or null.
const CurveSection* sectionOfKey(const std::string& key) {
  for (const auto& s : curveSections()) {
    if (key.size() > s.path.size() && key.compare(0, s.path.size(), s.path) == 0 &&
        key[s.path.size()] == '.') {
      return &s;
    }
  }
  return nullptr;
}

const model::HeightTableParams& tableOf(const model::VehicleParams& p, const CurveSection& s) {
  return s.name == "additional_thrust" ? p.additional_thrust.table : p.leveling_torque.table;
}

/// The node at a key path, or an invalid node. (Plain copies of nodes: yaml-cpp's operator[]
/// on a non-const node would insert missing keys.)
YAML::Node find(const YAML::Node& root, const std::string& key) {
  YAML::Node node = root;
  for (const auto& part : splitPath(key)) {
    if (!node.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node& cnode = node;
    YAML::Node child = cnode[part];
    if (!child.IsDefined()) return child;
    node.reset(child);
  }
  return node;
}

std::string comment(const VehicleUpdate& u, const VehicleUpdate::Entry& e) {
  std::string c = "# identified";
  if (!u.provenance.empty()) c += " from " + u.provenance;
  if (std::isfinite(e.std_error)) {
    char buf[32];
    const auto res = std::to_chars(buf, buf + sizeof buf, e.std_error, std::chars_format::general, 3);
    c += ", std. error " + std::string(buf, res.ptr);
  }
  return c;
}

/// Replaces one value in place. False when the text at the node's mark is not what yaml-cpp
/// read (a style this line-level edit does not handle); `lines` is then unchanged.
bool replaceInLine(std::vector<std::string>& lines, const YAML::Node& node,
                   const VehicleUpdate& u, const VehicleUpdate::Entry& e) {
  const YAML::Mark mark = node.Mark();
  if (mark.line < 0 || static_cast<std::size_t>(mark.line) >= lines.size()) return false;
  std::string& line = lines[static_cast<std::size_t>(mark.line)];
  const auto col = static_cast<std::size_t>(mark.column);
  if (col >= line.size()) return false;
  std::size_t end = col;
  std::string replacement;
  if (e.list) {
    if (!node.IsSequence() || node.Style() != YAML::EmitterStyle::Flow || line[col] != '[') {
      return false;
    }
    end = line.find(']', col);
    if (end == std::string::npos || line.find('[', col + 1) < end) return false;
    ++end;
    replacement = formatList(e.values);
  } else {
    if (!node.IsScalar()) return false;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != '#' &&
           line[end] != '\r') {
      ++end;
    }
    if (line.substr(col, end - col) != node.Scalar()) return false;  // quoted, tagged, …
    replacement = formatNumber(e.values.front());
  }
  // Keep the alignment of a trailing comment where the new value allows it.
  std::string rest = line.substr(end);
  const bool cr = !rest.empty() && rest.back() == '\r';
  if (cr) rest.pop_back();
  const std::size_t hash = rest.find('#');
  const std::size_t comment_col =
      hash == std::string::npos ? col + replacement.size() + 2 : end + hash;
  std::string out = line.substr(0, col) + replacement;
  out += std::string(out.size() + 1 < comment_col ? comment_col - out.size() : 1, ' ');
  out += comment(u, e);
  if (cr) out += '\r';
  line = out;
  return true;
}

/// The sections to rewrite. Throws std::invalid_argument when formula keys go into a base
/// table without all of the formula's keys.
std::vector<SectionRewrite> sectionRewrites(const YAML::Node& root, const VehicleUpdate& u) {
  std::vector<SectionRewrite> out;
  for (const auto& s : curveSections()) {
    SectionRewrite r;
    r.section = &s;
    r.table = entryFor(u, s.path, true);
    if (r.table != nullptr) {
      out.push_back(r);
      continue;
    }
    bool any = false;
    for (const auto& e : u.entries()) any = any || (!e.table && sectionOfKey(e.key) == &s);
    if (!any || !find(root, s.path + ".table").IsDefined()) continue;
    for (const auto& k : s.formula_keys) {
      const VehicleUpdate::Entry* e = entryFor(u, s.path + "." + k, false);
      if (e == nullptr) {
        throw std::invalid_argument("mergeVehicleYaml: the base gives " + s.values_key +
                                    " as a table; set " + joinKeys(s.formula_keys) + " together (" +
                                    s.path + "." + k + " is missing)");
      }
      r.formula.push_back(e);
    }
    out.push_back(r);
  }
  return out;
}

bool rewritten(const std::vector<SectionRewrite>& rewrites, const VehicleUpdate::Entry& e) {
  const CurveSection* s = e.table ? sectionByPath(e.key) : sectionOfKey(e.key);
  return std::any_of(rewrites.begin(), rewrites.end(),
                     [&](const SectionRewrite& r) { return r.section == s; });
}

/// The section's span, or nothing when it is not a block map under a plain key on its own
/// line (flow style, quoted key, anchors, …).
std::optional<SectionSpan> locateSection(const std::vector<std::string>& lines,
                                         const YAML::Node& root, const CurveSection& s) {
  const YAML::Node parent = find(root, "ground_effect");
  if (!parent.IsMap()) return std::nullopt;
  for (const auto& kv : parent) {
    if (!kv.first.IsScalar() || kv.first.Scalar() != s.name) continue;
    const YAML::Node& value = kv.second;
    if (!value.IsMap() || value.Style() == YAML::EmitterStyle::Flow) return std::nullopt;
    const YAML::Mark mark = kv.first.Mark();
    if (mark.line < 0 || static_cast<std::size_t>(mark.line) >= lines.size() || mark.column < 0) {
      return std::nullopt;
    }
    SectionSpan span;
    span.key_line = static_cast<std::size_t>(mark.line);
    span.key_column = static_cast<std::size_t>(mark.column);
    const std::string& line = lines[span.key_line];
    if (indentOf(line) != span.key_column ||
        line.compare(span.key_column, s.name.size(), s.name) != 0) {
      return std::nullopt;
    }
    std::size_t pos = line.find_first_not_of(' ', span.key_column + s.name.size());
    if (pos == std::string::npos || line[pos] != ':') return std::nullopt;
    span.colon_end = pos + 1;
    pos = line.find_first_not_of(" \t\r", span.colon_end);
    if (pos != std::string::npos) {
      if (line[pos] != '#' || pos == span.colon_end) return std::nullopt;
      span.comment_column = pos;
    }
    span.body_begin = span.key_line + 1;
    std::size_t end = span.body_begin;
    while (end < lines.size() && (blank(lines[end]) || indentOf(lines[end]) > span.key_column))
      ++end;
    while (end > span.body_begin && blank(lines[end - 1])) --end;
    span.body_end = end;
    // The whole section must lie in the body (a comment line less indented inside it would
    // end the body early).
    if (span.body_end == span.body_begin || value.Mark().line < mark.line + 1 ||
        static_cast<std::size_t>(lastLine(value)) >= span.body_end) {
      return std::nullopt;
    }
    return span;
  }
  return std::nullopt;
}

/// Replaces the section's key-line comment and body with the table or the formula's lines.
void rewriteSection(std::vector<std::string>& lines, const SectionSpan& span,
                    const SectionRewrite& r, const VehicleUpdate& u) {
  const CurveSection& s = *r.section;
  const std::string& key_line = lines[span.key_line];
  const std::string eol = !key_line.empty() && key_line.back() == '\r' ? "\r" : "";
  const std::size_t column = span.comment_column;
  const std::string ind2(span.key_column + 2, ' ');
  const std::string ind4(span.key_column + 4, ' ');
  std::vector<std::string> body;
  if (r.table != nullptr) {
    const VehicleUpdate::Entry& e = *r.table;
    body.push_back(withComment(ind2 + "table:", column, comment(u, e)) + eol);
    body.push_back(ind4 + "heights_m: " + formatList(e.heights_m) + eol);
    body.push_back(ind4 + s.values_key + ": " + formatList(e.values) + eol);
    if (!e.std_errors.empty()) {
      body.push_back(ind4 + "# std. errors of " + s.values_key + ": " + formatList(e.std_errors, 7) +
                     eol);
    }
  } else {
    for (std::size_t i = 0; i < s.formula_keys.size(); ++i) {
      const VehicleUpdate::Entry& e = *r.formula[i];
      body.push_back(withComment(ind2 + s.formula_keys[i] + ": " + formatNumber(e.values.front()),
                                 column, comment(u, e)) +
                     eol);
    }
  }
  lines[span.key_line] = withComment(key_line.substr(0, span.colon_end), column,
                                     r.table != nullptr ? s.table_comment : s.formula_comment) +
                         eol;
  lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(span.body_begin),
              lines.begin() + static_cast<std::ptrdiff_t>(span.body_end));
  lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(span.body_begin), body.begin(),
               body.end());
}

}  // namespace geaware::io::detail
