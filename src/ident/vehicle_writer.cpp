#include "geaware/ident/vehicle_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

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

/// Re-emits the whole document with the values set (comments are lost).
std::string reemit(const std::string& base_text, const VehicleUpdate& update) {
  YAML::Node root = YAML::Load(base_text);
  for (const auto& e : update.entries()) {
    const auto parts = splitPath(e.key);
    YAML::Node node = root;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      YAML::Node child = node[parts[i]];
      node.reset(child);
    }
    if (e.list) {
      YAML::Node seq(YAML::NodeType::Sequence);
      for (const double v : e.values) seq.push_back(formatNumber(v));
      seq.SetStyle(YAML::EmitterStyle::Flow);
      node[parts.back()] = seq;
    } else {
      node[parts.back()] = formatNumber(e.values.front());
    }
  }
  YAML::Emitter emitter;
  emitter << root;
  return std::string(emitter.c_str()) + "\n";
}

/// Parses the merged text and checks every merged value reads back as written.
bool readsBack(const std::string& text, const std::string& name, const VehicleUpdate& update) {
  const model::VehicleParams p = io::parseVehicleYaml(text, name);
  for (const auto& e : update.entries()) {
    const std::vector<double> got = readBack(p, e.key);
    if (got.size() != e.values.size()) return false;
    for (std::size_t i = 0; i < got.size(); ++i) {
      if (got[i] != parseBack(formatNumber(e.values[i]))) return false;
    }
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
  std::erase_if(entries_, [&](const Entry& e) { return e.key == key; });
  entries_.push_back({key, {value}, false, std_error});
}

void VehicleUpdate::setList(const std::string& key, std::vector<double> values) {
  if (!isListKey(key)) throw std::invalid_argument("VehicleUpdate: '" + key + "' is not a list key");
  for (const double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument("VehicleUpdate: " + key + " is not finite");
  }
  std::erase_if(entries_, [&](const Entry& e) { return e.key == key; });
  entries_.push_back({key, std::move(values), true, kNaN});
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

void addHoverThrust(VehicleUpdate& u, const HoverThrustFit& f) {
  u.set("ground_effect.additional_thrust.g1_m2", f.g1_m2);
  u.set("ground_effect.additional_thrust.g2_m2", f.g2_m2);
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
  bool in_place = true;
  for (const auto& e : update.entries()) {
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
    std::string merged;
    for (std::size_t i = 0; i < lines.size(); ++i) merged += lines[i] + (i + 1 < lines.size() ? "\n" : "");
    if (readsBack(merged, base_name + " (merged)", update)) {
      result.yaml = std::move(merged);
      return result;
    }
    result.notes.push_back("the line-level edit did not read back as written");
  }
  result.comments_preserved = false;
  result.notes.push_back("the file was re-emitted: every key is kept, the comments are lost");
  result.yaml = reemit(text, update);
  if (!readsBack(result.yaml, base_name + " (merged)", update)) {
    throw std::runtime_error("mergeVehicleYaml: the re-emitted vehicle file does not read back");
  }
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
