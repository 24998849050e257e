// `geaware bench`: parse the options into experiments::CampaignOptions, run the campaign, print.
// Thin: the campaign, its text, JSON and report live in the experiments layer.

#include "bench_command.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/experiments/campaign.hpp"
#include "geaware/experiments/campaign_report.hpp"
#include "geaware/io/vehicle_file.hpp"

namespace geaware::cli {
namespace {

struct BenchOptions {
  std::string vehicle;
  int seeds = 5;
  std::uint64_t first_seed = 1;
  std::vector<std::string> only;
  int jobs = 0;
  std::string json;
  std::string report;
  std::string cache = ".geaware-cache";
  bool no_cache = false;
  bool truth_mismatch = false;
  bool no_turbulence = false;
  std::string ground_effect = "paper";  ///< form the calibration identifies F_G and M_G in
  bool check = false;
};

/// Progress on stderr: stage messages on their own lines; the per-flight counter overwrites
/// itself on a terminal and is printed every tenth flight otherwise.
class Progress {
 public:
  Progress() : tty_(::isatty(STDERR_FILENO) == 1) {}
  void operator()(const std::string& m) {
    const bool counter = !m.empty() && m.front() == '[';
    if (counter) {
      if (tty_) {
        std::cerr << "\r\033[K" << m << std::flush;
        pending_ = true;
      } else if (++count_ % 10 == 0 || m.find("CRASH") != std::string::npos) {
        std::cerr << m << "\n";
      }
      return;
    }
    if (pending_) std::cerr << "\n";
    pending_ = false;
    std::cerr << "geaware bench: " << m << "\n";
  }
  void end() {
    if (pending_) std::cerr << "\n";
    pending_ = false;
  }

 private:
  bool tty_;
  bool pending_ = false;
  int count_ = 0;
};

int runBench(const BenchOptions& o, const std::string& command) {
  experiments::CampaignOptions c;
  c.vehicle = o.vehicle.empty() ? io::builtinVehicle() : io::loadVehicleFile(o.vehicle);
  c.seeds = o.seeds;
  c.first_seed = o.first_seed;
  c.jobs = o.jobs;
  if (!o.only.empty()) {
    c.experiments.clear();
    c.hover = false;
    for (const auto& e : o.only) {
      if (e == "hover") {
        c.hover = true;
      } else {
        c.experiments.push_back(std::stoi(e));
      }
    }
  }
  if (!o.no_cache) c.cache_dir = o.cache;
  c.turbulence = !o.no_turbulence;
  c.calibration.tables = o.ground_effect == "table";
  if (o.truth_mismatch) c.mismatch = experiments::defaultTruthMismatch();
  c.collect_series = !o.report.empty();
  auto progress = std::make_shared<Progress>();
  c.progress = [progress](const std::string& m) { (*progress)(m); };

  const experiments::CampaignResult r = experiments::runCampaign(c);
  progress->end();

  std::FILE* human = o.json == "-" ? stderr : stdout;
  fmt::print(human, "{}\n", command);
  if (c.calibration.tables) {
    fmt::print(human, "calibration: F_G and M_G identified as tables (--ground-effect table)\n");
  }
  if (o.truth_mismatch || o.no_turbulence) {
    fmt::print(human, "truth overrides:{}{}\n",
               o.truth_mismatch ? " per-flight mismatch (mass ±1 %, inertia ±10 %, CoG ±2 mm xy "
                                  "±5 mm z, thrust ±2 %)"
                                : "",
               o.no_turbulence ? " no near-ground turbulence" : "");
  }
  fmt::print(human, "{}", experiments::formatCampaign(r));
  std::fflush(human);

  if (!o.json.empty()) {
    const std::string doc = experiments::campaignJson(r);
    if (o.json == "-") {
      std::cout << doc << std::flush;
    } else {
      std::ofstream f(o.json);
      if (!(f << doc)) throw std::runtime_error(o.json + ": cannot write the JSON output");
      std::cerr << "geaware bench: wrote " << o.json << "\n";
    }
  }
  if (!o.report.empty()) {
    const auto html = experiments::writeCampaignReport(r, o.report, command);
    std::cerr << "geaware bench: wrote " << html.string() << "\n";
  }
  if (o.check) {
    for (const auto& chk : r.checks) {
      if (!chk.pass) return 3;
    }
  }
  return 0;
}

}  // namespace

Runner addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand(
      "bench",
      "The paper's experiments: calibrate on the virtual rigs, train the Neural-Lander baseline, "
      "fly Table I and the hover experiment over seeds, compare with the paper");
  cmd->add_option("--vehicle", o->vehicle,
                  "vehicle YAML file (default: the built-in paper quadrotor); the truth is built "
                  "from it, the controller gets the parameters identified on the virtual rigs")
      ->check(CLI::ExistingFile);
  cmd->add_option("--seeds", o->seeds, "flights per experiment and hover curve")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--first-seed", o->first_seed, "seeds are first-seed … first-seed + seeds − 1")
      ->capture_default_str();
  cmd->add_option("--only", o->only, "fly only these: Table I experiments 1–8 and/or 'hover'")
      ->check(CLI::IsMember({"1", "2", "3", "4", "5", "6", "7", "8", "hover"}));
  cmd->add_option("--jobs", o->jobs, "parallel flights (0: one per core); results do not depend on it")
      ->capture_default_str()
      ->check(CLI::Range(0, 256));
  cmd->add_option("--json", o->json, "write the results as JSON ('-': stdout, the summary goes to stderr)");
  cmd->add_option("--report", o->report, "write an HTML report (bench.html) into DIR");
  cmd->add_option("--cache", o->cache, "directory of the cached Neural-Lander weights")
      ->capture_default_str();
  cmd->add_flag("--no-cache", o->no_cache, "always retrain the Neural-Lander network, save nothing");
  cmd->add_flag("--truth-mismatch", o->truth_mismatch,
                "give every flight a seeded truth mismatch the controller does not know (mass ±1 %, "
                "inertia ±10 %, CoG ±2 mm xy ±5 mm z, thrust ±2 %)");
  cmd->add_flag("--no-turbulence", o->no_turbulence, "switch off the truth's near-ground turbulence");
  cmd->add_option("--ground-effect", o->ground_effect,
                  "form in which the calibration identifies F_G and M_G for the controllers: 'paper' (closed "
                  "forms) or 'table' (values at the swept heights)")
      ->check(CLI::IsMember({"paper", "table"}))
      ->capture_default_str();
  cmd->add_flag("--check", o->check, "exit with status 3 when an acceptance check fails");
  return [o, cmd]() {
    std::string command = "geaware bench";
    for (const auto* opt : cmd->get_options()) {
      if (opt->count() == 0 || opt->get_name() == "--help") continue;
      command += " " + opt->get_name();
      for (const auto& v : opt->results()) command += " " + v;
    }
    return runBench(*o, command);
  };
}

}  // namespace geaware::cli
