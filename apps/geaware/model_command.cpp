// SPDX-License-Identifier: BSD-3-Clause
// `geaware model`: the controller-side ground-effect model per height (experiments/model_table).

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "geaware/experiments/model_table.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/range.hpp"
#include "geaware/io/vehicle_file.hpp"

namespace geaware::cli {
namespace {

struct ModelOptions {
  std::string vehicle;
  std::string heights = "0.072:2.0:0.05";
  std::string format = "table";
  std::string json;
};

int runModel(const ModelOptions& o) {
  io::OutputChecks files;
  files.input("--vehicle", o.vehicle);
  files.output("--json", o.json);
  files.check();
  const model::VehicleModel vehicle(o.vehicle.empty() ? io::builtinVehicle()
                                                      : io::loadVehicleFile(o.vehicle));
  const io::Range range = io::parseRange(o.heights, "--heights", 100'000);
  if (range.from < 0.0) throw std::invalid_argument("--heights '" + o.heights + "': heights must be ≥ 0 m");
  const auto rows = experiments::modelRows(vehicle, range.values());
  const double lowest = vehicle.params().min_rotor_plane_height_m;
  if (range.from < lowest) {
    std::cerr << fmt::format("geaware: note: heights below {} m (the vehicle's lowest rotor-plane "
                             "height) are evaluated at {} m\n", lowest, lowest);
  }
  // With --json - stdout carries the JSON document alone; the table goes to stderr.
  std::FILE* human = o.json == "-" ? stderr : stdout;
  fmt::print(human, "{}", o.format == "csv" ? experiments::formatModelCsv(rows)
                                            : experiments::formatModelTable(rows, vehicle.params()));
  std::fflush(human);
  if (!o.json.empty()) {
    writeJsonOutput(o.json, experiments::modelJson(rows, vehicle.params()), runInfo({}, {o.vehicle}));
  }
  return 0;
}

}  // namespace

Runner addModelCommand(CLI::App& app) {
  auto opts = std::make_shared<ModelOptions>();
  auto* cmd = app.add_subcommand(
      "model", "Tabulate the ground-effect model (F_G, M_G, J', drag, hover rpm) over heights");
  addVehicleOption(cmd, opts->vehicle);
  cmd->add_option("--heights", opts->heights, "rotor-plane heights FROM:TO:STEP [m]")->capture_default_str();
  cmd->add_option("--format", opts->format, "output format")
      ->check(CLI::IsMember({"table", "csv"}))
      ->capture_default_str();
  cmd->add_option("--json", opts->json,
                  "also write the rows and the vehicle's parameters as one JSON object to FILE "
                  "('-': stdout, the table then goes to stderr)");
  return [opts] { return runModel(*opts); };
}

}  // namespace geaware::cli
