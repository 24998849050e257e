// SPDX-License-Identifier: BSD-3-Clause
// `geaware identify`: rig and flight logs → parameters with standard errors, a merged vehicle
// file (--out), one JSON object (--json) and an HTML report (--report). Thin: parse, read the
// log, call the ident library (ident/identify.hpp), print and write.

#include "commands.hpp"
#include "flight_input.hpp"
#include "numbers.hpp"

#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/experiments/identify_report.hpp"
#include "geaware/ident/identify.hpp"
#include "geaware/ident/screen.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_map.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/provenance.hpp"
#include "geaware/io/range.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/io/vehicle_writer.hpp"

namespace geaware::cli {
namespace {

struct IdentifyOptions {
  std::string kind;                  ///< rotor, platform, flight, correlations
  std::string log;
  std::string vehicle;               ///< base vehicle file (default: built-in)
  std::string out;                   ///< merged vehicle file
  std::string json;                  ///< JSON output ('-': stdout)
  std::string report;                ///< report directory
  std::vector<std::string> columns;    ///< --column NAME=EXPR
  std::vector<std::string> constants;  ///< --const NAME=VALUE
  std::string loss = "huber";
  double tilt_limit_deg = 10.0;
  int height_bands = 6;
  bool hover = false;
  bool fade = false;                    ///< flight: the forward-flight fade v_i
  bool accept_warnings = false;         ///< write --out despite blocking warnings
  std::string ground_effect = "paper";  ///< paper: the closed forms; table: values at knots
  double table_top_m = 0.5;             ///< automatic F_G knots up to this height [m]
  std::string table_heights;            ///< explicit knots FROM:TO:STEP (empty: automatic)
  std::string map;                      ///< log map (built-in name or file) for autopilot logs
  std::string rotor_speed = "auto";     ///< with --map: rpm (logged), throttle (through the curve), auto
  std::string voltage_column;           ///< rotor: the battery-voltage column (empty: none)
  double reference_voltage_V = 0.0;     ///< rotor: the curve's reference voltage (0: median) [V]
  double mass_kg = 0.0;                 ///< vehicle mass [kg]; 0: the base vehicle's
  std::string std_column;               ///< platform: rows are means, the std of fz_N [N] (empty: none)
  std::string count_column;             ///< platform: rows are means, the samples behind each (empty: none)
  bool k_T_only = false;                ///< platform: k_T alone, one height band, F_G not fitted
};

/// The --column NAME=EXPR and --const NAME=VALUE definitions (io/column_expression.hpp),
/// parsed before any log is read; a bad one is a usage error naming the option and character.
ident::ColumnDefinitions columnDefinitions(const IdentifyOptions& opt) {
  ident::ColumnDefinitions d;
  try {
    for (const auto& s : opt.columns) d.push_back(io::parseColumnDefinition(s, "--column"));
    for (const auto& s : opt.constants) d.push_back(io::parseColumnDefinition(s, "--const", true));
  } catch (const io::ExpressionError& e) {
    throw UsageError(e.what());
  }
  for (std::size_t i = 0; i < d.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (d[i].name == d[j].name) throw UsageError(d[i].option + ": '" + d[i].name + "' is defined twice (also " + d[j].option + ")");
    }
  }
  return d;
}

/// A flight log read from an autopilot log (ULog, DataFlash, CSV export) through a log map:
/// the mapped channels on one time axis in ENU/FLU, a_ext computed by the paper's observer.
/// Whether a mapped flight's rotor speeds come from the log's rotor speeds ("rpm") or its
/// throttles ("throttle"): --rotor-speed, or with auto the map's rotor_speed when the log has it,
/// else its throttle when the log has that, else "rpm" (mapFlight then names the fields missing).
std::string rotorSpeedSource(const IdentifyOptions& opt, const io::LogData& data, const io::LogMap& map) {
  if (opt.rotor_speed != "auto") return opt.rotor_speed;
  if (io::logHasChannel(data, map, "rotor_speed")) return "rpm";
  if (io::logHasChannel(data, map, "throttle")) return "throttle";
  return "rpm";  // mapFlight then names the rotor_speed fields the log lacks
}

ident::FlightLog readMappedFlight(const IdentifyOptions& opt, const model::VehicleParams& base,
                                  std::vector<std::string>& notes) {
  io::LogMap map = io::loadLogMap(opt.map);
  try {
    io::applyColumnDefinitions(map, columnDefinitions(opt));
  } catch (const io::ExpressionError& e) {
    throw UsageError(e.what());
  }
  std::vector<std::string> wanted = {"height", "specific_force", "attitude"};
  if (!opt.hover) wanted.emplace_back("velocity");
  std::vector<std::string> asked = wanted;
  for (const char* c : {"rotor_speed", "throttle", "armed", "battery_voltage"}) asked.emplace_back(c);
  // Only the mapped topics are decoded, unless a channel names none (its fields are looked up
  // in every topic) or --column/--const may name any.
  io::LogReadOptions read;
  bool every_topic = !opt.columns.empty() || !opt.constants.empty();
  for (const auto& w : asked) {
    if (const auto it = map.channels.find(w); it != map.channels.end()) {
      read.topics.push_back(it->second.topic);
      every_topic = every_topic || it->second.topic.empty();
    }
  }
  if (every_topic) read.topics.clear();
  const io::LogData data = io::readLog(opt.log, read);
  for (const auto& w : data.warnings) std::cerr << "geaware: warning: " << opt.log << ": " << w << "\n";
  const std::string source = rotorSpeedSource(opt, data, map);
  if (source == "throttle") {
    // The built-in quadrotor's curve is another ESC's and motor's: refused, as its mass is.
    if (opt.vehicle.empty()) {
      throw UsageError(opt.log + ": rotor speeds from throttles need the vehicle's throttle curve: --vehicle FILE "
                       "with throttle_curve (`identify rotor` fits it from a stand log with throttle and voltage "
                       "columns; the built-in paper quadrotor's curve is not taken for another vehicle)");
    }
    wanted.emplace_back("throttle");
    // The voltage only when the curve uses it (a battery logged slower or with gaps would
    // otherwise cost rows); a log that has it for a curve without a voltage dependence is said.
    if (base.throttle.reference_voltage_V > 0.0) {
      if (map.channels.count("battery_voltage") > 0) wanted.emplace_back("battery_voltage");
    } else if (io::logHasChannel(data, map, "battery_voltage")) {
      std::cerr << "geaware: warning: " << opt.log << ": the log has the battery voltage but the vehicle's throttle "
                << "curve has no voltage dependence (throttle_curve.reference_voltage_V = 0; `identify rotor` with "
                << "a voltage column fits it): a sagging battery reads as lost lift\n";
    }
    if (map.channels.count("armed") > 0 && io::logHasChannel(data, map, "armed")) wanted.emplace_back("armed");
  } else {
    wanted.emplace_back("rotor_speed");
  }
  io::MappedFlight mapped = io::mapFlight(data, map, wanted);
  std::vector<std::string> warnings = mapped.warnings;
  if (source == "throttle") {
    const ident::ThrottleConversion conversion = ident::rotorSpeedsFromThrottle(mapped, base.throttle);
    mapped.notes.insert(mapped.notes.end(), conversion.notes.begin(), conversion.notes.end());
    warnings.insert(warnings.end(), conversion.warnings.begin(), conversion.warnings.end());
  }
  ident::MappedFlightLog flight = ident::flightLogFromMapped(mapped, base.mass_kg, base.rotor.k_T_N_per_rpm2);
  ident::FlightColumns names;
  for (std::size_t k = 0; k < names.n.size() && k < mapped.rotor_fields.size(); ++k) {
    names.n[k] = "rotor " + std::to_string(k + 1) + " (" + mapped.rotor_fields[k] + ")";
  }
  names.a_ext[2] = "a_ext z (computed)";
  notes = ident::screenFlight(flight.log, names);
  for (const auto& n : mapped.notes) std::cerr << "geaware: note: " << opt.log << ": " << n << "\n";
  for (const auto& n : flight.notes) std::cerr << "geaware: note: " << opt.log << ": " << n << "\n";
  for (const auto& w : warnings) std::cerr << "geaware: warning: " << opt.log << ": " << w << "\n";
  std::cerr << "geaware: note: " << opt.log << ": " << flight.log.size() << " samples for the fit, a_ext from the IMU, "
            << "attitude and rotor speeds" << (source == "throttle" ? " (from throttles)" : "") << " with m = "
            << base.mass_kg << " kg\n";
  return std::move(flight.log);
}

ident::PlatformLog readPlatform(const IdentifyOptions& opt, std::vector<std::string>& notes) {
  ident::PlatformColumns c;
  c.fz_std = opt.std_column;
  c.count = opt.count_column;
  ident::PlatformLog log = ident::readPlatformLog(opt.log, c, columnDefinitions(opt));
  notes = ident::screenPlatform(log, c);
  return log;
}

/// The result with the screening's notes (rows dropped before the fit) in front of its own.
ident::IdentifyResult withNotes(ident::IdentifyResult r, std::vector<std::string> notes) {
  notes.insert(notes.end(), r.notes.begin(), r.notes.end());
  r.notes = std::move(notes);
  return r;
}

/// A flight or hover log: through --map, or a CSV with the --column and --const definitions; screened.
ident::FlightLog readFlight(const IdentifyOptions& opt, const model::VehicleParams& base,
                            std::vector<std::string>& notes) {
  if (!opt.map.empty()) return readMappedFlight(opt, base, notes);
  ident::FlightColumns c;
  const ident::ColumnDefinitions d = columnDefinitions(opt);
  ident::FlightLog log = opt.hover ? ident::readHoverLog(opt.log, c, d) : ident::readFlightLog(opt.log, c, d);
  notes = ident::screenFlight(log, c);
  return log;
}

ident::IdentifyResult identify(const IdentifyOptions& opt, const model::VehicleParams& base) {
  ident::IdentifyOptions io_opt;
  io_opt.robust = ident::robustLoss(opt.loss);
  io_opt.height_bands = opt.height_bands;
  io_opt.tilt_limit_deg = opt.tilt_limit_deg;
  io_opt.k_T_only = opt.k_T_only;
  if (opt.ground_effect == "table") {
    io_opt.ground_effect = ident::CurveForm::kTable;
    io_opt.table_top_m = opt.table_top_m;
    if (!opt.table_heights.empty()) {
      io_opt.table_heights_m = io::parseRange(opt.table_heights, "--table-heights", 1000).values();
    }
  }
  std::vector<std::string> notes;  // of the screening before the fit (ident/screen.hpp)
  if (opt.kind == "rotor") {
    ident::RotorStandColumns c;
    c.voltage = opt.voltage_column;
    io_opt.reference_voltage_V = opt.reference_voltage_V;
    ident::RotorStandLog log = ident::readRotorStandLog(opt.log, c, columnDefinitions(opt));
    notes = ident::screenRotorStand(log, c);
    return withNotes(ident::identifyRotorStand(log, io_opt), notes);
  }
  if (opt.kind == "platform") {
    const ident::PlatformLog log = readPlatform(opt, notes);
    return withNotes(ident::identifyPlatform(log, base, io_opt), notes);
  }
  if (opt.kind == "correlations") {
    const ident::PlatformLog log = readPlatform(opt, notes);
    return withNotes(ident::identifyCorrelations(log, base), notes);
  }
  const ident::FlightLog log = readFlight(opt, base, notes);
  if (opt.fade) return withNotes(ident::identifyForwardFade(log, base, io_opt), notes);
  return withNotes(opt.hover ? ident::identifyHover(log, base, io_opt) : ident::identifyFlight(log, base, io_opt),
                   notes);
}

io::Json estimateJson(const ident::Estimate& e) { return {{"value", e.value}, {"std_error", e.std_error}}; }

/// The result as the JSON document of `identify --json` (the kind's extras after the
/// parameters, fits and warnings).
io::Json toJson(const ident::IdentifyResult& r, const IdentifyOptions& opt) {
  io::Json doc{{"command", opt.kind}, {"log", opt.log}};
  io::Json& params = doc["parameters"] = io::Json::object();
  for (const auto& p : r.parameters) {
    params[p.name] = {{"value", p.estimate.value}, {"std_error", p.estimate.std_error}, {"unit", p.unit}};
  }
  io::Json& fits = doc["fits"] = io::Json::object();
  for (const auto& f : r.residuals) {
    fits[f.name] = {{"residual_rms", f.stats.residual_rms}, {"unit", f.unit}, {"count", f.stats.count},
                    {"outliers", f.stats.outliers}, {"condition_number", f.stats.condition_number}};
  }
  doc["warnings"] = r.warnings;
  doc["notes"] = r.notes;
  doc["blocking_warnings"] = r.blocking;
  doc["base_vehicle"] = opt.vehicle.empty() ? std::string("built-in paper quadrotor") : opt.vehicle;
  if (r.kind == "hover") doc["ground_effect_fitted"] = !r.fits.hover_thrust.has_value();
  const auto optional = [](const std::optional<ident::Estimate>& e) { return e ? estimateJson(*e) : io::Json(); };
  if (r.fits.mixing) {
    io::Json& bands = doc["height_bands"] = io::Json::array();
    for (const auto& b : r.fits.mixing->bands) {
      bands.push_back({{"h_min_m", b.h_min_m}, {"h_max_m", b.h_max_m}, {"h_mean_m", b.h_mean_m},
                       {"count", b.count}, {"k_T", optional(b.k_T_N_per_rpm2)},
                       {"k_TX", optional(b.k_TX_N_per_rpm2)}, {"k_TY", optional(b.k_TY_N_per_rpm2)},
                       {"k_I", optional(b.k_I_Nm_per_rpm2)}});
    }
  }
  for (const auto& t : r.tables) {
    io::Json values = io::Json::array();
    io::Json errors = io::Json::array();
    for (const auto& e : t.curve.values) values.push_back(e.value), errors.push_back(e.std_error);
    doc["tables"][t.section] = {{"heights_m", t.curve.heights_m}, {t.values_key, values},
                                {"std_error", errors}, {"samples", t.curve.samples}};
  }
  if (r.fits.drag) {
    io::Json& table = doc["drag_table"] = io::Json::array();
    for (const auto& b : r.fits.drag->bands) {
      table.push_back({{"h_m", b.h_mean_m}, {"d_x_N_per_mps", b.d_x_N_per_mps.value},
                       {"d_x_std_error", b.d_x_N_per_mps.std_error}, {"d_y_N_per_mps", b.d_y_N_per_mps.value},
                       {"d_y_std_error", b.d_y_N_per_mps.std_error}});
    }
  }
  if (const auto& t = r.fits.correlations) {
    io::Json rows = io::Json::array();
    for (Eigen::Index i = 0; i < t->r.rows(); ++i) {
      io::Json row = io::Json::array();
      for (Eigen::Index j = 0; j < t->r.cols(); ++j) row.push_back(t->r(i, j));
      rows.push_back(std::move(row));
    }
    doc["correlations"] = {{"rows", t->row_names}, {"columns", t->column_names}, {"r", rows},
                           {"samples", t->samples}};
  }
  doc["provenance"] = io::provenanceJson({commandLine(), {}, opt.vehicle.empty()
                                                              ? std::vector<std::string>{opt.log}
                                                              : std::vector<std::string>{opt.log, opt.vehicle}});
  return doc;
}

int runIdentify(const IdentifyOptions& opt) {
  if (!opt.out.empty() && opt.kind == "correlations") {
    throw UsageError("--out: `identify correlations` fits no vehicle-file keys");
  }
  // Every output checked before the log is read (docs/reliability.md).
  io::OutputChecks files;
  files.input("LOG", opt.log);
  files.input("--vehicle", opt.vehicle);
  files.input("--map", opt.map);
  files.output("--out", opt.out, false);
  files.output("--json", opt.json);
  files.directory("--report", opt.report);
  files.check();
  (void)columnDefinitions(opt);  // a bad --column or --const is named before the log is read
  if (!opt.map.empty() && opt.vehicle.empty() && opt.mass_kg == 0.0) {
    throw UsageError("--map: a flight fit on an autopilot log needs the vehicle's mass: --mass-kg M or --vehicle FILE "
                     "(the built-in paper quadrotor's mass is not taken for another vehicle)");
  }
  if (opt.rotor_speed != "auto" && opt.map.empty()) {
    throw UsageError("--rotor-speed: chooses between a log map's rotor_speed and throttle channels; give --map");
  }
  if (opt.fade && opt.vehicle.empty()) {
    throw UsageError("--fade: the fade is fitted against the vehicle's F_G(h): --vehicle FILE (the built-in paper "
                     "quadrotor's curve is not taken for another vehicle)");
  }
  if (opt.rotor_speed == "throttle" && opt.vehicle.empty()) {
    throw UsageError("--rotor-speed throttle: rotor speeds from throttles need the vehicle's throttle curve: --vehicle "
                     "FILE (the built-in paper quadrotor's curve is not taken for another vehicle)");
  }
  if (opt.kind == "flight" && opt.vehicle.empty() && opt.mass_kg == 0.0) {
    throw UsageError("identify flight: a flight fit needs the vehicle's mass: --vehicle FILE or --mass-kg M (the "
                     "built-in paper quadrotor's 1.696 kg is not taken for another vehicle)");
  }
  model::VehicleParams base = opt.vehicle.empty() ? io::builtinVehicle() : io::loadVehicleFile(opt.vehicle);
  if (opt.mass_kg > 0.0) base.mass_kg = opt.mass_kg;
  if (opt.vehicle.empty()) {
    // Said, not silent (issue 11): the priors of a fit without --vehicle are another vehicle's.
    std::cerr << "geaware: note: no --vehicle: the priors (b, propeller radius, k_T of the observer, the curves "
                 "compared) and the file --out merges into are the built-in paper quadrotor's ("
              << base.name << (opt.mass_kg > 0.0 ? "; the mass from --mass-kg" : ", its mass too") << ")\n";
  }
  ident::IdentifyResult r = identify(opt, base);
  // Human text on stdout, unless stdout carries the JSON.
  (opt.json == "-" ? std::cerr : std::cout) << ident::resultText(r);
  for (const auto& w : r.warnings) std::cerr << "geaware: warning: " << w << "\n";
  for (const auto& w : r.blocking) std::cerr << "geaware: warning: " << w << "\n";
  if (!opt.out.empty() && !r.blocking.empty() && !opt.accept_warnings) {
    throw std::runtime_error("--out " + opt.out + " not written: " + std::to_string(r.blocking.size()) +
                             " fitted value(s) outside their physical range, at a bound or not determined by "
                             "the data (warnings above); "
                             "--accept-warnings writes it anyway");
  }
  if (!opt.out.empty()) {
    r.update.provenance = std::filesystem::path(opt.log).filename().string();
    const auto merged = opt.vehicle.empty()
                            ? io::writeVehicleFile(io::builtinVehicleYaml(), "built-in vehicle", opt.out, r.update)
                            : io::writeVehicleFile(opt.vehicle, opt.out, r.update);
    for (const auto& n : merged.notes) std::cerr << "geaware: note: " << opt.out << ": " << n << "\n";
  }
  if (!opt.json.empty()) io::writeJson(opt.json, toJson(r, opt));
  if (!opt.report.empty()) {
    (void)experiments::writeIdentifyReport(
        r, opt.report, "geaware identify " + opt.kind + ": " + std::filesystem::path(opt.log).filename().string(),
        commandLine());
  }
  return 0;
}

}  // namespace

ident::FlightLog readFlightInput(const std::string& log, const std::string& map, const std::vector<std::string>& columns,
                                 const std::vector<std::string>& constants, const model::VehicleParams& base,
                                 const std::string& vehicle_file) {
  IdentifyOptions opt;
  opt.kind = "flight";
  opt.log = log;
  opt.map = map;
  opt.vehicle = vehicle_file;
  opt.columns = columns;
  opt.constants = constants;
  std::vector<std::string> notes;
  ident::FlightLog out = readFlight(opt, base, notes);
  for (const auto& n : notes) std::cerr << "geaware: note: " << log << ": " << n << "\n";
  return out;
}

Runner addIdentifyCommand(CLI::App& app) {
  auto opts = std::make_shared<IdentifyOptions>();
  auto* cmd = app.add_subcommand("identify", "Fit vehicle parameters from rig and flight logs");
  cmd->require_subcommand(1);
  const std::vector<std::pair<std::string, std::string>> kinds = {
      {"rotor", "k_T, k_I, J_R and the throttle curve from a single-rotor stand log"},
      {"platform", "k_T, F_G (g1, g2), k_TX, k_TY, k_I and the leveling torque from a quadrotor platform log"},
      {"flight", "the drag table D(h) from a flight log, or F_G from a hover descent (--hover)"},
      {"correlations", "the Spearman rank-correlation table of a quadrotor platform log"}};
  for (const auto& [name, help] : kinds) {
    auto* sub = cmd->add_subcommand(name, help);
    sub->add_option("log", opts->log,
                    "the log: CSV, or a .mat, ULog, DataFlash or Crazyflie uSD log whose fields carry the column names "
                    "or are defined by --column (docs/identification.md)")
        ->required()
        ->check(CLI::ExistingFile);
    addVehicleOption(sub, opts->vehicle,
                     "base vehicle file: b, m and the priors the fits need, and the file --out "
                     "merges into (default: the built-in paper quadrotor)");
    sub->add_option("--out", opts->out, "write the base vehicle file with the fitted keys merged in");
    sub->add_option("--json", opts->json,
                    "write every parameter, standard error and residual RMS as JSON ('-': stdout, the text "
                    "then goes to stderr)");
    sub->add_option("--report", opts->report, "write an HTML report (parameters, residuals, fit plots) to DIR");
    sub->add_option("--column", opts->columns,
                    "a column from the log's fields, NAME=EXPR with units: fz_N=Fz, h_m=z[mm], "
                    "thrust_N=Thrust[kgf], n1_rpm=rpm1*2/14 (docs/identification.md, \"Columns from expressions\"); "
                    "repeatable");
    sub->add_option("--const", opts->constants,
                    "a column the log does not have, NAME=VALUE in the column's unit or with one: tilt_deg=0, "
                    "h_m=120[mm]; repeatable");
    if (name != "correlations") {
      sub->add_flag("--accept-warnings", opts->accept_warnings,
                    "write --out even when a fitted value is outside its physical range (a negative drag band, "
                    "left out of the table; k_T, g1 or g2 <= 0) or ended at a bound of its fit");
    }
    sub->add_option("--loss", opts->loss, "robust loss")->check(CLI::IsMember({"huber", "cauchy", "none"}))->capture_default_str();
    if (name == "rotor") {
      sub->add_option("--voltage-column", opts->voltage_column,
                      "the log's battery-voltage column [V]: fit the throttle curve's voltage dependence "
                      "n ∝ (V/V_ref)^p (throttle_curve.reference_voltage_V, voltage_exponent; "
                      "docs/vehicle-file.md)");
      sub->add_option("--reference-voltage", opts->reference_voltage_V,
                      "with --voltage-column: the voltage the fitted curve holds at (default: the log's "
                      "median voltage) [V]")
          ->check(positive());
    }
    if (name == "platform") {
      sub->add_option("--tilt-limit", opts->tilt_limit_deg, "largest board tilt used for the leveling torque [deg]")
          ->check(finiteIn(0.0, 90.0, true))
          ->capture_default_str();
      sub->add_option("--ground-effect", opts->ground_effect,
                      "form of F_G and M_G: 'paper' (g2/(h² + g1), scale·h/(h² + g3·h + g4)²) or 'table' "
                      "(values at knot heights, for curves the closed forms do not follow)")
          ->check(CLI::IsMember({"paper", "table"}))
          ->capture_default_str();
      sub->add_option("--table-top", opts->table_top_m,
                      "table: F_G knots at the logged heights up to this one; level samples above it follow the "
                      "1/h² tail and fix k_T [m]")
          ->check(positive())
          ->capture_default_str();
      sub->add_option("--table-heights", opts->table_heights,
                      "table: explicit knot heights FROM:TO:STEP for both curves [m] (instead of the logged heights)");
      sub->add_flag("--k-T-only", opts->k_T_only,
                    "fit k_T alone from every level sample as one height band, F_G taken as 0 and not fitted "
                    "(a stand at one height, or out of ground effect)");
      sub->add_option("--std-column", opts->std_column,
                      "rows are means (a table of mean ± std per height): the column of fz_N's standard deviation "
                      "[N]; each row is weighted 1/σ², σ = std/√count");
      sub->add_option("--count-column", opts->count_column,
                      "rows are means: the column of the samples behind each row (default: 1 each); the height "
                      "bands and sample thresholds count these samples");
    }
    if (name == "platform" || name == "flight") {
      sub->add_option("--height-bands", opts->height_bands, "number of height bands")->check(wholeIn(1, 100))->capture_default_str();
    }
    if (name == "flight") {
      auto* hover = sub->add_flag("--hover", opts->hover, "the log is a hover descent: fit F_G (eq. 10)");
      sub->add_flag("--fade", opts->fade,
                    "the log flies near the ground at two or more speeds: fit the ground effect's forward-flight "
                    "fade, ground_effect.forward_fade.induced_velocity_mps, against --vehicle's F_G(h)")
          ->excludes(hover);
      sub->add_option("--map", opts->map,
                      "read an autopilot log (PX4 .ulg, ArduPilot .bin, Crazyflie uSD, MATLAB .mat, CSV export) through a log map: a built-in "
                      "name (px4, ardupilot, crazyflie) or a map file (docs/identification.md, \"Mapping a log\")");
      sub->add_option("--mass-kg", opts->mass_kg, "the vehicle's mass [kg] (instead of the base vehicle's)")
          ->check(finiteIn(0.0, 1000.0, true));
      sub->add_option("--rotor-speed", opts->rotor_speed,
                      "with --map: the rotor speeds from the log's rotor_speed channel (rpm), from its throttle "
                      "channel through the --vehicle file's throttle curve and the battery voltage (throttle: "
                      "vehicles without rotor-speed telemetry), or auto: rpm when the log has it")
          ->check(CLI::IsMember({"auto", "rpm", "throttle"}))
          ->capture_default_str();
    }
    sub->callback([opts, name = name] { opts->kind = name; });
  }
  return [opts] { return runIdentify(*opts); };
}

}  // namespace geaware::cli
