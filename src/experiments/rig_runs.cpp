// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/rig_runs.hpp"

#include "geaware/sim/similarity.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

namespace geaware::experiments {

void checkPlatformRigRun(const PlatformRigRun& run) {
  if (run.collect_means && run.sweep.setpointCount() > 200'000) {
    throw std::invalid_argument(
        "--report: at most 200000 setpoints can be plotted (this sweep has " +
        std::to_string(run.sweep.setpointCount()) + ")");
  }
}

PlatformRigResult runPlatformRig(const sim::TruthParams& truth, const PlatformRigRun& run,
                                 const std::function<void(const sim::PlatformRow&)>& sink,
                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  checkPlatformRigRun(run);
  const sim::RotorGeometry geometry = platformGeometry(truth);
  const sim::ForceTorquePlatform platform(geometry, truth.aero, run.params);
  double k_sum = 0.0;
  for (double k : geometry.k_T_N_per_rpm2) k_sum += k;
  PlatformRigResult result;
  result.rows = platform.sweep(
      run.sweep, run.seed,
      [&](const sim::PlatformRow& r) {
        sink(r);
        if (run.collect_means && r.n_rpm[0] == r.n_rpm[1] && r.n_rpm[0] == r.n_rpm[2] &&
            r.n_rpm[0] == r.n_rpm[3]) {
          PlatformSetpointMean& m = result.means[{r.tilt_deg, r.n_rpm[0], r.h_m}];
          m.fz_N += r.force_B.z();
          m.ty_Nm += r.torque_B.y();
          m.t_free_N = k_sum * r.n_rpm[0] * r.n_rpm[0];
          ++m.count;
        }
      },
      progress);
  return result;
}

report::Page platformRigPage(const PlatformMeans& means, const std::string& produced_by) {
  report::Page page("Virtual force/torque platform");
  page.addText(produced_by);
  report::Plot thrust{"Additional thrust ratio on the platform (level board rows)", "h [m]",
                      "ΣF_z/ΣT_free − 1 [-]", {}};
  report::Plot torque{"Leveling torque τ_y", "h [m]", "τ_y [N·m]", {}};
  std::map<std::pair<double, double>, report::Series> thrust_s;
  std::map<std::pair<double, double>, report::Series> torque_s;
  for (const auto& [key, m] : means) {
    const auto [tilt, n, h] = key;
    auto& ts = torque_s[{tilt, n}];
    ts.name = fmt::format("{:g}°, {:g} rpm", tilt, n);
    ts.mode = "lines+markers";
    ts.x.push_back(h);
    ts.y.push_back(m.ty_Nm / m.count);
    if (tilt == 0.0 && m.t_free_N > 0.0) {
      auto& fs = thrust_s[{tilt, n}];
      fs.name = fmt::format("{:g} rpm", n);
      fs.mode = "lines+markers";
      fs.x.push_back(h);
      fs.y.push_back(m.fz_N / m.count / m.t_free_N - 1.0);
    }
  }
  for (auto& [k, s] : thrust_s) thrust.series.push_back(std::move(s));
  for (auto& [k, s] : torque_s) torque.series.push_back(std::move(s));
  if (!thrust.series.empty()) page.addPlot(std::move(thrust));
  if (!torque.series.empty()) page.addPlot(std::move(torque));
  return page;
}

sim::RotorGeometry platformGeometry(const sim::TruthParams& truth) {
  sim::TruthParams mounted = truth;
  mounted.cog_offset_B.setZero();
  return mounted.rotorGeometry();
}

model::VehicleParams rotorStandVehicle(const model::VehicleParams& file_vehicle,
                                       const sim::TruthParams& truth) {
  model::VehicleParams v = file_vehicle;
  v.rotor.k_T_N_per_rpm2 = truth.k_T_N_per_rpm2 * truth.thrust_multiplier[0];
  v.rotor.k_I_Nm_per_rpm2 = truth.k_I_Nm_per_rpm2 * truth.torque_multiplier[0];
  v.rotor.J_R_kgm2 = truth.motor.J_R_kgm2;
  v.throttle = truth.motor.throttle;
  return v;
}

RotorRigResult runRotorRig(const model::VehicleParams& vehicle, const sim::RotorStandParams& params,
                           const std::vector<double>& throttles, std::uint64_t seed,
                           const std::function<void(const sim::RotorStandRow&)>& sink,
                           bool collect) {
  const sim::RotorStand stand(vehicle, params);
  RotorRigResult result;
  result.rows = stand.sweep(throttles, seed, [&](const sim::RotorStandRow& r) {
    sink(r);
    if (collect && result.kept.size() < 500'000) result.kept.push_back(r);
  });
  return result;
}

report::Page rotorRigPage(const std::vector<sim::RotorStandRow>& rows, const std::string& produced_by) {
  report::Series rpm_s{"rotor speed", {}, {}, "lines", ""};
  report::Series thrust_s{"thrust", {}, {}, "markers", ""};
  report::Series torque_s{"torque", {}, {}, "markers", ""};
  for (const auto& r : rows) {
    rpm_s.x.push_back(r.t_s);
    rpm_s.y.push_back(r.rpm);
    thrust_s.x.push_back(r.rpm);
    thrust_s.y.push_back(r.thrust_N);
    torque_s.x.push_back(r.rpm);
    torque_s.y.push_back(r.torque_Nm);
  }
  report::Page page("Virtual single-rotor stand");
  page.addText(produced_by);
  page.addPlot({"Rotor speed over time (throttle steps)", "t [s]", "n [rpm]", {rpm_s}});
  page.addPlot({"Thrust against rotor speed", "n [rpm]", "T [N]", {thrust_s}});
  page.addPlot({"Torque against rotor speed (J_R·ṅ spikes at the steps)", "n [rpm]", "M [N·m]",
                {torque_s}});
  return page;
}

std::string differsFromThePapersRotors(const model::VehicleParams& v) {
  using Ref = sim::ReferenceVehicle;
  // The mass counts too: the drag targets are at the hover speed √(m·g/(4·k_T)).
  if (v.mass_kg == Ref::kMassKg && v.propeller_radius_m == Ref::kPropellerRadiusM &&
      v.diagonal_rotor_distance_m == Ref::kDiagonalRotorDistanceM &&
      v.rotor.k_T_N_per_rpm2 == Ref::kThrustCoefficientNPerRpm2) {
    return {};
  }
  return fmt::format(
      "m {:.4g} kg, R {:.4g} m, b {:.4g} m, k_T {:.4g} N/rpm² against the paper vehicle's {:.4g} kg, "
      "{:.4g} m, {:.4g} m, {:.4g}",
      v.mass_kg, v.propeller_radius_m, v.diagonal_rotor_distance_m, v.rotor.k_T_N_per_rpm2, Ref::kMassKg,
      Ref::kPropellerRadiusM, Ref::kDiagonalRotorDistanceM, Ref::kThrustCoefficientNPerRpm2);
}

std::string calibrationText(const sim::CalibrationResult& res, const std::string& vehicle_name,
                            const std::string& world, const std::string& differs) {
  std::string s = fmt::format(
      "Truth aerodynamics against the paper (docs/paper-facts.md), vehicle {}, the aerodynamics of {}\n",
      vehicle_name, world);
  if (!differs.empty()) {
    s += fmt::format(
        "note: the targets are measurements of the paper vehicle's rotors; this vehicle's differ ({}): "
        "its heights, speeds and torques are not the paper's, so the results are information, not a test\n",
        differs);
  }
  s += fmt::format("{:<46} {:>10} {:>10}  {:<18} {}\n", "target", "paper", "ours", "tolerance", "result");
  std::size_t failed = 0;
  for (const auto& c : res.checks) {
    s += fmt::format("{:<46} {:>10.4g} {:>10.4g}  {:<18} {}\n",
                     c.name + (c.unit == "-" ? "" : " [" + c.unit + "]"), c.paper, c.ours,
                     c.tolerance, !differs.empty() ? "info" : c.pass ? "pass" : "FAIL");
    failed += c.pass ? 0 : 1;
  }
  s += differs.empty()
           ? fmt::format("{} of {} targets pass\n", res.checks.size() - failed, res.checks.size())
           : fmt::format("{} of {} within the paper's tolerances (information)\n", res.checks.size() - failed,
                         res.checks.size());
  return s;
}

report::Page calibrationPage(const sim::CalibrationResult& res, const std::string& produced_by) {
  report::Page page("Truth aerodynamics: calibration against the paper");
  page.addText(produced_by);
  const auto& cv = res.curves;
  report::Table table{"Targets (docs/paper-facts.md) against the truth",
                      {"target", "unit", "paper", "ours", "tolerance", "result"},
                      {}};
  for (const auto& c : res.checks) {
    table.rows.push_back({c.name, c.unit, fmt::format("{:.4g}", c.paper), fmt::format("{:.4g}", c.ours),
                          c.tolerance, c.pass ? "pass" : "FAIL"});
  }
  page.addTable(std::move(table));
  // The paper's measured points (docs/paper-facts.md tables) as markers.
  const std::vector<double> h15{0.36, 0.33, 0.31, 0.28, 0.22, 0.18, 0.16, 0.14, 0.13, 0.12, 0.11, 0.10};
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
                 {"paper (measured, docs/paper-facts.md)", h15, t15, "markers", ""}}});
  page.addPlot({"Leveling torque at 0.11 m against board tilt, 15,000 rpm",
                "board tilt δ [deg]",
                "τ_y [N·m]",
                {{"truth (virtual platform)", cv.tilt_deg, cv.torque_011_Nm, "lines", ""},
                 {"paper (measured, docs/paper-facts.md)", dtilt, ttilt, "markers", ""}}});
  return page;
}

std::vector<std::filesystem::path> writeRigPage(const report::Page& page, const std::filesystem::path& dir,
                                                const std::string& stem, bool png, int png_height_px) {
  if (std::filesystem::exists(dir) && !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("--report " + dir.string() + ": exists and is not a directory");
  }
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> written{dir / (stem + ".html")};
  page.write(written.back());
  if (png) {
    written.push_back(dir / (stem + ".png"));
    report::exportPng(written.front(), written.back(), 1200, png_height_px);
  }
  return written;
}

}  // namespace geaware::experiments
