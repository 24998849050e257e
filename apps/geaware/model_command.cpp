// `geaware model`: the controller-side ground-effect model per height.

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

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

model::VehicleParams loadVehicle(const std::string& path) {
  return path.empty() ? io::builtinVehicle() : io::loadVehicleFile(path);
}

void printTable(const std::vector<Row>& rows, const model::VehicleParams& p) {
  fmt::print("vehicle {} (m = {} kg, b = {} m); h = rotor-plane height above ground\n", p.name,
             p.mass_kg, p.diagonal_rotor_distance_m);
  fmt::print("{:>8} {:>8} {:>10} {:>11} {:>11} {:>9} {:>9} {:>10}\n", "h [m]", "F_G [-]",
             "M_G [m]", "J'x [kgm2]", "J'y [kgm2]", "d_x [Ns/m]", "d_y [Ns/m]", "n_hov [rpm]");
  for (const auto& r : rows) {
    fmt::print("{:8.3f} {:8.4f} {:10.5f} {:11.6f} {:11.6f} {:9.4f} {:9.4f} {:10.0f}\n", r.h, r.f_g,
               r.m_g, r.jx, r.jy, r.dx, r.dy, r.n_hover);
  }
}

void printCsv(const std::vector<Row>& rows, std::FILE* out) {
  fmt::print(out, "h_m,F_G,M_G_m,Jx_kgm2,Jy_kgm2,d_x_N_per_mps,d_y_N_per_mps,n_hover_rpm\n");
  for (const auto& r : rows) {
    fmt::print(out, "{},{},{},{},{},{},{},{}\n", r.h, r.f_g, r.m_g, r.jx, r.jy, r.dx, r.dy, r.n_hover);
  }
}

std::string toJson(const std::vector<Row>& rows, const model::VehicleParams& p) {
  std::string s = fmt::format("{{\"vehicle\":\"{}\",\"rows\":[", p.name);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    s += fmt::format(
        "{}{{\"h_m\":{},\"F_G\":{},\"M_G_m\":{},\"Jx_kgm2\":{},\"Jy_kgm2\":{},"
        "\"d_x_N_per_mps\":{},\"d_y_N_per_mps\":{},\"n_hover_rpm\":{}}}",
        i ? "," : "", r.h, r.f_g, r.m_g, r.jx, r.jy, r.dx, r.dy, r.n_hover);
  }
  return s + "]}\n";
}

int runModel(const ModelOptions& o) {
  const model::VehicleModel vehicle(loadVehicle(o.vehicle));
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

  if (o.format == "csv") {
    printCsv(rows, stdout);
  } else {
    printTable(rows, vehicle.params());
  }
  if (!o.json.empty()) {
    const std::string doc = toJson(rows, vehicle.params());
    if (o.json == "-") {
      std::cout << doc;
    } else {
      std::ofstream f(o.json);
      if (!(f << doc)) throw std::runtime_error(o.json + ": cannot write JSON output");
    }
  }
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
  cmd->add_option("--json", opts->json, "also write the rows as one JSON object to FILE ('-': stdout)");
  return [opts] { return runModel(*opts); };
}

}  // namespace geaware::cli
