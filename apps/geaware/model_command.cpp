// `geaware model`: the controller-side ground-effect model per height.

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "commands.hpp"
#include "geaware/io/range.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::cli {
namespace {

struct ModelOptions {
  std::string vehicle;
  std::string heights = "0.072:2.0:0.05";
  std::string format = "table";
  std::string json;
};

struct Row {
  double h, f_g, m_g, jx, jy, dx, dy, n_hover;
};

/// Column keys (CSV header and JSON keys), in Row order.
constexpr const char* kKeys[] = {"h_m",     "F_G",           "M_G_m",         "Jx_kgm2",
                                 "Jy_kgm2", "d_x_N_per_mps", "d_y_N_per_mps", "n_hover_rpm"};

void printTable(std::FILE* out, const std::vector<Row>& rows, const model::VehicleParams& p) {
  fmt::print(out, "vehicle {} (m = {} kg, b = {} m); h = rotor-plane height above ground\n", p.name,
             p.mass_kg, p.diagonal_rotor_distance_m);
  fmt::print(out, "{:>8} {:>8} {:>10} {:>11} {:>11} {:>9} {:>9} {:>10}\n", "h [m]", "F_G [-]",
             "M_G [m]", "J'x [kgm2]", "J'y [kgm2]", "d_x [Ns/m]", "d_y [Ns/m]", "n_hov [rpm]");
  for (const auto& r : rows) {
    fmt::print(out, "{:8.3f} {:8.4f} {:10.5f} {:11.6f} {:11.6f} {:9.4f} {:9.4f} {:10.0f}\n", r.h,
               r.f_g, r.m_g, r.jx, r.jy, r.dx, r.dy, r.n_hover);
  }
}

void printCsv(std::FILE* out, const std::vector<Row>& rows) {
  fmt::print(out, "{}\n", fmt::join(kKeys, ","));
  for (const auto& r : rows) {
    fmt::print(out, "{},{},{},{},{},{},{},{}\n", r.h, r.f_g, r.m_g, r.jx, r.jy, r.dx, r.dy, r.n_hover);
  }
}

io::Json toJson(const std::vector<Row>& rows, const model::VehicleParams& p) {
  io::Json doc = {{"vehicle", p.name}, {"rows", io::Json::array()}};
  for (const auto& r : rows) {
    const double v[] = {r.h, r.f_g, r.m_g, r.jx, r.jy, r.dx, r.dy, r.n_hover};
    io::Json row;
    for (std::size_t i = 0; i < std::size(kKeys); ++i) row[kKeys[i]] = v[i];
    doc["rows"].push_back(std::move(row));
  }
  return doc;
}

int runModel(const ModelOptions& o) {
  const model::VehicleModel vehicle(o.vehicle.empty() ? io::builtinVehicle()
                                                      : io::loadVehicleFile(o.vehicle));
  const io::Range range = io::parseRange(o.heights, "--heights", 100'000);
  if (range.from < 0.0) throw std::invalid_argument("--heights '" + o.heights + "': heights must be ≥ 0 m");

  std::vector<Row> rows;
  const auto& ge = vehicle.groundEffect();
  for (double h : range.values()) {
    const Eigen::Vector3d J = ge.levelingInertiaDiagonal(h);
    const Eigen::Vector2d d = vehicle.drag().coefficients(h);
    rows.push_back({h, ge.thrustRatio(h), ge.levelingCoefficient(h), J.x(), J.y(), d.x(), d.y(),
                    vehicle.hoverSpeedRpm(h)});
  }
  if (range.from < vehicle.params().min_rotor_plane_height_m) {
    std::cerr << fmt::format(
        "geaware: note: heights below {} m (the vehicle's lowest rotor-plane height) are "
        "evaluated at {} m\n",
        vehicle.params().min_rotor_plane_height_m, vehicle.params().min_rotor_plane_height_m);
  }
  // With --json - stdout carries the JSON document alone; the table goes to stderr.
  std::FILE* human = o.json == "-" ? stderr : stdout;
  if (o.format == "csv") {
    printCsv(human, rows);
  } else {
    printTable(human, rows, vehicle.params());
  }
  if (!o.json.empty()) writeJsonOutput(o.json, toJson(rows, vehicle.params()), runInfo({}, {o.vehicle}));
  return 0;
}

}  // namespace

Runner addModelCommand(CLI::App& app) {
  auto opts = std::make_shared<ModelOptions>();
  auto* cmd = app.add_subcommand(
      "model", "Tabulate the ground-effect model (F_G, M_G, J', drag, hover rpm) over heights");
  cmd->add_option("--vehicle", opts->vehicle,
                  "vehicle YAML file (default: the built-in paper quadrotor)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--heights", opts->heights, "rotor-plane heights FROM:TO:STEP [m]")
      ->capture_default_str();
  cmd->add_option("--format", opts->format, "output format")
      ->check(CLI::IsMember({"table", "csv"}))
      ->capture_default_str();
  cmd->add_option("--json", opts->json,
                  "also write the rows as one JSON object to FILE ('-': stdout, the table then "
                  "goes to stderr)");
  return [opts] { return runModel(*opts); };
}

}  // namespace geaware::cli
