// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Writing identified parameters into a vehicle file (docs/vehicle-file.md): the fitted values
// are MERGED into a given base file, every other key stays as it was.
//
// The merge works on the text, line by line: each fitted key's value (a plain scalar, or a
// flow list `[a, b, c]` for the drag table) is replaced where yaml-cpp says it is, and that
// line's trailing comment becomes "# identified …", so the rest of the file, comments
// included, is kept byte for byte. Comment lines elsewhere that describe an old value (such
// as the notes above `k_T_N_per_rpm2` in paper_quad.yaml) are kept too and may then be stale.
// When a key cannot be replaced in place (block-style lists, anchors, a key missing from the
// base), the whole file is re-emitted by yaml-cpp instead: all keys and values are kept, the
// comments are lost, and MergeResult::comments_preserved says so.
//
// A ground-effect curve (ground_effect.additional_thrust or ground_effect.leveling_torque) may
// instead be set as a table of knots (VehicleUpdate::setTable). Its section is then rewritten
// in the text: the lines under the section's key (those blank or indented deeper than it,
// trailing blank lines excepted) become `table:` with `heights_m` and `F_G` (or `M_G_m`)
// flow lists, and a `# std. errors of F_G: [...]` line when the errors are known; the key's
// own trailing comment, which described the formula, now describes the table. Formula keys
// merged into a base whose section holds a table rewrite the section the same way, into the
// formula's lines; all of that curve's formula keys must then be set (std::invalid_argument
// otherwise). Every line outside the rewritten sections is kept byte for byte. A section
// written in flow style (`additional_thrust: {g1_m2: …}`) falls back to re-emitting.
//
// The result is always checked: it must load with io::parseVehicleYaml (strict keys and the
// physical validation) and read back the merged values, tables included, or nothing is
// written.

//
// Identification turns its fits into a VehicleUpdate with ident/vehicle_update.hpp.

#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace geaware::io {

/// The values to merge, by key path of the vehicle file ("rotor.k_T_N_per_rpm2").
class VehicleUpdate {
 public:
  struct Entry {
    std::string key;                 ///< key path; for a table, the section ("ground_effect.…")
    std::vector<double> values;      ///< one value for a scalar key; a table's curve values
    bool list = false;               ///< the drag table's lists
    double std_error = std::numeric_limits<double>::quiet_NaN();  ///< in the comment when known
    bool table = false;              ///< a ground-effect curve table (setTable)
    std::vector<double> heights_m;   ///< the table's knots [m]
    std::vector<double> std_errors;  ///< standard errors of the table's values, or empty
  };

  /// Sets a scalar key; throws std::invalid_argument for a key identification does not fit
  /// or a non-finite value. Setting a key again replaces the earlier value.
  void set(const std::string& key, double value,
           double std_error = std::numeric_limits<double>::quiet_NaN());
  /// Sets one of the drag table's lists.
  void setList(const std::string& key, std::vector<double> values);
  /// Sets a ground-effect curve as a table: `section` is "ground_effect.additional_thrust"
  /// (values are F_G) or "ground_effect.leveling_torque" (values are M_G in m). Needs at least
  /// 2 knots, one finite value per knot, and std_errors empty or one per knot; throws
  /// std::invalid_argument otherwise (heights and ranges are checked by the merge's
  /// validation). Replaces the section's formula keys set earlier, and a later set() of one
  /// of its formula keys replaces the table.
  void setTable(const std::string& section, std::vector<double> heights_m,
                std::vector<double> values, std::vector<double> std_errors = {});

  /// Text for the comments of the replaced lines, e.g. the log file ("identified from …").
  std::string provenance;

  [[nodiscard]] const std::vector<Entry>& entries() const noexcept { return entries_; }
  [[nodiscard]] bool empty() const noexcept { return entries_.empty(); }

  /// The scalar and list keys identification may write (tables go by section: setTable).
  [[nodiscard]] static const std::vector<std::string>& fittedKeys();

 private:
  std::vector<Entry> entries_;
};

struct MergeResult {
  std::string yaml;                ///< the merged file's text
  bool comments_preserved = true;  ///< false when the file had to be re-emitted
  std::vector<std::string> notes;  ///< why it was re-emitted, etc.
};

/// Merges into the text of a base vehicle file (`base_name` names it in errors). Throws
/// io::ConfigError when the base or the result is not a valid vehicle file, and
/// std::invalid_argument when the update sets only some formula keys of a curve that the
/// base gives as a table.
[[nodiscard]] MergeResult mergeVehicleYaml(std::string_view base_text, const std::string& base_name,
                                           const VehicleUpdate& update);

/// Reads `base`, merges, checks and writes `out` (through a temporary file and a rename, so a
/// failure leaves `out` untouched). `out` may be the base file itself only because the caller
/// names it: nothing is ever written anywhere else.
MergeResult writeVehicleFile(const std::filesystem::path& base, const std::filesystem::path& out,
                             const VehicleUpdate& update);

/// The same from the text of a base file (e.g. io::builtinVehicleYaml()).
MergeResult writeVehicleFile(std::string_view base_text, const std::string& base_name,
                             const std::filesystem::path& out, const VehicleUpdate& update);

}  // namespace geaware::io
