#include "geaware/io/vehicle_file.hpp"

#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "geaware/io/yaml_reader.hpp"

namespace geaware::io {
namespace detail {
extern const std::string_view kBuiltinVehicleYaml;
}  // namespace detail

namespace {

/// A curve given as `table: {heights_m: [...], <values_key>: [...]}` instead of the formula's
/// keys. Returns false when the section has no table (the caller reads the formula). A table
/// next to the formula's keys is a problem: one of them would be silently ignored.
bool readHeightTable(MapReader& section, const std::string& values_key,
                     const std::vector<std::string>& formula_keys, model::HeightTableParams& out) {
  if (!section.has("table")) return false;
  auto t = section.map("table");
  out.heights_m = t.numbers("heights_m");
  out.values = t.numbers(values_key);
  t.rejectUnknownKeys();
  for (const auto& k : formula_keys) {
    if (section.has(k)) {
      (void)section.number(k);  // read, so it is reported once, here, not as unknown
      section.problem(k, "is not used when the curve is given as a table: give either " +
                             std::string("the formula's keys or 'table', not both"));
    }
  }
  return true;
}

model::VehicleParams readVehicle(MapReader& root) {
  model::VehicleParams p;
  p.name = root.text("name");
  p.mass_kg = root.number("mass_kg");
  {
    auto m = root.map("inertia_kgm2");
    p.inertia_kgm2 = {m.number("xx"), m.number("yy"), m.number("zz")};
    m.rejectUnknownKeys();
  }
  {
    auto m = root.map("geometry");
    p.diagonal_rotor_distance_m = m.number("diagonal_rotor_distance_m");
    p.propeller_radius_m = m.number("propeller_radius_m");
    p.min_rotor_plane_height_m = m.number("min_rotor_plane_height_m");
    m.rejectUnknownKeys();
  }
  {
    auto m = root.map("rotor");
    p.rotor.k_T_N_per_rpm2 = m.number("k_T_N_per_rpm2");
    p.rotor.k_TX_N_per_rpm2 = m.number("k_TX_N_per_rpm2");
    p.rotor.k_TY_N_per_rpm2 = m.number("k_TY_N_per_rpm2");
    p.rotor.k_I_Nm_per_rpm2 = m.number("k_I_Nm_per_rpm2");
    p.rotor.J_R_kgm2 = m.number("J_R_kgm2");
    m.rejectUnknownKeys();
  }
  {
    auto m = root.map("throttle_curve");
    p.throttle.c2_rpm2 = m.number("c2_rpm2");
    p.throttle.c1_rpm2 = m.number("c1_rpm2");
    p.throttle.c0_rpm2 = m.number("c0_rpm2");
    m.rejectUnknownKeys();
  }
  {
    auto ge = root.map("ground_effect");
    auto at = ge.map("additional_thrust");
    if (!readHeightTable(at, "F_G", {"g1_m2", "g2_m2"}, p.additional_thrust.table)) {
      p.additional_thrust.g1_m2 = at.number("g1_m2");
      p.additional_thrust.g2_m2 = at.number("g2_m2");
    }
    at.rejectUnknownKeys();
    auto lt = ge.map("leveling_torque");
    if (!readHeightTable(lt, "M_G_m", {"g3_m", "g4_m2", "scale_m4"}, p.leveling_torque.table)) {
      p.leveling_torque.g3_m = lt.number("g3_m");
      p.leveling_torque.g4_m2 = lt.number("g4_m2");
      p.leveling_torque.scale_m4 = lt.number("scale_m4");
    }
    lt.rejectUnknownKeys();
    ge.rejectUnknownKeys();
  }
  {
    auto m = root.map("drag");
    p.drag.heights_m = m.numbers("heights_m");
    p.drag.d_x_N_per_mps = m.numbers("d_x_N_per_mps");
    p.drag.d_y_N_per_mps = m.numbers("d_y_N_per_mps");
    m.rejectUnknownKeys();
  }
  root.rejectUnknownKeys();
  return p;
}

}  // namespace

model::VehicleParams parseVehicleYaml(std::string_view yaml_text, const std::string& source) {
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  if (!doc.IsMap()) {
    throw ConfigError(source, {{1, "", "expected a map of vehicle parameters at the top level"}});
  }
  YamlContext ctx;
  MapReader root(doc, "", ctx);
  model::VehicleParams params = readVehicle(root);
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));

  // Physical validation, each problem reported at the line of its key.
  for (const auto& e : params.validate()) {
    ctx.problem(ctx.lineOf(e.field), e.field, "got " + e.value + ", expected " + e.expected);
  }
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));
  return params;
}

model::VehicleParams loadVehicleFile(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw std::runtime_error(file.string() + (std::filesystem::exists(file, ec)
                                                  ? ": not a regular file (expected a vehicle YAML file)"
                                                  : ": no such vehicle file"));
  }
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  if (!in || !(text << in.rdbuf())) throw std::runtime_error(file.string() + ": cannot read vehicle file");
  return parseVehicleYaml(text.str(), file.string());
}

std::string_view builtinVehicleYaml() noexcept { return detail::kBuiltinVehicleYaml; }

model::VehicleParams builtinVehicle() {
  return parseVehicleYaml(detail::kBuiltinVehicleYaml, "<built-in paper_quad>");
}

}  // namespace geaware::io
