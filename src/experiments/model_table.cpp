// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/model_table.hpp"

#include <fmt/format.h>

#include <array>

#include "geaware/model/vehicle_schema.hpp"

namespace geaware::experiments {
namespace {

/// Column keys (CSV header and JSON keys), in ModelRow order.
constexpr std::array<const char*, 8> kKeys = {"h_m",     "F_G",           "M_G_m",
                                              "Jx_kgm2", "Jy_kgm2",       "d_x_N_per_mps",
                                              "d_y_N_per_mps", "n_hover_rpm"};

std::array<double, 8> values(const ModelRow& r) {
  return {r.h_m, r.f_g, r.m_g_m, r.jx_kgm2, r.jy_kgm2, r.d_x_N_per_mps, r.d_y_N_per_mps, r.n_hover_rpm};
}

}  // namespace

std::vector<ModelRow> modelRows(const model::VehicleModel& vehicle, const std::vector<double>& heights_m) {
  std::vector<ModelRow> rows;
  const auto& ge = vehicle.groundEffect();
  for (double h : heights_m) {
    const Eigen::Vector3d J = ge.levelingInertiaDiagonal(h);
    const Eigen::Vector2d d = vehicle.drag().coefficients(h);
    rows.push_back({h, ge.thrustRatio(h), ge.levelingCoefficient(h), J.x(), J.y(), d.x(), d.y(),
                    vehicle.hoverSpeedRpm(h)});
  }
  return rows;
}

std::string formatModelTable(const std::vector<ModelRow>& rows, const model::VehicleParams& p) {
  std::string s = fmt::format("vehicle {} (m = {} kg, b = {} m); h = rotor-plane height above ground\n",
                              p.name, p.mass_kg, p.diagonal_rotor_distance_m);
  s += fmt::format("{:>8} {:>8} {:>10} {:>11} {:>11} {:>9} {:>9} {:>10}\n", "h [m]", "F_G [-]",
                   "M_G [m]", "J'x [kgm2]", "J'y [kgm2]", "d_x [Ns/m]", "d_y [Ns/m]", "n_hov [rpm]");
  for (const auto& r : rows) {
    s += fmt::format("{:8.3f} {:8.4f} {:10.5f} {:11.6f} {:11.6f} {:9.4f} {:9.4f} {:10.0f}\n", r.h_m,
                     r.f_g, r.m_g_m, r.jx_kgm2, r.jy_kgm2, r.d_x_N_per_mps, r.d_y_N_per_mps,
                     r.n_hover_rpm);
  }
  return s;
}

std::string formatModelCsv(const std::vector<ModelRow>& rows) {
  std::string s = fmt::format("{},{},{},{},{},{},{},{}\n", kKeys[0], kKeys[1], kKeys[2], kKeys[3],
                              kKeys[4], kKeys[5], kKeys[6], kKeys[7]);
  for (const auto& r : rows) {
    const auto v = values(r);
    s += fmt::format("{},{},{},{},{},{},{},{}\n", v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
  }
  return s;
}

io::Json modelJson(const std::vector<ModelRow>& rows, const model::VehicleParams& p) {
  io::Json doc = {{"vehicle", p.name}, {"rows", io::Json::array()}};
  for (const auto& r : rows) {
    const auto v = values(r);
    io::Json row;
    for (std::size_t i = 0; i < kKeys.size(); ++i) row[kKeys[i]] = v[i];
    doc["rows"].push_back(std::move(row));
  }
  io::Json parameters = io::Json::object();
  model::forEachParameter(p, [&](const auto& key, const auto& unit, const auto& value) {
    parameters[std::string(key)] = {{"value", value}, {"unit", std::string(unit)}};
  });
  doc["parameters"] = std::move(parameters);
  return doc;
}

}  // namespace geaware::experiments
