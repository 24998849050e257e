// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/yaml_reader.hpp"

#include "text.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

namespace geaware::io {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Levenshtein distance, for the nearest valid key of an unknown one.
std::size_t keyEditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

/// The known key nearest to `key` when it is a plausible misspelling (at most a third of its
/// characters edited), else empty.
std::string nearestKey(const std::string& key, const std::set<std::string>& known) {
  std::string best;
  std::size_t best_d = key.size() / 3 + 1;
  for (const auto& k : known) {
    const std::size_t d = keyEditDistance(key, k);
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return best;
}

int lineOfNode(const YAML::Node& n) { return n.Mark().line >= 0 ? n.Mark().line + 1 : 0; }

const char* typeName(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Scalar: return "a scalar";
    case YAML::NodeType::Null: return "an empty value";
    default: return "nothing";
  }
}

/// Parses a scalar as a double; YAML's .nan/.inf are accepted here and rejected by validation
/// with the expected range, which makes a better message.
bool toNumber(const YAML::Node& n, double& out) {
  if (!n.IsScalar()) return false;
  try {
    out = n.as<double>();
    return true;
  } catch (const YAML::Exception&) {
    return false;
  }
}

/// A finite number, parsed strictly with std::from_chars (a leading '+' allowed, nothing after
/// the number); NaN after a problem at `path`.
double strictFinite(const YAML::Node& n, const std::string& path, YamlContext& ctx) {
  if (!n.IsScalar()) {
    ctx.problem(lineOfNode(n), path, std::string("expected a number, got ") + typeName(n));
    return kNaN;
  }
  const std::string& s = n.Scalar();
  double v = kNaN;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (!s.empty() && s[0] == '+') ++first;
  const auto res = std::from_chars(first, last, v);
  if (res.ec == std::errc() && res.ptr == last && std::isfinite(v)) return v;
  std::string lower;
  for (char c : s) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool special = (res.ec == std::errc() && res.ptr == last) ||
                       lower.find("nan") != std::string::npos ||
                       lower.find("inf") != std::string::npos;
  ctx.problem(lineOfNode(n), path,
              special ? "'" + detail::excerpt(s) + "' is not a finite number"
                      : "expected a number, got '" + detail::excerpt(s) + "'");
  return kNaN;
}

/// A list of finite numbers at `path`; with `length`, another count is a problem.
std::vector<double> strictFiniteList(const YAML::Node& n, const std::string& path,
                                     std::optional<std::size_t> length, YamlContext& ctx) {
  std::vector<double> out;
  if (!n.IsSequence()) {
    ctx.problem(lineOfNode(n), path, std::string("expected a list of numbers, got ") + typeName(n));
    return out;
  }
  if (length && n.size() != *length) {
    ctx.problem(lineOfNode(n), path,
                "has " + std::to_string(n.size()) + " entries, expected " + std::to_string(*length));
  }
  out.reserve(n.size());
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string item = path + "[" + std::to_string(i) + "]";
    ctx.lines[item] = lineOfNode(n[i]);
    out.push_back(strictFinite(n[i], item, ctx));
  }
  return out;
}

}  // namespace

int lineOfKey(const std::map<std::string, int>& lines, std::string key) {
  while (true) {
    if (auto it = lines.find(key); it != lines.end()) return it->second;
    const auto cut = key.find_last_of(".[");
    if (cut == std::string::npos) return 0;
    key.resize(cut);
  }
}

MapReader::MapReader(YAML::Node node, std::string path, YamlContext& ctx, int header_line)
    : node_(std::move(node)),
      path_(std::move(path)),
      ctx_(ctx),
      valid_(node_.IsMap()),
      header_line_(header_line) {}

std::string MapReader::pathOf(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

YAML::Node MapReader::required(const std::string& key) {
  read_.insert(key);
  if (!valid_) return YAML::Node(YAML::NodeType::Undefined);
  // Look the key up by iteration: we want the line of the key itself (for a section, its
  // header line), not of its value, which for a map is the line of its first child.
  for (const auto& kv : node_) {
    if (kv.first.IsScalar() && kv.first.Scalar() == key) {
      const YAML::Node child = kv.second;
      if (!child.IsDefined() || child.IsNull()) {
        ctx_.problem(lineOfNode(kv.first), pathOf(key), "has no value");
        return YAML::Node(YAML::NodeType::Undefined);
      }
      ctx_.lines[pathOf(key)] = lineOfNode(kv.first);
      return child;
    }
  }
  ctx_.problem(header_line_, pathOf(key),
               path_.empty() ? "is missing (required)"
                             : "is missing (required in section '" + path_ + "')");
  return YAML::Node(YAML::NodeType::Undefined);
}

bool MapReader::has(const std::string& key) const {
  if (!valid_) return false;
  for (const auto& kv : node_) {
    if (kv.first.IsScalar() && kv.first.Scalar() == key) return true;
  }
  return false;
}

double MapReader::number(const std::string& key) {
  const YAML::Node n = required(key);
  if (!n.IsDefined()) return kNaN;
  double v = kNaN;
  if (!toNumber(n, v)) {
    ctx_.problem(lineOfNode(n), pathOf(key),
                 n.IsScalar() ? "expected a number, got '" + detail::excerpt(n.Scalar()) + "'"
                              : std::string("expected a number, got ") + typeName(n));
    return kNaN;
  }
  return v;
}

std::string MapReader::text(const std::string& key) {
  const YAML::Node n = required(key);
  if (!n.IsDefined()) return {};
  if (!n.IsScalar()) {
    ctx_.problem(lineOfNode(n), pathOf(key), std::string("expected text, got ") + typeName(n));
    return {};
  }
  return n.Scalar();
}

std::vector<double> MapReader::numbers(const std::string& key) {
  const YAML::Node n = required(key);
  std::vector<double> out;
  if (!n.IsDefined()) return out;
  if (!n.IsSequence()) {
    ctx_.problem(lineOfNode(n), pathOf(key),
                 std::string("expected a list of numbers, got ") + typeName(n));
    return out;
  }
  out.reserve(n.size());
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string item = pathOf(key) + "[" + std::to_string(i) + "]";
    ctx_.lines[item] = lineOfNode(n[i]);
    double v = kNaN;
    if (!toNumber(n[i], v)) {
      ctx_.problem(lineOfNode(n[i]), item,
                   n[i].IsScalar() ? "expected a number, got '" + detail::excerpt(n[i].Scalar()) + "'"
                                   : std::string("expected a number, got ") + typeName(n[i]));
    }
    out.push_back(v);
  }
  return out;
}

MapReader MapReader::map(const std::string& key) {
  YAML::Node n = required(key);
  if (n.IsDefined() && !n.IsMap()) {
    ctx_.problem(lineOfNode(n), pathOf(key), std::string("expected a map, got ") + typeName(n));
  }
  // An absent or malformed map still yields a reader, so its keys are reported once as the
  // parent's problem rather than once per missing child.
  MapReader child(n.IsDefined() && n.IsMap() ? n : YAML::Node(YAML::NodeType::Undefined),
                  pathOf(key), ctx_, ctx_.lineOf(pathOf(key)));
  return child;
}

long MapReader::integer(const std::string& key, long lo, long hi) {
  const double v = number(key);
  if (std::isnan(v)) return lo;  // already reported (missing or not a number)
  if (!(v == std::floor(v) && v >= static_cast<double>(lo) && v <= static_cast<double>(hi))) {
    ctx_.problem(ctx_.lineOf(pathOf(key)), pathOf(key),
                 "expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return lo;
  }
  return static_cast<long>(v);
}

bool MapReader::boolean(const std::string& key) {
  const YAML::Node n = required(key);
  if (!n.IsDefined()) return false;
  try {
    if (n.IsScalar()) return n.as<bool>();
  } catch (const YAML::Exception&) {
  }
  ctx_.problem(lineOfNode(n), pathOf(key),
               n.IsScalar() ? "expected true or false, got '" + detail::excerpt(n.Scalar()) + "'"
                            : std::string("expected true or false, got ") + typeName(n));
  return false;
}

std::vector<double> MapReader::fixedNumbers(const std::string& key, std::size_t n) {
  std::vector<double> v = numbers(key);
  if (v.size() != n && ctx_.lines.contains(pathOf(key))) {
    ctx_.problem(ctx_.lineOf(pathOf(key)), pathOf(key),
                 "expected a list of " + std::to_string(n) + " numbers, got " + std::to_string(v.size()));
  }
  v.resize(n, kNaN);
  return v;
}

std::vector<std::vector<double>> MapReader::rows(const std::string& key, std::size_t n) {
  const YAML::Node node = required(key);
  std::vector<std::vector<double>> out;
  if (!node.IsDefined()) return out;
  if (!node.IsSequence()) {
    ctx_.problem(lineOfNode(node), pathOf(key), std::string("expected a list of lists, got ") + typeName(node));
    return out;
  }
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = pathOf(key) + "[" + std::to_string(i) + "]";
    const YAML::Node row = node[i];
    std::vector<double> values(n, kNaN);
    if (!row.IsSequence() || row.size() != n) {
      ctx_.problem(lineOfNode(row), item, "expected a list of " + std::to_string(n) + " numbers");
    } else {
      for (std::size_t j = 0; j < n; ++j) {
        if (!toNumber(row[j], values[j])) {
          ctx_.problem(lineOfNode(row[j]), item + "[" + std::to_string(j) + "]", "expected a number");
        }
      }
    }
    out.push_back(std::move(values));
  }
  return out;
}

std::string MapReader::choice(const std::string& key, const std::vector<std::string>& choices) {
  const std::string v = text(key);
  if (!ctx_.lines.contains(pathOf(key))) return {};
  for (const auto& c : choices) {
    if (v == c) return v;
  }
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  ctx_.problem(ctx_.lineOf(pathOf(key)), pathOf(key), "got '" + detail::excerpt(v) + "', expected one of: " + list);
  return {};
}

double MapReader::finiteNumber(const std::string& key) {
  const YAML::Node n = required(key);
  return n.IsDefined() ? strictFinite(n, pathOf(key), ctx_) : kNaN;
}

std::vector<double> MapReader::finiteNumbers(const std::string& key,
                                             std::optional<std::size_t> length) {
  const YAML::Node n = required(key);
  if (!n.IsDefined()) return {};
  return strictFiniteList(n, pathOf(key), length, ctx_);
}

std::vector<std::vector<double>> MapReader::finiteRows(const std::string& key,
                                                       std::optional<std::size_t> row_length) {
  const YAML::Node node = required(key);
  std::vector<std::vector<double>> out;
  if (!node.IsDefined()) return out;
  if (!node.IsSequence()) {
    ctx_.problem(lineOfNode(node), pathOf(key),
                 std::string("expected a list of lists of numbers, got ") + typeName(node));
    return out;
  }
  if (!row_length && node.size() > 0 && node[0].IsSequence()) row_length = node[0].size();
  out.reserve(node.size());
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = pathOf(key) + "[" + std::to_string(i) + "]";
    ctx_.lines[item] = lineOfNode(node[i]);
    out.push_back(strictFiniteList(node[i], item, row_length, ctx_));
  }
  return out;
}

std::vector<MapReader> MapReader::maps(const std::string& key) {
  const YAML::Node node = required(key);
  std::vector<MapReader> out;
  if (!node.IsDefined()) return out;
  if (!node.IsSequence()) {
    ctx_.problem(lineOfNode(node), pathOf(key),
                 std::string("expected a list of maps, got ") + typeName(node));
    return out;
  }
  out.reserve(node.size());
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = pathOf(key) + "[" + std::to_string(i) + "]";
    const YAML::Node n = node[i];
    ctx_.lines[item] = lineOfNode(n);
    if (!n.IsMap()) {
      ctx_.problem(lineOfNode(n), item, std::string("expected a map, got ") + typeName(n));
    }
    out.emplace_back(n.IsMap() ? n : YAML::Node(YAML::NodeType::Undefined), item, ctx_,
                     lineOfNode(n));
  }
  return out;
}

std::vector<std::string> MapReader::texts(const std::string& key) {
  const YAML::Node node = required(key);
  std::vector<std::string> out;
  if (!node.IsDefined()) return out;
  if (!node.IsSequence()) {
    ctx_.problem(lineOfNode(node), pathOf(key),
                 std::string("expected a list of texts, got ") + typeName(node));
    return out;
  }
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = pathOf(key) + "[" + std::to_string(i) + "]";
    ctx_.lines[item] = lineOfNode(node[i]);
    if (!node[i].IsScalar()) {
      ctx_.problem(lineOfNode(node[i]), item, std::string("expected text, got ") + typeName(node[i]));
    }
    out.push_back(node[i].IsScalar() ? node[i].Scalar() : std::string());
  }
  return out;
}

std::map<std::string, std::string> MapReader::optionalTextMap(const std::string& key) {
  std::map<std::string, std::string> out;
  if (!has(key)) {
    read_.insert(key);  // optional: absent is fine
    return out;
  }
  const YAML::Node node = required(key);
  if (!node.IsDefined()) return out;
  if (!node.IsMap()) {
    ctx_.problem(lineOfNode(node), pathOf(key),
                 std::string("expected a map of text values, got ") + typeName(node));
    return out;
  }
  for (const auto& kv : node) {
    const std::string name = kv.first.IsScalar() ? kv.first.Scalar() : "?";
    const std::string item = pathOf(key) + "." + name;
    ctx_.lines[item] = lineOfNode(kv.first);
    if (!kv.second.IsScalar()) {
      ctx_.problem(lineOfNode(kv.first), item,
                   std::string("expected text, got ") + typeName(kv.second));
    } else {
      out[name] = kv.second.Scalar();
    }
  }
  return out;
}

bool MapReader::valueIs(const std::string& key, std::string_view word) const {
  if (!valid_) return false;
  for (const auto& kv : node_) {
    if (kv.first.IsScalar() && kv.first.Scalar() == key) {
      return kv.second.IsScalar() && kv.second.Scalar() == word;
    }
  }
  return false;
}

bool MapReader::isScalar(const std::string& key) const {
  if (!valid_) return false;
  for (const auto& kv : node_) {
    if (kv.first.IsScalar() && kv.first.Scalar() == key) return kv.second.IsScalar();
  }
  return false;
}

void MapReader::problem(const std::string& key, const std::string& message) {
  ctx_.problem(ctx_.lineOf(pathOf(key)), pathOf(key), message);
}

void MapReader::rejectUnknownKeys() {
  if (!valid_) return;
  std::set<std::string> seen;
  for (const auto& kv : node_) {
    const std::string key = kv.first.Scalar();
    // yaml-cpp keeps the first of two equal keys silently; a duplicated key is almost always
    // an edit gone wrong, and which value wins must not be a guess.
    if (!seen.insert(key).second) {
      ctx_.problem(lineOfNode(kv.first), pathOf(key), "appears more than once in this map");
      continue;
    }
    if (!read_.contains(key)) {
      std::string known;
      for (const auto& k : read_) known += (known.empty() ? "" : ", ") + k;
      const std::string nearest = nearestKey(key, read_);
      ctx_.problem(lineOfNode(kv.first), pathOf(key),
                   "unknown key (" + (nearest.empty() ? "" : "did you mean '" + nearest + "'? ") +
                       "expected one of: " + known + ")");
    }
  }
}

}  // namespace geaware::io
