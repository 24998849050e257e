// SPDX-License-Identifier: BSD-3-Clause
// `geaware train-residual LOGS… --out weights.yaml`: the Neural-Lander baseline trained on flight
// logs (docs/neural-lander.md, "Training on your logs"). Thin: parse, read the logs as
// `identify flight` does (flight_input.hpp), build the rows and train (experiments/
// neural_baseline.hpp, neural/trainer.hpp), print and write.

#include "commands.hpp"
#include "flight_input.hpp"
#include "numbers.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "geaware/experiments/neural_baseline.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/neural/trainer.hpp"
#include "geaware/neural/weights_file.hpp"

namespace geaware::cli {
namespace {

struct TrainOptions {
  std::vector<std::string> logs;
  std::vector<std::string> held_out;  ///< logs evaluated, not trained on
  std::string out;
  std::string json;
  std::string vehicle;
  std::string map;
  std::vector<std::string> columns;    ///< --column NAME=EXPR
  std::vector<std::string> constants;  ///< --const NAME=VALUE
  double mass_kg = 0.0;
  std::uint64_t seed = 1;
  int epochs = 300;
  double validation_fraction = 0.2;
};

/// Rows of every log in `logs`, one line per log on stderr.
neural::TrainingSet rows(const std::vector<std::string>& logs, const TrainOptions& o,
                         const model::VehicleParams& base, io::Json& per_log) {
  neural::TrainingSet set;
  for (const auto& log : logs) {
    const ident::FlightLog flight = readFlightInput(log, o.map, o.columns, o.constants, base, o.vehicle);
    const std::size_t added = experiments::addLogRows(set, flight, base);
    std::cerr << "geaware: note: " << log << ": " << added << " rows of " << flight.size() << " samples\n";
    per_log.push_back({{"log", log}, {"rows", added}, {"samples", flight.size()}});
  }
  return set;
}

int runTrain(const TrainOptions& o) {
  io::OutputChecks files;
  for (const auto& l : o.logs) files.input("LOGS", l);
  for (const auto& l : o.held_out) files.input("--held-out", l);
  files.input("--vehicle", o.vehicle);
  files.input("--map", o.map);
  files.output("--out", o.out, false);
  files.output("--json", o.json);
  files.check();
  if (o.vehicle.empty() && o.mass_kg == 0.0) {
    throw UsageError("train-residual: the labels need the vehicle's mass: --vehicle FILE or --mass-kg M (the built-in "
                     "paper quadrotor's 1.696 kg is not taken for another vehicle)");
  }
  model::VehicleParams base = o.vehicle.empty() ? io::builtinVehicle() : io::loadVehicleFile(o.vehicle);
  if (o.mass_kg > 0.0) base.mass_kg = o.mass_kg;

  io::Json doc{{"command", "train-residual"}, {"out", o.out}};
  io::Json& logs = doc["logs"] = io::Json::array();
  const neural::TrainingSet set = rows(o.logs, o, base, logs);
  neural::TrainOptions t = experiments::NeuralSettings::defaultTrainOptions();
  t.seed = o.seed;
  t.epochs = o.epochs;
  t.validation_fraction = o.validation_fraction;
  std::cerr << "geaware: training on " << set.size() << " rows (" << t.epochs << " epochs, seed " << t.seed << ", "
            << o.validation_fraction * 100.0 << " % held out for validation)\n";
  const neural::TrainResult trained = neural::train(set, t);
  const double train_mse = trained.train_loss.empty() ? NAN : trained.train_loss.back();
  const double validation_mse = trained.validation_loss.empty() ? NAN : trained.validation_loss.back();
  // Human text on stdout, unless stdout carries the JSON.
  std::ostream& text = o.json == "-" ? std::cerr : std::cout;
  text << fmt::format("rows                 {:>8} training, {} validation\n", trained.train_rows,
                           trained.validation_rows)
            << fmt::format("MSE without network  {:>12.5g} N² per component (the labels: what the nominal model leaves)\n",
                           experiments::labelMeanSquare(set))
            << fmt::format("MSE training rows    {:>12.5g} N²\n", train_mse)
            << fmt::format("MSE validation rows  {:>12.5g} N² (the {:g} % of rows split off at random)\n",
                           validation_mse, o.validation_fraction * 100.0);
  doc["rows"] = {{"training", trained.train_rows}, {"validation", trained.validation_rows}};
  doc["mse_N2"] = {{"labels", experiments::labelMeanSquare(set)}, {"training", train_mse},
                   {"validation", validation_mse}};
  if (!o.held_out.empty()) {
    io::Json& held_logs = doc["held_out_logs"] = io::Json::array();
    const neural::TrainingSet held = rows(o.held_out, o, base, held_logs);
    const double without = experiments::labelMeanSquare(held);
    const double with = neural::meanSquaredError(trained.weights, held);
    text << fmt::format("MSE held-out logs    {:>12.5g} N² with the network, {:.5g} N² without ({} rows)\n", with,
                             without, held.size());
    doc["held_out"] = {{"rows", held.size()}, {"mse_with_network_N2", with}, {"mse_without_network_N2", without}};
  }

  neural::WeightsDocument weights;
  weights.weights = trained.weights;
  weights.provenance["produced_by"] = "geaware train-residual";
  weights.provenance["command"] = commandLine();
  weights.provenance["seed"] = std::to_string(o.seed);
  weights.provenance["rows"] = std::to_string(set.size());
  weights.provenance["final_validation_loss_N2"] = fmt::format("{}", validation_mse);
  std::string names;
  for (const auto& l : o.logs) names += (names.empty() ? "" : " ") + std::filesystem::path(l).filename().string();
  weights.provenance["logs"] = names;
  neural::saveWeights(o.out, weights);
  std::cerr << "geaware: wrote " << o.out << "\n";
  if (!o.json.empty()) {
    std::vector<std::string> inputs = o.logs;
    inputs.insert(inputs.end(), o.held_out.begin(), o.held_out.end());
    inputs.push_back(o.vehicle);
    writeJsonOutput(o.json, std::move(doc), runInfo({o.seed}, inputs));
  }
  return 0;
}

}  // namespace

Runner addTrainCommand(CLI::App& app) {
  auto o = std::make_shared<TrainOptions>();
  auto* cmd = app.add_subcommand("train-residual",
                                 "Train the Neural-Lander residual network on flight logs (docs/neural-lander.md)");
  cmd->add_option("logs", o->logs, "flight logs, read as `identify flight` reads them (CSV, or --map)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "the weight file to write (docs/neural-lander.md)")->required();
  cmd->add_option("--held-out", o->held_out, "flight logs to evaluate the trained network on (not trained on)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--json", o->json, "write the rows and losses as JSON ('-': stdout)");
  addVehicleOption(cmd, o->vehicle, "vehicle file: the mass and the high-altitude drag the labels subtract");
  cmd->add_option("--mass-kg", o->mass_kg, "the vehicle's mass [kg] (instead of the vehicle file's)")
      ->check(finiteIn(0.0, 1000.0, true));
  cmd->add_option("--map", o->map,
                  "read autopilot logs through a log map: a built-in name (px4, ardupilot, crazyflie) or a map file "
                  "(docs/identification.md, \"Mapping a log\")");
  cmd->add_option("--column", o->columns,
                  "a column from the logs' fields, NAME=EXPR with units, as for identify flight (e.g. h_m=z[mm]); "
                  "repeatable");
  cmd->add_option("--const", o->constants, "a column the logs do not have, NAME=VALUE (as for identify flight); repeatable");
  cmd->add_option("--seed", o->seed, "initialisation, validation split and shuffling")->check(seed())->capture_default_str();
  cmd->add_option("--epochs", o->epochs, "passes over the training rows")->check(wholeIn(1, 100000))->capture_default_str();
  cmd->add_option("--validation-fraction", o->validation_fraction, "share of the rows held out for validation")
      ->check(finiteIn(0.0, 0.9))
      ->capture_default_str();
  return [o] { return runTrain(*o); };
}

}  // namespace geaware::cli
