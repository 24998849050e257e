// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading a parameter struct from YAML by its schema (model/param_schema.hpp): every parameter
// at its key path, maps opened as the paths go down and closed (unknown keys reported) as they
// leave, in the schema's order. A curve with two forms is read as its table when its section
// has a `table` key, else by its formula's keys; formula keys next to a table are reported at
// their own key, since one of the two would be silently ignored. Include it only from loaders:
// it brings in yaml-cpp.

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geaware/io/yaml_reader.hpp"
#include "geaware/model/param_schema.hpp"

namespace geaware::io {

namespace detail {

/// The open maps along the current key path: [0] is the root.
class MapStack {
 public:
  explicit MapStack(MapReader& root) : root_(root) {}
  ~MapStack() = default;
  MapStack(const MapStack&) = delete;
  MapStack& operator=(const MapStack&) = delete;

  /// The reader of the map at `sections` (the key path's parts but the last), opening and
  /// closing maps as needed.
  MapReader& at(const std::vector<std::string>& sections) {
    std::size_t common = 0;
    while (common < open_.size() && common < sections.size() &&
           open_[common].first == sections[common]) {
      ++common;
    }
    closeTo(common);
    for (std::size_t i = common; i < sections.size(); ++i) {
      MapReader& parent = open_.empty() ? root_ : *open_.back().second;
      open_.emplace_back(sections[i], std::make_unique<MapReader>(parent.map(sections[i])));
    }
    return open_.empty() ? root_ : *open_.back().second;
  }
  /// Whether every map of `sections` exists (opening those that do, as at() would); the maps
  /// already open along the path are not closed.
  bool has(const std::vector<std::string>& sections) {
    std::size_t open = 0;
    while (open < open_.size() && open < sections.size() && open_[open].first == sections[open]) {
      ++open;
    }
    for (std::size_t n = open; n < sections.size(); ++n) {
      const std::vector<std::string> parent(sections.begin(), sections.begin() + static_cast<std::ptrdiff_t>(n));
      if (!at(parent).has(sections[n])) return false;
    }
    return true;
  }
  /// Closes every map below the root (the root is the caller's).
  void closeAll() { closeTo(0); }

 private:
  void closeTo(std::size_t depth) {
    while (open_.size() > depth) {
      open_.back().second->rejectUnknownKeys();
      open_.pop_back();
    }
  }
  MapReader& root_;
  std::vector<std::pair<std::string, std::unique_ptr<MapReader>>> open_;
};

inline std::vector<std::string> splitKey(std::string_view key) {
  std::vector<std::string> parts;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t dot = key.find('.', pos);
    parts.emplace_back(key.substr(pos, dot == std::string_view::npos ? dot : dot - pos));
    if (dot == std::string_view::npos) return parts;
    pos = dot + 1;
  }
}

template <class T>
void readOne(MapStack& maps, const model::ParamSpec<T>& s, T& out) {
  auto parts = splitKey(s.key);
  const std::string leaf = parts.back();
  parts.pop_back();
  // An optional key, or a whole section of them, left out: the struct's default stays.
  if (s.optional && !maps.has(parts)) return;
  MapReader& m = maps.at(parts);
  if (s.optional && !m.has(leaf)) return;
  switch (s.kind) {
    case model::ParamKind::kNumber: s.number(out) = m.number(leaf); break;
    case model::ParamKind::kList: s.list(out) = m.numbers(leaf); break;
    case model::ParamKind::kText: s.text(out) = m.text(leaf); break;
  }
}

}  // namespace detail

/// Reads every parameter of `schema` from `root` into `out`, reporting missing, mistyped and
/// unknown keys (in every map below the root; the root's own unknown keys are the caller's,
/// after it has read its other keys) to root's context.
template <class T>
void readParameters(MapReader& root, const model::ParamSchema<T>& schema, T& out) {
  using model::ParamForm;
  detail::MapStack maps(root);
  std::vector<std::string_view> curves_done;
  for (const auto& s : schema.specs()) {
    if (s.form == ParamForm::kAlways) {
      detail::readOne(maps, s, out);
      continue;
    }
    bool done = false;
    for (const auto c : curves_done) done = done || c == s.curve;
    if (done) continue;
    curves_done.push_back(s.curve);
    // The whole curve at once: its table first when it has one, then its formula keys.
    MapReader& section = maps.at(detail::splitKey(s.curve));
    const bool table = section.has("table");
    for (const auto& t : schema.specs()) {
      if (t.curve == s.curve && t.form == ParamForm::kTable && table) detail::readOne(maps, t, out);
    }
    for (const auto& f : schema.specs()) {
      if (f.curve != s.curve || f.form != ParamForm::kFormula) continue;
      if (!table) {
        detail::readOne(maps, f, out);
        continue;
      }
      MapReader& m = maps.at(detail::splitKey(s.curve));
      const std::string leaf = detail::splitKey(f.key).back();
      if (m.has(leaf)) {
        (void)m.number(leaf);  // read, so it is reported once, here, not as unknown
        m.problem(leaf, "is not used when the curve is given as a table: give either the "
                        "formula's keys or 'table', not both");
      }
    }
  }
  maps.closeAll();
}

}  // namespace geaware::io
