// `geaware fly`: parse the options into an experiments::FlightScenario, fly it, print the
// Table I metrics. Thin: the loop, the metrics and the log live in the experiments layer.

#include "fly_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_log.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/experiments/scenario_file.hpp"
#include "geaware/io/json.hpp"
#include "geaware/model/units.hpp"
#include "geaware/neural/residual_network.hpp"
#include "geaware/neural/weights_file.hpp"
#include "geaware/report/page.hpp"
#include "geaware/traj/hover_descent.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::cli {
namespace {

using io::jsonString;

struct FlyOptions {
  std::string scenario;
  std::string vehicle;
  std::string trajectory;
  double height_m = std::nan("");
  double speed_mps = std::nan("");
  double extent_x_m = 1.5;
  double extent_y_m = 0.8;
  int laps = 1;
  double from_height_m = 1.5;
  std::string controller;
  std::uint64_t seed = 1;
  std::string out;
  std::string json;
  bool no_turbulence = false;
  std::string report;
  std::string neural_weights;
  double start_hover_s = 1.0;
  double yaw_rate_gain = std::nan("");
  std::vector<std::string> ablate;
};

model::VehicleParams loadVehicle(const std::string& path) {
  return path.empty() ? io::builtinVehicle() : io::loadVehicleFile(path);
}

std::string jsonNumber(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

/// Parses "ACC:TORQUE" into the controller's two switches; false when malformed.
bool parseController(const std::string& text, control::ControllerParams& p) {
  const auto colon = text.find(':');
  return colon != std::string::npos && control::parse(text.substr(0, colon), p.acceleration) &&
         control::parse(text.substr(colon + 1), p.torque);
}

/// CLI11 check of --controller (a malformed value is a usage error, exit status 2).
const CLI::Validator kControllerSpec(
    [](std::string& text) -> std::string {
      control::ControllerParams p;
      if (parseController(text, p)) return {};
      return "--controller '" + text +
             "': expected ACC:TORQUE with ACC one of none, indi, neural, model and TORQUE one of "
             "none, model, indi, model_indi (e.g. model:model_indi)";
    },
    "ACC:TORQUE");

std::shared_ptr<const traj::Trajectory> makeTrajectory(const FlyOptions& o) {
  if (o.trajectory == "lemniscate") {
    traj::LemniscateParams p;
    p.half_extent_x_m = o.extent_x_m;
    p.half_extent_y_m = o.extent_y_m;
    p.height_m = o.height_m;
    p.peak_speed_mps = o.speed_mps;
    p.laps = o.laps;
    return std::make_shared<traj::Lemniscate>(p);
  }
  traj::HoverDescentParams p;
  p.from_height_m = o.from_height_m;
  p.to_height_m = o.height_m;
  if (std::isfinite(o.speed_mps)) p.descent_rate_mps = o.speed_mps;
  return std::make_shared<traj::HoverDescent>(p);
}

std::string describeTrajectory(const FlyOptions& o) {
  if (o.trajectory == "lemniscate") {
    return fmt::format("lemniscate ±{} m × ±{} m at {} m, {} m/s peak, {} lap{}", o.extent_x_m,
                       o.extent_y_m, o.height_m, o.speed_mps, o.laps, o.laps == 1 ? "" : "s");
  }
  return fmt::format(
      "hover descent {} m → {} m at {} m/s", o.from_height_m, o.height_m,
      std::isfinite(o.speed_mps) ? o.speed_mps : traj::HoverDescentParams{}.descent_rate_mps);
}

/// Several observers behind one.
class FanOut final : public experiments::FlightObserver {
 public:
  void add(experiments::FlightObserver* o) { observers_.push_back(o); }
  [[nodiscard]] bool empty() const { return observers_.empty(); }
  void onTick(const experiments::FlightTick& t) noexcept override {
    for (auto* o : observers_) o->onTick(t);
  }
  void finish(const experiments::FlightResult& r) override {
    for (auto* o : observers_) o->finish(r);
  }

 private:
  std::vector<experiments::FlightObserver*> observers_;
};

/// Collects the series of the HTML report, one point per control tick (≈ 200 per simulated
/// second; a 20 s flight is a few thousand points per series). Memory is reserved up front.
class ReportCollector final : public experiments::FlightObserver {
 public:
  explicit ReportCollector(std::size_t ticks) {
    for (auto* v : all()) v->reserve(ticks);
  }
  void onTick(const experiments::FlightTick& k) noexcept override {
    if (t.size() == t.capacity()) return;  // never reallocate inside the loop
    t.push_back(k.t_s);
    ref_x.push_back(k.input.reference.p_W.x());
    ref_y.push_back(k.input.reference.p_W.y());
    ref_z.push_back(k.input.reference.p_W.z());
    true_x.push_back(k.truth.p_W.x());
    true_y.push_back(k.truth.p_W.y());
    true_z.push_back(k.truth.p_W.z());
    err_xy.push_back((k.input.reference.p_W - k.truth.p_W).head<2>().norm() * 100.0);
    err_z.push_back((k.input.reference.p_W.z() - k.truth.p_W.z()) * 100.0);
    h_true.push_back(k.true_height_m);
    h_meas.push_back(k.input.height_valid ? k.input.height_m : std::nan(""));
    att_err.push_back(k.controller_active ? k.attitude_error_rad / model::kDegToRad : std::nan(""));
    for (int i = 0; i < 4; ++i) {
      n_true[static_cast<std::size_t>(i)].push_back(k.truth.n_rpm[static_cast<std::size_t>(i)]);
    }
    for (int i = 0; i < 3; ++i) {
      tau_des[static_cast<std::size_t>(i)].push_back(k.output.tau_des_B(i));
      tau_hat[static_cast<std::size_t>(i)].push_back(k.output.tau_hat_B(i));
    }
  }

  std::vector<double> t, ref_x, ref_y, ref_z, true_x, true_y, true_z, err_xy, err_z, h_true, h_meas,
      att_err;
  std::array<std::vector<double>, 4> n_true;
  std::array<std::vector<double>, 3> tau_des, tau_hat;

 private:
  std::vector<std::vector<double>*> all() {
    std::vector<std::vector<double>*> v{&t,      &ref_x,  &ref_y, &ref_z,  &true_x, &true_y,
                                        &true_z, &err_xy, &err_z, &h_true, &h_meas, &att_err};
    for (auto& s : n_true) v.push_back(&s);
    for (auto& s : tau_des) v.push_back(&s);
    for (auto& s : tau_hat) v.push_back(&s);
    return v;
  }
};

void writeReport(const std::filesystem::path& dir, const ReportCollector& c,
                 const experiments::FlightResult& r, const std::string& command,
                 const std::string& title) {
  if (std::filesystem::exists(dir) && !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("--report " + dir.string() + ": exists and is not a directory");
  }
  std::filesystem::create_directories(dir);
  report::Page page("Closed-loop flight: " + title);
  page.addText("Produced by: " + command);
  const auto& m = r.tracking;
  page.addTable(
      {"Tracking (reference vs true position, cm)",
       {"RMSE XOY", "RMSE Z", "RMSE all", "max ‖E_P‖", "σ‖E_P‖", "crash"},
       {{fmt::format("{:.2f}", m.rmse_xy_m * 100), fmt::format("{:.2f}", m.rmse_z_m * 100),
         fmt::format("{:.2f}", m.rmse_all_m * 100), fmt::format("{:.2f}", m.max_m * 100),
         fmt::format("{:.2f}", m.std_m * 100),
         r.crash ? r.crash_description : std::string("none")}}});
  page.addPlot({"Trajectory seen from above",
                "x [m]",
                "y [m]",
                {{"reference", c.ref_x, c.ref_y, "lines", "dash"},
                 {"flown (truth)", c.true_x, c.true_y, "lines", ""}}});
  page.addPlot({"Height over time",
                "t [s]",
                "z [m]",
                {{"reference", c.t, c.ref_z, "lines", "dash"},
                 {"flown (truth)", c.t, c.true_z, "lines", ""},
                 {"ranger height", c.t, c.h_meas, "lines", "dot"}}});
  page.addPlot({"Position error over time",
                "t [s]",
                "error [cm]",
                {{"‖E_xy‖", c.t, c.err_xy, "lines", ""}, {"E_z", c.t, c.err_z, "lines", ""}}});
  page.addPlot({"Attitude error (desired vs true) over time",
                "t [s]",
                "angle [deg]",
                {{"angle error", c.t, c.att_err, "lines", ""}}});
  report::Plot rotors{"Rotor speeds (truth)", "t [s]", "n [rpm]", {}};
  for (std::size_t i = 0; i < 4; ++i) {
    rotors.series.push_back({fmt::format("rotor {}", i + 1), c.t, c.n_true[i], "lines", ""});
  }
  page.addPlot(std::move(rotors));
  report::Plot torques{
      "Body torques: command τ_des and rotor estimate τ̂_B", "t [s]", "τ [N·m]", {}};
  const char* axis[3] = {"x", "y", "z"};
  for (std::size_t i = 0; i < 3; ++i) {
    torques.series.push_back({fmt::format("τ_des,{}", axis[i]), c.t, c.tau_des[i], "lines", ""});
    torques.series.push_back({fmt::format("τ̂_B,{}", axis[i]), c.t, c.tau_hat[i], "lines", "dot"});
  }
  page.addPlot(std::move(torques));
  const auto html = dir / "flight.html";
  page.write(html);
  std::cerr << "geaware: wrote " << html.string() << "\n";
}

int runFly(const FlyOptions& o, const std::string& command) {
  experiments::FlightScenario s;
  if (!o.scenario.empty()) {
    // The scenario file fixes vehicle, trajectory, controller, terrain, disturbances and seed;
    // the options that would contradict it are refused at parse time.
    s = experiments::loadScenarioFile(o.scenario);
  } else {
    s.vehicle = loadVehicle(o.vehicle);
    if (!parseController(o.controller, s.controller)) {
      throw std::invalid_argument("--controller '" + o.controller + "': expected ACC:TORQUE");
    }
    s.trajectory = makeTrajectory(o);
    s.seed = o.seed;
    s.disturbances.turbulence = !o.no_turbulence;
  }
  if (std::isfinite(o.yaw_rate_gain)) s.controller.k_w_per_s.z() = o.yaw_rate_gain;
  s.start_hover_s = o.start_hover_s;
  for (const auto& a : o.ablate) {
    if (a == "motor_reaction") s.plant.motor_reaction = false;
    if (a == "gyroscopic") s.plant.gyroscopic = false;
  }
  if (s.controller.acceleration == control::AccelerationCompensation::kNeural) {
    if (o.neural_weights.empty()) {
      throw std::invalid_argument(
          "controller neural:" + std::string(control::toString(s.controller.torque)) +
          ": the Neural-Lander baseline needs a trained residual network; pass "
          "--neural-weights FILE (a weight file written by neural::saveWeights — the "
          "`geaware bench` campaign trains one from simulated flights and caches it)");
    }
    s.residual =
        std::make_shared<neural::ResidualNetwork>(neural::loadWeights(o.neural_weights).weights);
  } else if (!o.neural_weights.empty()) {
    throw std::invalid_argument("--neural-weights is only used with --controller neural:…");
  }

  FanOut observers;
  std::unique_ptr<experiments::CsvFlightLog> log;
  if (!o.out.empty()) {
    log = std::make_unique<experiments::CsvFlightLog>(o.out);
    observers.add(log.get());
  }
  std::unique_ptr<ReportCollector> collector;
  if (!o.report.empty()) {
    const double ticks =
        (s.start_hover_s + s.trajectory->duration() + s.settle_s) * s.controller.rate_hz + 2.0;
    collector = std::make_unique<ReportCollector>(static_cast<std::size_t>(ticks));
    observers.add(collector.get());
  }

  const std::string controller_name = std::string(control::toString(s.controller.acceleration)) + ":" +
                                      control::toString(s.controller.torque);
  const std::string title = (o.scenario.empty() ? describeTrajectory(o) : "scenario " + o.scenario) +
                            ", controller " + controller_name;
  const experiments::FlightResult r =
      experiments::runFlight(s, observers.empty() ? nullptr : &observers);

  const auto& m = r.tracking;
  // With --json - the summary goes to stderr, so that stdout is the JSON object alone.
  std::FILE* human = o.json == "-" ? stderr : stdout;
  std::string variations = o.no_turbulence ? ", no turbulence" : "";
  if (std::isfinite(o.yaw_rate_gain)) variations += fmt::format(", K^ω_z = {}/s", o.yaw_rate_gain);
  for (const auto& a : o.ablate) variations += ", truth without " + a;
  fmt::print(human, "{}, seed {}{}\n", title, s.seed, variations);
  fmt::print(
      human,
      "RMSE XOY {:.2f} cm, Z {:.2f} cm, all {:.2f} cm; max ‖E_P‖ {:.2f} cm; σ‖E_P‖ {:.2f} cm "
      "({} samples)\n",
      m.rmse_xy_m * 100, m.rmse_z_m * 100, m.rmse_all_m * 100, m.max_m * 100, m.std_m * 100,
      m.samples);
  if (r.crash) {
    fmt::print(human, "CRASHED: {}\n", r.crash_description);
  } else {
    fmt::print(human, "completed, no crash\n");
  }
  std::string flags;
  for (int b = 0; b < experiments::kControllerFlagBits; ++b) {
    const auto n = r.flag_counts[static_cast<std::size_t>(b)];
    if (n > 0)
      flags +=
          fmt::format("{}{} {}", flags.empty() ? "" : ", ", experiments::controllerFlagName(b), n);
  }
  if (!flags.empty()) fmt::print(human, "controller flags (ticks): {}\n", flags);
  fmt::print(human, "simulated {:.2f} s in {:.3f} s: {:.0f}× real time\n", r.simulated_s, r.wall_s,
             r.real_time_factor);
  if (log) std::cerr << fmt::format("geaware: wrote {} rows to {}\n", log->rows(), o.out);

  if (!o.json.empty()) {
    std::string doc = fmt::format(
        "{{\"rmse_xy_cm\":{},\"rmse_z_cm\":{},\"rmse_all_cm\":{},\"max_cm\":{},\"std_cm\":{},"
        "\"crashed\":{}",
        jsonNumber(m.rmse_xy_m * 100), jsonNumber(m.rmse_z_m * 100), jsonNumber(m.rmse_all_m * 100),
        jsonNumber(m.max_m * 100), jsonNumber(m.std_m * 100), r.crash ? "true" : "false");
    if (r.crash) {
      doc += fmt::format(",\"crash\":{{\"t_s\":{},\"point_m\":[{},{},{}],\"description\":{}}}",
                         jsonNumber(r.crash->t_s), jsonNumber(r.crash->point_W.x()),
                         jsonNumber(r.crash->point_W.y()), jsonNumber(r.crash->point_W.z()),
                         jsonString(r.crash_description));
    } else {
      doc += ",\"crash\":null";
    }
    doc += fmt::format(",\"samples\":{},\"controller\":{},\"seed\":{},\"flags\":{{", m.samples,
                       jsonString(controller_name), s.seed);
    for (int b = 0; b < experiments::kControllerFlagBits; ++b) {
      doc += fmt::format("{}{}:{}", b ? "," : "", jsonString(experiments::controllerFlagName(b)),
                         r.flag_counts[static_cast<std::size_t>(b)]);
    }
    doc += fmt::format("}},\"simulated_s\":{},\"wall_s\":{},\"real_time_factor\":{}}}\n",
                       jsonNumber(r.simulated_s), jsonNumber(r.wall_s),
                       jsonNumber(r.real_time_factor));
    if (o.json == "-") {
      std::cout << doc;
    } else {
      std::ofstream f(o.json);
      if (!(f << doc)) throw std::runtime_error(o.json + ": cannot write JSON output");
    }
  }
  if (collector) writeReport(o.report, *collector, r, command, title);
  return 0;
}

}  // namespace

Runner addFlyCommand(CLI::App& app) {
  auto o = std::make_shared<FlyOptions>();
  auto* cmd = app.add_subcommand(
      "fly", "Fly a trajectory in the simulator in closed loop and report the tracking error");
  cmd->add_option("--vehicle", o->vehicle,
                  "vehicle YAML file (default: the built-in paper quadrotor)")
      ->check(CLI::ExistingFile);
  auto* scenario = cmd->add_option("--scenario", o->scenario,
                                   "flight scenario YAML file (docs/scenario-file.md); replaces "
                                   "--vehicle, --trajectory…, --controller, --seed, --no-turbulence")
                       ->check(CLI::ExistingFile);
  auto* trajectory = cmd->add_option("--trajectory", o->trajectory, "lemniscate or hover-descent")
                         ->check(CLI::IsMember({"lemniscate", "hover-descent"}));
  auto* height = cmd->add_option("--height", o->height_m,
                                 "flight height of the lemniscate / final height of the descent, "
                                 "rotor plane above the ground [m]")
                     ->check(CLI::PositiveNumber);
  cmd->add_option("--speed", o->speed_mps,
                  "lemniscate: peak speed; hover-descent: descent rate (default 0.1) [m/s]")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--extent-x", o->extent_x_m, "lemniscate half extent along x [m]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--extent-y", o->extent_y_m, "lemniscate half extent along y [m]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--laps", o->laps, "lemniscate laps")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--from-height", o->from_height_m, "hover-descent start height [m]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  auto* controller = cmd->add_option("--controller", o->controller,
                                     "ACC:TORQUE, ACC in none|indi|neural|model, TORQUE in "
                                     "none|model|indi|model_indi (the paper's: model:model_indi)")
                         ->check(kControllerSpec);
  cmd->add_option("--yaw-rate-gain", o->yaw_rate_gain,
                  "override K^ω_z, the controller's yaw-rate gain (default: the paper's 16) "
                  "[1/s]; see docs/closed-loop.md on the yaw channel")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", o->seed, "seed of sensors and disturbances")->capture_default_str();
  cmd->add_option("--start-hover", o->start_hover_s,
                  "hover at the first point before the trajectory starts [s]")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", o->out, "CSV log, one row per control tick");
  cmd->add_option("--json", o->json, "write the summary as one JSON object ('-': stdout)");
  cmd->add_flag("--no-turbulence", o->no_turbulence, "switch off the near-ground turbulence");
  cmd->add_option("--ablate", o->ablate,
                  "switch off a physical effect of the truth, for diagnosis only: "
                  "motor_reaction (J_R·ṅ), gyroscopic")
      ->check(CLI::IsMember({"motor_reaction", "gyroscopic"}));
  cmd->add_option("--report", o->report, "write an HTML report (flight.html) into DIR");
  cmd->add_option("--neural-weights", o->neural_weights,
                  "Neural-Lander weight file, for --controller neural:…")
      ->check(CLI::ExistingFile);
  // Either a scenario file or the trajectory options, never both.
  for (auto* opt : {trajectory, height, controller}) scenario->excludes(opt);
  for (const char* name : {"--vehicle", "--speed", "--extent-x", "--extent-y", "--laps",
                           "--from-height", "--seed", "--no-turbulence"}) {
    scenario->excludes(cmd->get_option(name));
  }
  // Combinations CLI11 cannot express: usage errors (exit status 2) at parse time.
  cmd->parse_complete_callback([o]() {
    if (o->scenario.empty() && (o->trajectory.empty() || !std::isfinite(o->height_m) || o->controller.empty())) {
      throw CLI::ValidationError("geaware fly",
                                 "give --scenario FILE, or --trajectory, --height and --controller");
    }
    if (o->trajectory == "lemniscate" && !std::isfinite(o->speed_mps)) {
      throw CLI::ValidationError("--speed",
                                 "--trajectory lemniscate needs --speed V (peak speed) [m/s]");
    }
  });
  return [o, cmd]() {
    std::string command = "geaware fly";
    for (const auto* opt : cmd->get_options()) {
      if (opt->count() == 0 || opt->get_name() == "--help") continue;
      command += " " + opt->get_name();
      for (const auto& v : opt->results()) command += " " + v;
    }
    return runFly(*o, command);
  };
}

}  // namespace geaware::cli
