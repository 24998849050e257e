// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to the io layer: the line-level text surgery of the vehicle-file writer
// (include/geaware/io/vehicle_writer.hpp). Values are replaced where yaml-cpp says they are,
// ground-effect curve sections are rewritten as a whole; every other line is kept byte for byte.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "geaware/io/vehicle_writer.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::io::detail {

/// A number as the writer writes it: the shortest text that reads back as exactly `v`.
[[nodiscard]] std::string formatNumber(double v);
/// "[a, b, c]", each as formatNumber, or with `digits` significant digits (comments).
[[nodiscard]] std::string formatList(const std::vector<double>& v, int digits = 0);
/// "a.b.c" → {"a", "b", "c"}
[[nodiscard]] std::vector<std::string> splitPath(const std::string& key);

/// One ground-effect curve: given by the paper's formula keys or by a table.
struct CurveSection {
  std::string path;                       ///< "ground_effect.additional_thrust"
  std::string name;                       ///< its key in ground_effect
  std::string values_key;                 ///< the table's values list
  std::vector<std::string> formula_keys;  ///< in the order they are written
  std::string table_comment;              ///< the section key's comment, table form
  std::string formula_comment;            ///< the same, formula form
};

[[nodiscard]] const std::array<CurveSection, 2>& curveSections();
/// The curve section at a path, or null.
[[nodiscard]] const CurveSection* sectionByPath(const std::string& path);
/// The curve section a formula key path belongs to, or null.
[[nodiscard]] const CurveSection* sectionOfKey(const std::string& key);
[[nodiscard]] const model::HeightTableParams& tableOf(const model::VehicleParams& p,
                                                      const CurveSection& s);

/// The node at a key path, or an invalid node.
[[nodiscard]] YAML::Node find(const YAML::Node& root, const std::string& key);

/// The trailing comment of a replaced line: "# identified from …, std. error …".
[[nodiscard]] std::string comment(const VehicleUpdate& u, const VehicleUpdate::Entry& e);

/// Replaces one value in place. False when the text at the node's mark is not what yaml-cpp
/// read (a style this line-level edit does not handle); `lines` is then unchanged.
bool replaceInLine(std::vector<std::string>& lines, const YAML::Node& node,
                   const VehicleUpdate& u, const VehicleUpdate::Entry& e);

/// A curve section the merge rewrites as a whole: set as a table, or set by its formula keys
/// while the base gives it as a table.
struct SectionRewrite {
  const CurveSection* section = nullptr;
  const VehicleUpdate::Entry* table = nullptr;       ///< the table, or null: the formula
  std::vector<const VehicleUpdate::Entry*> formula;  ///< in section.formula_keys' order
};

/// The sections to rewrite. Throws std::invalid_argument when formula keys go into a base
/// table without all of the formula's keys.
[[nodiscard]] std::vector<SectionRewrite> sectionRewrites(const YAML::Node& root,
                                                          const VehicleUpdate& u);
/// Whether the entry is written by one of the section rewrites.
[[nodiscard]] bool rewritten(const std::vector<SectionRewrite>& rewrites,
                             const VehicleUpdate::Entry& e);

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
[[nodiscard]] std::optional<SectionSpan> locateSection(const std::vector<std::string>& lines,
                                                       const YAML::Node& root,
                                                       const CurveSection& s);

/// Replaces the section's key-line comment and body with the table or the formula's lines.
void rewriteSection(std::vector<std::string>& lines, const SectionSpan& span,
                    const SectionRewrite& r, const VehicleUpdate& u);

}  // namespace geaware::io::detail
