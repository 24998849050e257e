// SPDX-License-Identifier: BSD-3-Clause
// `geaware rig platform|rotor|calibrate`: the virtual test rigs (sim/rigs.hpp) writing CSV
// logs like the paper's rigs, and the calibration of the truth aerodynamics against the paper's
// measurements (docs/paper-facts.md).
// Thin: parse, call experiments/rig_runs.hpp, write the rows, the JSON and the pages.

#include "commands.hpp"
#include "numbers.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/experiments/rig_runs.hpp"
#include "geaware/io/csv_writer.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/provenance.hpp"
#include "geaware/io/range.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/io/vehicle_file.hpp"

namespace geaware::cli {
namespace {

struct RigOptions {
  std::string truth;
  std::string vehicle;  ///< the replaced --vehicle (an error saying so)
  std::string out;
  std::string report;
  std::uint64_t seed = 1;
  bool png = false;
  // platform
  std::string heights;
  std::string tilts = "0";
  std::string rpm;
  std::string rpm_diff;
  std::vector<std::string> diff_axes{"roll", "pitch", "yaw"};
  int samples = 5;
  double force_noise_N = sim::PlatformParams{}.force_noise_N;
  double torque_noise_Nm = sim::PlatformParams{}.torque_noise_Nm;
  // rotor stand
  std::string throttle = "0:1:0.05";
  double hold_s = sim::RotorStandParams{}.hold_s;
  double sample_period_s = sim::RotorStandParams{}.sample_period_s;
  // calibrate
  std::string json;
};

/// The world the rigs run on: --truth, or the ideal world of the built-in vehicle. Every output
/// is checked here, before any sweep (docs/reliability.md).
sim::World loadWorld(const RigOptions& o) {
  if (!o.vehicle.empty()) {
    throw UsageError("rig: --vehicle is now --truth FILE (a vehicle file is a valid truth file: "
                     "its ideal world; docs/truth-file.md)");
  }
  sim::World world = o.truth.empty() ? sim::idealWorld(io::builtinVehicle(), "<built-in paper_quad>")
                                     : io::resolveTruth(o.truth, {});
  io::OutputChecks files;
  files.input("--truth", truthInputFile(o.truth));
  files.output("--out", o.out, false);
  files.output("--json", o.json);
  files.directory("--report", o.report);
  files.check();
  return world;
}

/// Progress on stderr for long sweeps: at most about twice a second, only when it takes a while.
class Progress {
 public:
  explicit Progress(std::string what) : what_(std::move(what)), last_(Clock::now()) {}
  void operator()(std::size_t done, std::size_t total) {
    const auto now = Clock::now();
    if (done != total && now - last_ < std::chrono::milliseconds(500)) return;
    if (done == total && !shown_) return;  // short sweeps stay quiet
    last_ = now;
    shown_ = true;
    std::cerr << fmt::format("\r{}: {}/{} setpoints ({:.0f} %)", what_, done, total,
                             100.0 * static_cast<double>(done) / static_cast<double>(total))
              << (done == total ? "\n" : "") << std::flush;
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_;
  Clock::time_point last_;
  bool shown_ = false;
};

void writePage(const report::Page& page, const std::string& dir, const std::string& stem, bool png,
               int png_height_px) {
  for (const auto& f : experiments::writeRigPage(page, dir, stem, png, png_height_px)) {
    std::cerr << "geaware: wrote " << f.string() << "\n";
  }
}

std::string producedBy() { return "Produced by: " + commandLine(); }

// ---------------------------------------------------------------------------------------------

int runPlatform(const RigOptions& o) {
  const sim::World world = loadWorld(o);
  experiments::PlatformRigRun run;
  run.sweep.heights_m = io::parseRange(o.heights, "--heights").values();
  run.sweep.tilts_deg = io::parseRange(o.tilts, "--tilts-deg").values();
  run.sweep.rpm = io::parseRange(o.rpm, "--rpm").values();
  if (!o.rpm_diff.empty()) run.sweep.rpm_diffs = io::parseRange(o.rpm_diff, "--rpm-diff").values();
  run.sweep.diff_axes.clear();
  for (const auto& a : o.diff_axes) {
    run.sweep.diff_axes.push_back(a == "roll"    ? sim::DiffAxis::kRoll
                                  : a == "pitch" ? sim::DiffAxis::kPitch
                                                 : sim::DiffAxis::kYaw);
  }
  run.params.samples_per_setpoint = o.samples;
  run.params.force_noise_N = o.force_noise_N;
  run.params.torque_noise_Nm = o.torque_noise_Nm;
  run.seed = o.seed;
  run.collect_means = !o.report.empty();
  experiments::checkPlatformRigRun(run);

  io::CsvWriter csv(o.out, {"t_s", "h_m", "tilt_deg", "n1_rpm", "n2_rpm", "n3_rpm", "n4_rpm", "fx_N", "fy_N",
                            "fz_N", "tx_Nm", "ty_Nm", "tz_Nm"});
  Progress progress("rig platform");
  const auto result = experiments::runPlatformRig(
      world.truth, run,
      [&](const sim::PlatformRow& r) {
        csv.row({r.t_s, r.h_m, r.tilt_deg, r.n_rpm[0], r.n_rpm[1], r.n_rpm[2], r.n_rpm[3], r.force_B.x(),
                 r.force_B.y(), r.force_B.z(), r.torque_B.x(), r.torque_B.y(), r.torque_B.z()});
      },
      [&progress](std::size_t done, std::size_t total) { progress(done, total); });
  csv.close();
  std::cerr << fmt::format("geaware: wrote {} rows to {}\n", result.rows, o.out);
  if (!o.report.empty()) {
    writePage(experiments::platformRigPage(result.means, producedBy()), o.report, "rig-platform", o.png, 1100);
  }
  return 0;
}

int runRotor(const RigOptions& o) {
  const sim::World world = loadWorld(o);
  sim::RotorStandParams sp;
  sp.motor_time_constant_s = world.truth.motor.time_constant_s;  // the world's motor, not a default
  sp.hold_s = o.hold_s;
  sp.sample_period_s = o.sample_period_s;
  const std::vector<double> throttles = io::parseRange(o.throttle, "--throttle").values();
  io::CsvWriter csv(o.out, {"t_s", "throttle", "rpm", "thrust_N", "torque_Nm"});
  const auto result = experiments::runRotorRig(
      experiments::rotorStandVehicle(world.vehicle, world.truth), sp, throttles, o.seed,
      [&](const sim::RotorStandRow& r) { csv.row({r.t_s, r.throttle, r.rpm, r.thrust_N, r.torque_Nm}); },
      !o.report.empty());
  csv.close();
  std::cerr << fmt::format("geaware: wrote {} rows to {}\n", result.rows, o.out);
  if (!o.report.empty()) {
    writePage(experiments::rotorRigPage(result.kept, producedBy()), o.report, "rig-rotor", o.png, 1600);
  }
  return 0;
}

int runCalibrate(const RigOptions& o) {
  const sim::World world = loadWorld(o);
  const sim::CalibrationResult res = sim::calibrate(world.vehicle, world.truth.aero);
  // Human text on stdout, unless stdout carries the JSON.
  const std::string differs = experiments::differsFromThePapersRotors(world.vehicle);
  (o.json == "-" ? std::cerr : std::cout)
      << experiments::calibrationText(res, world.vehicle.name, world.source, differs);
  if (!o.json.empty()) {
    io::Json doc{{"all_pass", res.allPass()}, {"checks", io::Json::array()}};
    // Another vehicle's rotors: the paper's targets are information, not a test.
    doc["papers_rotors"] = differs.empty();
    if (!differs.empty()) doc["all_pass"] = nullptr;
    for (const auto& c : res.checks) {
      doc["checks"].push_back({{"name", c.name}, {"unit", c.unit}, {"paper", c.paper}, {"ours", c.ours},
                               {"tolerance", c.tolerance}, {"pass", c.pass}});
    }
    const std::string truth_file = truthInputFile(o.truth);
    doc["provenance"] = io::provenanceJson(
        {commandLine(), {}, truth_file.empty() ? std::vector<std::string>{} : std::vector<std::string>{truth_file}});
    io::writeJson(o.json, doc);
  }
  if (!o.report.empty()) {
    writePage(experiments::calibrationPage(res, producedBy()), o.report, "rig-calibration", o.png, 2500);
  }
  std::size_t failed = 0;
  for (const auto& c : res.checks) failed += c.pass ? 0 : 1;
  if (failed > 0 && differs.empty()) {
    throw std::runtime_error(fmt::format("{} calibration target(s) failed", failed));
  }
  return 0;
}

}  // namespace

Runner addRigCommand(CLI::App& app) {
  auto opts = std::make_shared<RigOptions>();
  auto* rig = app.add_subcommand("rig", "The paper's virtual test rigs on the truth simulator");
  rig->require_subcommand(1);
  auto runner = std::make_shared<Runner>();

  const auto common = [&opts](CLI::App* cmd) {
    addTruthOption(cmd, opts->truth,
                   "the world whose rotors the rig holds: a truth file (docs/truth-file.md; any "
                   "vehicle file is one: its ideal world) or a built-in world (ideal, as_built) (default: the "
                   "ideal world of the built-in paper quadrotor)");
    // Replaced by --truth: kept, hidden, to say so.
    cmd->add_option("--vehicle", opts->vehicle)->group("");
  };

  auto* platform = rig->add_subcommand(
      "platform", "Quadrotor force/torque platform sweep over height × tilt × rpm");
  common(platform);
  platform
      ->add_option("--heights", opts->heights,
                   "rotor-plane heights above the board FROM:TO:STEP [m]")
      ->required();
  platform
      ->add_option("--tilts-deg", opts->tilts,
                   "board tilts about the vehicle's y axis FROM:TO:STEP [deg]")
      ->capture_default_str();
  platform->add_option("--rpm", opts->rpm, "mean rotor speeds FROM:TO:STEP [rpm]")->required();
  platform->add_option("--rpm-diff", opts->rpm_diff,
                       "rotor-speed differences FROM:TO:STEP [rpm] along each --diff-axes mixer "
                       "row (mixing experiments)");
  platform->add_option("--diff-axes", opts->diff_axes, "axes excited by --rpm-diff")
      ->check(CLI::IsMember({"roll", "pitch", "yaw"}))
      ->delimiter(',')
      ->capture_default_str();
  platform->add_option("--samples", opts->samples, "samples per setpoint")
      ->check(wholeIn(1, 1000000))
      ->capture_default_str();
  platform->add_option("--force-noise", opts->force_noise_N, "force sensor noise std [N]")
      ->check(nonNegative())
      ->capture_default_str();
  platform->add_option("--torque-noise", opts->torque_noise_Nm, "torque sensor noise std [N·m]")
      ->check(nonNegative())
      ->capture_default_str();
  platform->add_option("--seed", opts->seed, "noise seed (same seed: identical file)")
      ->check(seed())
      ->capture_default_str();
  platform->add_option("--out", opts->out, "CSV file to write (overwritten)")->required();
  platform->add_option("--report", opts->report, "also write an HTML page of the sweep into DIR");
  platform->add_flag("--png", opts->png,
                     "with --report: also export the page as PNG (headless Chromium)");
  platform->callback([opts, runner] { *runner = [opts] { return runPlatform(*opts); }; });

  auto* rotor = rig->add_subcommand(
      "rotor", "Single-rotor stand: thrust and torque against throttle and rotor speed");
  common(rotor);
  rotor->add_option("--throttle", opts->throttle, "throttle steps FROM:TO:STEP in [0, 1]")
      ->capture_default_str();
  rotor->add_option("--hold", opts->hold_s, "time each throttle is held [s]")
      ->check(positive())
      ->capture_default_str();
  rotor->add_option("--sample-period", opts->sample_period_s, "time between samples [s]")
      ->check(positive())
      ->capture_default_str();
  rotor->add_option("--seed", opts->seed, "noise seed")->capture_default_str()->check(seed());
  rotor->add_option("--out", opts->out, "CSV file to write (overwritten)")->required();
  rotor->add_option("--report", opts->report, "also write an HTML page into DIR");
  rotor->add_flag("--png", opts->png,
                  "with --report: also export the page as PNG (headless Chromium)");
  rotor->callback([opts, runner] { *runner = [opts] { return runRotor(*opts); }; });

  auto* cal = rig->add_subcommand("calibrate",
                                  "Check the truth aerodynamics against the paper's measurements");
  common(cal);
  cal->add_option("--report", opts->report,
                  "also write the comparison page (table and figures) into DIR");
  cal->add_option("--json", opts->json,
                  "also write the checks as JSON to FILE ('-': stdout, the table then goes to stderr)");
  cal->add_flag("--png", opts->png,
                "with --report: also export the page as PNG (headless Chromium)");
  cal->callback([opts, runner] { *runner = [opts] { return runCalibrate(*opts); }; });

  return [runner] {
    if (!*runner) throw std::logic_error("geaware rig: no subcommand ran");
    return (*runner)();
  };
}

}  // namespace geaware::cli
