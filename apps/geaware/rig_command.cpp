// `geaware rig platform|rotor|calibrate`: the virtual test rigs (sim/rigs.hpp) writing CSV
// logs like the paper's rigs, and the calibration of the truth aerodynamics against FACTS.md.

#include "rig_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/io/range.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/report/page.hpp"
#include "geaware/sim/rigs.hpp"

namespace geaware::cli {
namespace {

struct RigOptions {
  std::string vehicle;
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

model::VehicleParams loadVehicle(const std::string& path) {
  return path.empty() ? io::builtinVehicle() : io::loadVehicleFile(path);
}

/// A CSV output file that reports write errors (disk full…) instead of losing rows silently.
class CsvFile {
 public:
  explicit CsvFile(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "w")) {
    if (f_ == nullptr) throw std::runtime_error(path + ": cannot open for writing");
  }
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;
  ~CsvFile() {
    if (f_ != nullptr) std::fclose(f_);
  }
  [[nodiscard]] std::FILE* get() const { return f_; }
  void close() {
    const bool bad = std::ferror(f_) != 0;
    const int rc = std::fclose(f_);
    f_ = nullptr;
    if (bad || rc != 0) throw std::runtime_error(path_ + ": write failed");
  }

 private:
  std::string path_;
  std::FILE* f_;
};

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

std::filesystem::path reportDir(const std::string& dir) {
  const std::filesystem::path p(dir);
  if (std::filesystem::exists(p) && !std::filesystem::is_directory(p)) {
    throw std::runtime_error("--report " + dir + ": exists and is not a directory");
  }
  std::filesystem::create_directories(p);
  return p;
}

void writePage(const report::Page& page, const std::filesystem::path& dir, const std::string& stem,
               bool png, int png_height_px) {
  const auto html = dir / (stem + ".html");
  page.write(html);
  std::cerr << "geaware: wrote " << html.string() << "\n";
  if (png) {
    const auto file = dir / (stem + ".png");
    report::exportPng(html, file, 1200, png_height_px);
    std::cerr << "geaware: wrote " << file.string() << "\n";
  }
}

std::string commandLine(const std::string& what) { return "Produced by: geaware " + what; }

// ---------------------------------------------------------------------------------------------

int runPlatform(const RigOptions& o) {
  const model::VehicleParams vehicle = loadVehicle(o.vehicle);
  sim::PlatformSweep sw;
  sw.heights_m = io::parseRange(o.heights, "--heights").values();
  sw.tilts_deg = io::parseRange(o.tilts, "--tilts-deg").values();
  sw.rpm = io::parseRange(o.rpm, "--rpm").values();
  if (!o.rpm_diff.empty()) sw.rpm_diffs = io::parseRange(o.rpm_diff, "--rpm-diff").values();
  sw.diff_axes.clear();
  for (const auto& a : o.diff_axes) {
    sw.diff_axes.push_back(a == "roll"    ? sim::DiffAxis::kRoll
                           : a == "pitch" ? sim::DiffAxis::kPitch
                                          : sim::DiffAxis::kYaw);
  }
  sim::PlatformParams pp;
  pp.samples_per_setpoint = o.samples;
  pp.force_noise_N = o.force_noise_N;
  pp.torque_noise_Nm = o.torque_noise_Nm;
  const sim::ForceTorquePlatform platform(sim::rigGeometry(vehicle), sim::RotorAeroParams{}, pp);

  // Per equal-speed setpoint means, for the report (bounded: one entry per setpoint).
  struct Mean {
    double fz = 0, ty = 0, tfree = 0;
    int count = 0;
  };
  std::map<std::tuple<double, double, double>, Mean> means;
  const bool want_report = !o.report.empty();
  if (want_report && sw.setpointCount() > 200'000) {
    throw std::invalid_argument(
        "--report: at most 200000 setpoints can be plotted (this sweep has " +
        std::to_string(sw.setpointCount()) + ")");
  }
  double k_sum = 0.0;
  for (double k : sim::rigGeometry(vehicle).k_T_N_per_rpm2) k_sum += k;

  CsvFile csv(o.out);
  fmt::print(csv.get(),
             "t_s,h_m,tilt_deg,n1_rpm,n2_rpm,n3_rpm,n4_rpm,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm\n");
  Progress progress("rig platform");
  const std::size_t rows = platform.sweep(
      sw, o.seed,
      [&](const sim::PlatformRow& r) {
        fmt::print(csv.get(), "{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.t_s, r.h_m, r.tilt_deg,
                   r.n_rpm[0], r.n_rpm[1], r.n_rpm[2], r.n_rpm[3], r.force_B.x(), r.force_B.y(),
                   r.force_B.z(), r.torque_B.x(), r.torque_B.y(), r.torque_B.z());
        if (want_report && r.n_rpm[0] == r.n_rpm[1] && r.n_rpm[0] == r.n_rpm[2] &&
            r.n_rpm[0] == r.n_rpm[3]) {
          Mean& m = means[{r.tilt_deg, r.n_rpm[0], r.h_m}];
          m.fz += r.force_B.z();
          m.ty += r.torque_B.y();
          m.tfree = k_sum * r.n_rpm[0] * r.n_rpm[0];
          ++m.count;
        }
      },
      [&progress](std::size_t done, std::size_t total) { progress(done, total); });
  csv.close();
  std::cerr << fmt::format("geaware: wrote {} rows to {}\n", rows, o.out);

  if (want_report) {
    report::Page page("Virtual force/torque platform");
    page.addText(commandLine(
        fmt::format("rig platform --heights {} --tilts-deg {} --rpm {} --seed {} (vehicle {})",
                    o.heights, o.tilts, o.rpm, o.seed, vehicle.name)));
    report::Plot thrust{"Additional thrust ratio on the platform (level board rows)",
                        "h [m]",
                        "ΣF_z/ΣT_free − 1 [-]",
                        {}};
    report::Plot torque{"Leveling torque τ_y", "h [m]", "τ_y [N·m]", {}};
    std::map<std::pair<double, double>, report::Series> thrust_s;
    std::map<std::pair<double, double>, report::Series> torque_s;
    for (const auto& [key, m] : means) {
      const auto [tilt, n, h] = key;
      auto& ts = torque_s[{tilt, n}];
      ts.name = fmt::format("{:g}°, {:g} rpm", tilt, n);
      ts.mode = "lines+markers";
      ts.x.push_back(h);
      ts.y.push_back(m.ty / m.count);
      if (tilt == 0.0 && m.tfree > 0.0) {
        auto& fs = thrust_s[{tilt, n}];
        fs.name = fmt::format("{:g} rpm", n);
        fs.mode = "lines+markers";
        fs.x.push_back(h);
        fs.y.push_back(m.fz / m.count / m.tfree - 1.0);
      }
    }
    for (auto& [k, s] : thrust_s) thrust.series.push_back(std::move(s));
    for (auto& [k, s] : torque_s) torque.series.push_back(std::move(s));
    if (!thrust.series.empty()) page.addPlot(std::move(thrust));
    if (!torque.series.empty()) page.addPlot(std::move(torque));
    writePage(page, reportDir(o.report), "rig-platform", o.png, 1100);
  }
  return 0;
}

// ---------------------------------------------------------------------------------------------

int runRotor(const RigOptions& o) {
  const model::VehicleParams vehicle = loadVehicle(o.vehicle);
  sim::RotorStandParams sp;
  sp.hold_s = o.hold_s;
  sp.sample_period_s = o.sample_period_s;
  const sim::RotorStand stand(vehicle, sp);
  const std::vector<double> throttles = io::parseRange(o.throttle, "--throttle").values();
  report::Series rpm_s{"rotor speed", {}, {}, "lines", ""};
  report::Series thrust_s{"thrust", {}, {}, "lines", ""};
  report::Series torque_s{"torque", {}, {}, "lines", ""};
  const bool want_report = !o.report.empty();
  CsvFile csv(o.out);
  fmt::print(csv.get(), "t_s,throttle,rpm,thrust_N,torque_Nm\n");
  const std::size_t rows = stand.sweep(throttles, o.seed, [&](const sim::RotorStandRow& r) {
    fmt::print(csv.get(), "{},{},{},{},{}\n", r.t_s, r.throttle, r.rpm, r.thrust_N, r.torque_Nm);
    if (want_report && rpm_s.x.size() < 500'000) {
      rpm_s.x.push_back(r.t_s);
      rpm_s.y.push_back(r.rpm);
      thrust_s.x.push_back(r.rpm);
      thrust_s.y.push_back(r.thrust_N);
      torque_s.x.push_back(r.rpm);
      torque_s.y.push_back(r.torque_Nm);
    }
  });
  csv.close();
  std::cerr << fmt::format("geaware: wrote {} rows to {}\n", rows, o.out);
  if (want_report) {
    report::Page page("Virtual single-rotor stand");
    page.addText(commandLine(fmt::format("rig rotor --throttle {} --seed {} (vehicle {})",
                                         o.throttle, o.seed, vehicle.name)));
    thrust_s.mode = "markers";
    torque_s.mode = "markers";
    page.addPlot({"Rotor speed over time (throttle steps)", "t [s]", "n [rpm]", {rpm_s}});
    page.addPlot({"Thrust against rotor speed", "n [rpm]", "T [N]", {thrust_s}});
    page.addPlot({"Torque against rotor speed (J_R·ṅ spikes at the steps)",
                  "n [rpm]",
                  "M [N·m]",
                  {torque_s}});
    writePage(page, reportDir(o.report), "rig-rotor", o.png, 1600);
  }
  return 0;
}

// ---------------------------------------------------------------------------------------------

std::string checkJson(const sim::CalibrationResult& res) {
  std::string s =
      "{\"all_pass\":" + std::string(res.allPass() ? "true" : "false") + ",\"checks\":[";
  const auto esc = [](const std::string& t) {
    std::string r;
    for (char c : t) {
      if (c == '"' || c == '\\') r += '\\';
      r += c;
    }
    return r;
  };
  for (std::size_t i = 0; i < res.checks.size(); ++i) {
    const auto& c = res.checks[i];
    s += fmt::format(
        "{}{{\"name\":\"{}\",\"unit\":\"{}\",\"paper\":{},\"ours\":{},\"tolerance\":\"{}\","
        "\"pass\":{}}}",
        i ? "," : "", esc(c.name), esc(c.unit), c.paper, c.ours, esc(c.tolerance),
        c.pass ? "true" : "false");
  }
  return s + "]}\n";
}

int runCalibrate(const RigOptions& o) {
  const model::VehicleParams vehicle = loadVehicle(o.vehicle);
  const sim::CalibrationResult res = sim::calibrate(vehicle, sim::RotorAeroParams{});
  fmt::print(
      "Truth aerodynamics against the paper (FACTS.md), vehicle {}, default RotorAeroParams\n",
      vehicle.name);
  fmt::print("{:<46} {:>10} {:>10}  {:<18} {}\n", "target", "paper", "ours", "tolerance", "result");
  for (const auto& c : res.checks) {
    fmt::print("{:<46} {:>10.4g} {:>10.4g}  {:<18} {}\n",
               c.name + (c.unit == "-" ? "" : " [" + c.unit + "]"), c.paper, c.ours, c.tolerance,
               c.pass ? "pass" : "FAIL");
  }
  std::size_t failed = 0;
  for (const auto& c : res.checks) failed += c.pass ? 0 : 1;
  fmt::print("{} of {} targets pass\n", res.checks.size() - failed, res.checks.size());

  if (!o.json.empty()) {
    const std::string doc = checkJson(res);
    if (o.json == "-") {
      std::cout << doc;
    } else {
      std::ofstream f(o.json);
      if (!(f << doc)) throw std::runtime_error(o.json + ": cannot write JSON output");
    }
  }
  if (!o.report.empty()) {
    report::Page page("Truth aerodynamics: calibration against the paper");
    page.addText(commandLine("rig calibrate --report " + o.report) + " (vehicle " + vehicle.name +
                 ")");
    const auto& cv = res.curves;
    report::Table table{"Targets (FACTS.md) against the truth",
                        {"target", "unit", "paper", "ours", "tolerance", "result"},
                        {}};
    for (const auto& c : res.checks) {
      table.rows.push_back({c.name, c.unit, fmt::format("{:.4g}", c.paper),
                            fmt::format("{:.4g}", c.ours), c.tolerance, c.pass ? "pass" : "FAIL"});
    }
    page.addTable(std::move(table));
    // Paper points (FACTS.md tables) as markers.
    const std::vector<double> h15{0.36, 0.33, 0.31, 0.28, 0.22, 0.18,
                                  0.16, 0.14, 0.13, 0.12, 0.11, 0.10};
    const std::vector<double> t15{0.0,    -0.03, -0.10, -0.14, -0.165, -0.215,
                                  -0.215, -0.20, -0.19, -0.17, -0.15,  -0.12};
    const std::vector<double> dtilt{3, 5, 6, 8, 9, 11, 15};
    const std::vector<double> ttilt{-0.05, -0.075, -0.105, -0.13, -0.15, -0.16, -0.15};
    std::vector<double> lo;
    std::vector<double> hi;
    for (double v : cv.thrust_ratio_paper) {
      lo.push_back(0.8 * v);
      hi.push_back(1.2 * v);
    }
    page.addPlot({"Additional thrust on the level board, ΣT/ΣT_free − 1",
                  "h [m]",
                  "F_G [-]",
                  {{"truth (virtual platform)", cv.h_m, cv.thrust_ratio, "lines", ""},
                   {"paper fit g2/(h²+g1)", cv.h_m, cv.thrust_ratio_paper, "lines", "dash"},
                   {"paper −20 %", cv.h_m, lo, "lines", "dot"},
                   {"paper +20 %", cv.h_m, hi, "lines", "dot"}}});
    page.addPlot({"Leveling torque at 15° board tilt, 15,000 rpm",
                  "h [m]",
                  "τ_y [N·m]",
                  {{"truth (virtual platform)", cv.h_m, cv.torque_15deg_Nm, "lines", ""},
                   {"paper (measured, FACTS.md)", h15, t15, "markers", ""}}});
    page.addPlot({"Leveling torque at 0.11 m against board tilt, 15,000 rpm",
                  "board tilt δ [deg]",
                  "τ_y [N·m]",
                  {{"truth (virtual platform)", cv.tilt_deg, cv.torque_011_Nm, "lines", ""},
                   {"paper (measured, FACTS.md)", dtilt, ttilt, "markers", ""}}});
    writePage(page, reportDir(o.report), "rig-calibration", o.png, 2500);
  }
  if (failed > 0) throw std::runtime_error(fmt::format("{} calibration target(s) failed", failed));
  return 0;
}

}  // namespace

Runner addRigCommand(CLI::App& app) {
  auto opts = std::make_shared<RigOptions>();
  auto* rig = app.add_subcommand("rig", "The paper's virtual test rigs on the truth simulator");
  rig->require_subcommand(1);
  auto runner = std::make_shared<Runner>();

  const auto common = [&opts](CLI::App* cmd) {
    cmd->add_option("--vehicle", opts->vehicle,
                    "vehicle YAML file (default: the built-in paper quadrotor)")
        ->check(CLI::ExistingFile);
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
      ->check(CLI::Range(1, 1'000'000))
      ->capture_default_str();
  platform->add_option("--force-noise", opts->force_noise_N, "force sensor noise std [N]")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  platform->add_option("--torque-noise", opts->torque_noise_Nm, "torque sensor noise std [N·m]")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  platform->add_option("--seed", opts->seed, "noise seed (same seed: identical file)")
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
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  rotor->add_option("--sample-period", opts->sample_period_s, "time between samples [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  rotor->add_option("--seed", opts->seed, "noise seed")->capture_default_str();
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
  cal->add_option("--json", opts->json, "also write the checks as JSON to FILE ('-': stdout)");
  cal->add_flag("--png", opts->png,
                "with --report: also export the page as PNG (headless Chromium)");
  cal->callback([opts, runner] { *runner = [opts] { return runCalibrate(*opts); }; });

  return [runner] {
    if (!*runner) throw std::logic_error("geaware rig: no subcommand ran");
    return (*runner)();
  };
}

}  // namespace geaware::cli
