#include "geaware/ident/vehicle_writer.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <exception>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <yaml-cpp/yaml.h>

#include "geaware/io/config_error.hpp"
#include "geaware/io/vehicle_file.hpp"

namespace geaware::ident {

namespace {

/// 7 significant digits: far below any fit's standard error, and readable.
std::string formatNumber(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 7);
  return std::string(buf, res.ptr);
}

double parseBack(const std::string& s) {
  double v = 0.0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}

std::string formatList(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i == 0 ? "" : ", ") + formatNumber(v[i]);
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

/// One ground-effect curve: given by the paper's formula keys or by a table.
struct CurveSection {
  std::string path;                       ///< "ground_effect.additional_thrust"
  std::string name;                       ///< its key in ground_effect
  std::string values_key;                 ///< the table's values list
  std::vector<std::string> formula_keys;  ///< in the order they are written
  std::string table_comment;              ///< the section key's comment, table form
  std::string formula_comment;            ///< the same, formula form
};

const std::array<CurveSection, 2>& curveSections() {
  static const std::array<CurveSection, 2> sections = {{
      {"ground_effect.additional_thrust",
       "additional_thrust",
       "F_G",
       {"g1_m2", "g2_m2"},
       "# F_G table: PCHIP between the knots, 1/h² above (docs/vehicle-file.md)",
       "# F_G(h) = g2/(h² + g1)"},
      {"ground_effect.leveling_torque",
       "leveling_torque",
       "M_G_m",
       {"g3_m", "g4_m2", "scale_m4"},
       "# M_G table [m]: PCHIP between the knots, 1/h² above (docs/vehicle-file.md)",
       "# M_G(h) = scale·h/(h² + g3·h + g4)², in N·m per N per sin δ"},
  }};
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

/// Value read back from a parsed vehicle for a key (NaN-free lists for the drag table).
std::vector<double> readBack(const model::VehicleParams& p, const std::string& key) {
  if (key == "rotor.k_T_N_per_rpm2") return {p.rotor.k_T_N_per_rpm2};
  if (key == "rotor.k_TX_N_per_rpm2") return {p.rotor.k_TX_N_per_rpm2};
  if (key == "rotor.k_TY_N_per_rpm2") return {p.rotor.k_TY_N_per_rpm2};
  if (key == "rotor.k_I_Nm_per_rpm2") return {p.rotor.k_I_Nm_per_rpm2};
  if (key == "rotor.J_R_kgm2") return {p.rotor.J_R_kgm2};
  if (key == "throttle_curve.c2_rpm2") return {p.throttle.c2_rpm2};
  if (key == "throttle_curve.c1_rpm2") return {p.throttle.c1_rpm2};
  if (key == "throttle_curve.c0_rpm2") return {p.throttle.c0_rpm2};
  if (key == "ground_effect.additional_thrust.g1_m2") return {p.additional_thrust.g1_m2};
  if (key == "ground_effect.additional_thrust.g2_m2") return {p.additional_thrust.g2_m2};
  if (key == "ground_effect.leveling_torque.g3_m") return {p.leveling_torque.g3_m};
  if (key == "ground_effect.leveling_torque.g4_m2") return {p.leveling_torque.g4_m2};
  if (key == "ground_effect.leveling_torque.scale_m4") return {p.leveling_torque.scale_m4};
  if (key == "drag.heights_m") return p.drag.heights_m;
  if (key == "drag.d_x_N_per_mps") return p.drag.d_x_N_per_mps;
  if (key == "drag.d_y_N_per_mps") return p.drag.d_y_N_per_mps;
  throw std::logic_error("readBack: unknown key " + key);
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

/// A curve section the merge rewrites as a whole: set as a table, or set by its formula keys
/// while the base gives it as a table.
struct SectionRewrite {
  const CurveSection* section = nullptr;
  const VehicleUpdate::Entry* table = nullptr;       ///< the table, or null: the formula
  std::vector<const VehicleUpdate::Entry*> formula;  ///< in section.formula_keys' order
};

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

/// Where a curve section is in the text: its key line and the body under it.
struct SectionSpan {
  std::size_t key_line = 0;
  std::size_t key_column = 0;
  std::size_t colon_end = 0;                       ///< just past the key's ':'
  std::size_t comment_column = std::string::npos;  ///< of the key line's comment, if any
  std::size_t body_begin = 0;
  std::size_t body_end = 0;  ///< one past the last body line
};

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

/// `code` followed by `comment`, which starts at `column` where that leaves a space (two
/// spaces after the code without a column, as replaceInLine does).
std::string withComment(const std::string& code, std::size_t column, const std::string& c) {
  std::size_t pad = 2;
  if (column != std::string::npos) pad = code.size() + 1 < column ? column - code.size() : 1;
  return code + std::string(pad, ' ') + c;
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
      body.push_back(ind4 + "# std. errors of " + s.values_key + ": " + formatList(e.std_errors) +
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

YAML::Node flowList(const std::vector<double>& values) {
  YAML::Node seq(YAML::NodeType::Sequence);
  for (const double v : values) seq.push_back(formatNumber(v));
  seq.SetStyle(YAML::EmitterStyle::Flow);
  return seq;
}

/// Re-emits the whole document with the values set (comments are lost).
std::string reemit(const std::string& base_text, const VehicleUpdate& update,
                   const std::vector<SectionRewrite>& rewrites) {
  YAML::Node root = YAML::Load(base_text);
  for (const auto& r : rewrites) {
    YAML::Node section(YAML::NodeType::Map);
    if (r.table != nullptr) {
      YAML::Node table(YAML::NodeType::Map);
      table["heights_m"] = flowList(r.table->heights_m);
      table[r.section->values_key] = flowList(r.table->values);
      section["table"] = table;
    } else {
      for (std::size_t i = 0; i < r.formula.size(); ++i) {
        section[r.section->formula_keys[i]] = formatNumber(r.formula[i]->values.front());
      }
    }
    root["ground_effect"][r.section->name] = section;
  }
  for (const auto& e : update.entries()) {
    if (rewritten(rewrites, e)) continue;
    const auto parts = splitPath(e.key);
    YAML::Node node = root;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      YAML::Node child = node[parts[i]];
      node.reset(child);
    }
    if (e.list) {
      node[parts.back()] = flowList(e.values);
    } else {
      node[parts.back()] = formatNumber(e.values.front());
    }
  }
  YAML::Emitter emitter;
  emitter << root;
  return std::string(emitter.c_str()) + "\n";
}

bool readsBackAs(const std::vector<double>& got, const std::vector<double>& written) {
  if (got.size() != written.size()) return false;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (got[i] != parseBack(formatNumber(written[i]))) return false;
  }
  return true;
}

/// Parses the merged text and checks every merged value reads back as written.
bool readsBack(const std::string& text, const std::string& name, const VehicleUpdate& update) {
  const model::VehicleParams p = io::parseVehicleYaml(text, name);
  for (const auto& e : update.entries()) {
    if (e.table) {
      const model::HeightTableParams& t = tableOf(p, *sectionByPath(e.key));
      if (!readsBackAs(t.heights_m, e.heights_m) || !readsBackAs(t.values, e.values)) return false;
      continue;
    }
    // A formula key is only in use when its curve is not a table.
    if (const CurveSection* s = sectionOfKey(e.key); s != nullptr && !tableOf(p, *s).empty()) {
      return false;
    }
    if (!readsBackAs(readBack(p, e.key), e.values)) return false;
  }
  return true;
}

}  // namespace

// ------------------------------------------------------------------------------ the update

const std::vector<std::string>& VehicleUpdate::fittedKeys() {
  static const std::vector<std::string> keys = {
      "rotor.k_T_N_per_rpm2",
      "rotor.k_TX_N_per_rpm2",
      "rotor.k_TY_N_per_rpm2",
      "rotor.k_I_Nm_per_rpm2",
      "rotor.J_R_kgm2",
      "throttle_curve.c2_rpm2",
      "throttle_curve.c1_rpm2",
      "throttle_curve.c0_rpm2",
      "ground_effect.additional_thrust.g1_m2",
      "ground_effect.additional_thrust.g2_m2",
      "ground_effect.leveling_torque.g3_m",
      "ground_effect.leveling_torque.g4_m2",
      "ground_effect.leveling_torque.scale_m4",
      "drag.heights_m",
      "drag.d_x_N_per_mps",
      "drag.d_y_N_per_mps",
  };
  return keys;
}

namespace {
bool isListKey(const std::string& key) { return key.rfind("drag.", 0) == 0; }
}  // namespace

void VehicleUpdate::set(const std::string& key, double value, double std_error) {
  const auto& keys = fittedKeys();
  if (std::find(keys.begin(), keys.end(), key) == keys.end() || isListKey(key)) {
    throw std::invalid_argument("VehicleUpdate: '" + key + "' is not a fitted scalar key");
  }
  if (!std::isfinite(value)) {
    throw std::invalid_argument("VehicleUpdate: " + key + " is not finite");
  }
  const CurveSection* section = sectionOfKey(key);
  std::erase_if(entries_, [&](const Entry& e) {
    return e.key == key || (section != nullptr && e.table && e.key == section->path);
  });
  Entry e;
  e.key = key;
  e.values = {value};
  e.std_error = std_error;
  entries_.push_back(std::move(e));
}

void VehicleUpdate::setList(const std::string& key, std::vector<double> values) {
  if (!isListKey(key)) throw std::invalid_argument("VehicleUpdate: '" + key + "' is not a list key");
  for (const double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument("VehicleUpdate: " + key + " is not finite");
  }
  std::erase_if(entries_, [&](const Entry& e) { return e.key == key; });
  Entry e;
  e.key = key;
  e.values = std::move(values);
  e.list = true;
  entries_.push_back(std::move(e));
}

void VehicleUpdate::setTable(const std::string& section, std::vector<double> heights_m,
                             std::vector<double> values, std::vector<double> std_errors) {
  const CurveSection* s = sectionByPath(section);
  if (s == nullptr) {
    throw std::invalid_argument("VehicleUpdate: '" + section +
                                "' is not a ground-effect curve (ground_effect.additional_thrust "
                                "or ground_effect.leveling_torque)");
  }
  if (heights_m.size() < 2) {
    throw std::invalid_argument("VehicleUpdate: the " + section +
                                " table needs at least 2 knots, got " +
                                std::to_string(heights_m.size()));
  }
  if (values.size() != heights_m.size() ||
      (!std_errors.empty() && std_errors.size() != heights_m.size())) {
    throw std::invalid_argument(
        "VehicleUpdate: the " + section + " table has " + std::to_string(heights_m.size()) +
        " heights, " + std::to_string(values.size()) + " values of " + s->values_key + " and " +
        std::to_string(std_errors.size()) +
        " std. errors (expected one value, and none or one std. error, per height)");
  }
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (!finite(heights_m) || !finite(values) || !finite(std_errors)) {
    throw std::invalid_argument("VehicleUpdate: the " + section + " table is not finite");
  }
  std::erase_if(entries_,
                [&](const Entry& e) { return e.key == section || sectionOfKey(e.key) == s; });
  Entry e;
  e.key = section;
  e.values = std::move(values);
  e.table = true;
  e.heights_m = std::move(heights_m);
  e.std_errors = std::move(std_errors);
  entries_.push_back(std::move(e));
}

void addRotorFit(VehicleUpdate& u, const RotorFit& f) {
  u.set("rotor.k_T_N_per_rpm2", f.k_T_N_per_rpm2);
  u.set("rotor.k_I_Nm_per_rpm2", f.k_I_Nm_per_rpm2);
  if (f.J_R_kgm2) u.set("rotor.J_R_kgm2", *f.J_R_kgm2);
  u.set("throttle_curve.c2_rpm2", f.c2_rpm2);
  u.set("throttle_curve.c1_rpm2", f.c1_rpm2);
  u.set("throttle_curve.c0_rpm2", f.c0_rpm2);
}

void addAdditionalThrust(VehicleUpdate& u, const AdditionalThrustFit& f, bool include_k_T) {
  if (include_k_T) u.set("rotor.k_T_N_per_rpm2", f.k_T_N_per_rpm2);
  u.set("ground_effect.additional_thrust.g1_m2", f.g1_m2);
  u.set("ground_effect.additional_thrust.g2_m2", f.g2_m2);
}

void addMixing(VehicleUpdate& u, const MixingFit& f) {
  if (f.k_TX_N_per_rpm2) u.set("rotor.k_TX_N_per_rpm2", *f.k_TX_N_per_rpm2);
  if (f.k_TY_N_per_rpm2) u.set("rotor.k_TY_N_per_rpm2", *f.k_TY_N_per_rpm2);
  if (f.k_I_Nm_per_rpm2) u.set("rotor.k_I_Nm_per_rpm2", *f.k_I_Nm_per_rpm2);
}

void addLeveling(VehicleUpdate& u, const LevelingFit& f) {
  u.set("ground_effect.leveling_torque.g3_m", f.g3_m);
  u.set("ground_effect.leveling_torque.g4_m2", f.g4_m2);
  u.set("ground_effect.leveling_torque.scale_m4", f.scale_m4);
}

void addDrag(VehicleUpdate& u, const DragFit& f) {
  const model::DragTableParams t = dragTable(f);
  u.setList("drag.heights_m", t.heights_m);
  u.setList("drag.d_x_N_per_mps", t.d_x_N_per_mps);
  u.setList("drag.d_y_N_per_mps", t.d_y_N_per_mps);
}

// ------------------------------------------------------------------------------- the merge

MergeResult mergeVehicleYaml(std::string_view base_text, const std::string& base_name,
                             const VehicleUpdate& update) {
  const std::string text(base_text);
  // The base must itself be a valid vehicle file: merging into a broken one would hide its
  // problems behind ours.
  (void)io::parseVehicleYaml(text, base_name);
  MergeResult result;
  const YAML::Node root = YAML::Load(text);

  std::vector<std::string> lines;
  {
    std::size_t pos = 0;
    for (;;) {
      const std::size_t nl = text.find('\n', pos);
      lines.push_back(text.substr(pos, nl == std::string::npos ? nl : nl - pos));
      if (nl == std::string::npos) break;
      pos = nl + 1;
    }
  }
  const std::vector<SectionRewrite> rewrites = sectionRewrites(root, update);
  bool in_place = true;
  std::exception_ptr in_place_error;
  // Locate the rewritten sections first, while the line numbers are yaml-cpp's.
  std::vector<std::pair<SectionSpan, const SectionRewrite*>> spans;
  for (const auto& r : rewrites) {
    const auto span = locateSection(lines, root, *r.section);
    if (!span) {
      result.notes.push_back("section '" + r.section->path +
                             "' is not a block map under its own key line in the base file");
      in_place = false;
      break;
    }
    spans.emplace_back(*span, &r);
  }
  for (const auto& e : update.entries()) {
    if (!in_place) break;
    if (rewritten(rewrites, e)) continue;
    const YAML::Node node = find(root, e.key);
    if (!node.IsDefined()) {
      result.notes.push_back("key '" + e.key + "' is not in the base file");
      in_place = false;
      break;
    }
    if (!replaceInLine(lines, node, update, e)) {
      result.notes.push_back("key '" + e.key + "' is not written as a plain value" +
                             std::string(e.list ? " or a one-line flow list" : "") +
                             " in the base file");
      in_place = false;
      break;
    }
  }
  if (in_place) {
    // Bottom up, so the spans above stay where they are.
    std::sort(spans.begin(), spans.end(),
              [](const auto& a, const auto& b) { return a.first.key_line > b.first.key_line; });
    for (const auto& [span, r] : spans) rewriteSection(lines, span, *r, update);
    std::string merged;
    for (std::size_t i = 0; i < lines.size(); ++i) merged += lines[i] + (i + 1 < lines.size() ? "\n" : "");
    try {
      if (readsBack(merged, base_name + " (merged)", update)) {
        result.yaml = std::move(merged);
        return result;
      }
      result.notes.push_back("the line-level edit did not read back as written");
    } catch (const io::ConfigError& e) {
      // The values or the edit are at fault: re-emitting tells which.
      in_place_error = std::current_exception();
      result.notes.push_back("the line-level edit did not load: " + std::string(e.what()));
    }
  }
  result.comments_preserved = false;
  result.notes.push_back("the file was re-emitted: every key is kept, the comments are lost");
  result.yaml = reemit(text, update, rewrites);
  bool ok = false;
  try {
    ok = readsBack(result.yaml, base_name + " (merged)", update);
  } catch (const io::ConfigError&) {
    // The values are invalid: the in-place edit's error has the base file's line numbers.
    if (in_place_error) std::rethrow_exception(in_place_error);
    throw;
  }
  if (!ok)
    throw std::runtime_error("mergeVehicleYaml: the re-emitted vehicle file does not read back");
  return result;
}

MergeResult writeVehicleFile(const std::filesystem::path& base, const std::filesystem::path& out,
                             const VehicleUpdate& update) {
  std::ifstream in(base, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the base vehicle file " + base.string());
  std::ostringstream buf;
  buf << in.rdbuf();
  return writeVehicleFile(buf.str(), base.string(), out, update);
}

MergeResult writeVehicleFile(std::string_view base_text, const std::string& base_name,
                             const std::filesystem::path& out, const VehicleUpdate& update) {
  MergeResult result = mergeVehicleYaml(base_text, base_name, update);
  std::filesystem::path tmp = out;
  tmp += ".tmp";
  {
    std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
    if (!os) throw std::runtime_error("cannot write " + tmp.string());
    os << result.yaml;
    os.close();
    if (!os) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, out);
  return result;
}

}  // namespace geaware::ident
