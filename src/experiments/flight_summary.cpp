// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/flight_summary.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "geaware/experiments/flight_plots.hpp"

namespace geaware::experiments {

std::string controllerName(const control::ControllerParams& p) {
  return control::configurationName(p);
}

std::string formatFlight(const FlightResult& r) {
  const auto& m = r.tracking;
  // A flight that ended before the trajectory has no tracking error (it printed RMSE 0).
  std::string s = m.samples == 0
                      ? std::string("RMSE none: no sample on the trajectory (0 samples)\n")
                      : fmt::format("RMSE XOY {:.2f} cm, Z {:.2f} cm, all {:.2f} cm; max ‖E_P‖ {:.2f} cm; "
                                    "σ‖E_P‖ {:.2f} cm ({} samples)\n",
                                    m.rmse_xy_m * 100, m.rmse_z_m * 100, m.rmse_all_m * 100, m.max_m * 100,
                                    m.std_m * 100, m.samples);
  s += r.crash ? "CRASHED: " + r.crash_description + "\n" : std::string("completed, no crash\n");
  std::string flags;
  for (int b = 0; b < kControllerFlagBits; ++b) {
    const auto n = r.flag_counts[static_cast<std::size_t>(b)];
    if (n > 0) flags += fmt::format("{}{} {}", flags.empty() ? "" : ", ", controllerFlagName(b), n);
  }
  if (!flags.empty()) s += "controller flags (ticks): " + flags + "\n";
  if (r.guard_active_s) s += fmt::format("clearance guard active {:.3f} s\n", *r.guard_active_s);
  if (r.min_obstacle_clearance_m) {
    s += fmt::format("closest a rotor disc's rim came to an obstacle: {:.1f} cm\n", *r.min_obstacle_clearance_m * 100);
  }
  if (const auto& g = r.ground_contact) {
    if (!std::isnan(g->touchdown_t_s)) {
      s += fmt::format("touchdown at {:.3f} s, sinking {:.3f} m/s; bounce {:.1f} mm; legs compressed "
                       "up to {:.1f} mm; tilt on the ground up to {:.1f}°\n",
                       g->touchdown_t_s, g->touchdown_speed_mps, g->bounce_m * 1e3,
                       g->max_compression_m * 1e3, g->max_tilt_on_ground_deg);
    }
    if (!std::isnan(g->liftoff_t_s)) {
      s += fmt::format("lift-off at {:.3f} s; tilt on the ground up to {:.1f}°; back on the ground "
                       "{} time(s) after it\n",
                       g->liftoff_t_s, g->max_tilt_on_ground_deg, g->recontacts);
    }
    if (g->landed) s += fmt::format("landed (land detector) at {:.3f} s\n", g->landed_t_s);
    s += fmt::format("feet on the ground at the end: {}\n", g->feet_down_at_end);
  }
  if (const auto& l = r.learned_ground_effect) {
    s += fmt::format("learned in flight: F_G at {} knots ({} samples, offset {:.4f}); leveling scale {:.4g} ({})\n",
                     l->heights_m.size(), l->samples, l->offset, l->leveling_scale,
                     l->leveling_learned ? fmt::format("learned from {} samples", l->leveling_samples)
                                         : fmt::format("its start: not excited enough, {} samples", l->leveling_samples));
  }
  s += fmt::format("simulated {:.2f} s in {:.3f} s: {:.0f}× real time\n", r.simulated_s, r.wall_s,
                   r.real_time_factor);
  return s;
}

io::Json flightJson(const FlightScenario& s, const FlightResult& r) {
  const auto& m = r.tracking;
  // No sample on the trajectory (a strike before it): the metrics are null, not 0.
  const auto cm = [&m](double v_m) { return m.samples == 0 ? io::Json(nullptr) : io::Json(v_m * 100); };
  io::Json j = {{"rmse_xy_cm", cm(m.rmse_xy_m)}, {"rmse_z_cm", cm(m.rmse_z_m)},
                {"rmse_all_cm", cm(m.rmse_all_m)}, {"max_cm", cm(m.max_m)},
                {"std_cm", cm(m.std_m)},          {"crashed", r.crash.has_value()}};
  if (r.crash) {
    const auto& p = r.crash->point_W;
    j["crash"] = {{"t_s", r.crash->t_s},
                  {"point_m", {p.x(), p.y(), p.z()}},
                  {"description", r.crash_description}};
  } else {
    j["crash"] = nullptr;
  }
  j["samples"] = m.samples;
  j["controller"] = controllerName(s.controller);
  j["seed"] = s.seed;
  io::Json flags = io::Json::object();
  for (int b = 0; b < kControllerFlagBits; ++b) {
    flags[controllerFlagName(b)] = r.flag_counts[static_cast<std::size_t>(b)];
  }
  j["flags"] = std::move(flags);
  j["guard_active_s"] = r.guard_active_s ? io::Json(*r.guard_active_s) : io::Json(nullptr);
  if (r.min_obstacle_clearance_m) j["min_obstacle_clearance_m"] = *r.min_obstacle_clearance_m;
  if (const auto& g = r.ground_contact) {
    j.update(touchdownJson(*g));  // NaN is written as null
    j["ground_contact"] = {{"touchdown_t_s", g->touchdown_t_s},
                           {"max_compression_m", g->max_compression_m},
                           {"max_tilt_on_ground_deg", g->max_tilt_on_ground_deg},
                           {"liftoff_t_s", g->liftoff_t_s},
                           {"recontacts", g->recontacts},
                           {"landed", g->landed},
                           {"landed_t_s", g->landed_t_s},
                           {"feet_down_at_end", g->feet_down_at_end}};
  }
  if (const auto& l = r.learned_ground_effect) {
    j["learned"] = {{"f_g", {{"heights_m", l->heights_m}, {"values", l->f_g}, {"learned", l->learned}}},
                    {"offset", l->offset},
                    {"samples", l->samples},
                    {"leveling_scale", l->leveling_scale},
                    {"leveling_learned", l->leveling_learned},
                    {"leveling_samples", l->leveling_samples}};
  }
  j["simulated_s"] = r.simulated_s;
  j["wall_s"] = r.wall_s;
  j["real_time_factor"] = r.real_time_factor;
  return j;
}

io::Json touchdownJson(const GroundContactSummary& g) {
  return {{"touchdown_speed_mps", g.touchdown_speed_mps},
          {"bounce_m", std::isnan(g.touchdown_t_s) ? std::nan("") : g.bounce_m}};
}

io::Json groundContactJson(const GroundContactSummary& g) {
  io::Json j = touchdownJson(g);
  j["landed"] = g.landed;
  j["liftoff_t_s"] = g.liftoff_t_s;
  j["recontacts"] = g.recontacts;
  j["max_tilt_on_ground_deg"] = g.max_tilt_on_ground_deg;
  return j;
}

std::filesystem::path writeFlightReport(const std::filesystem::path& dir, const FlightSeries& series,
                                        const FlightResult& r, const std::string& title,
                                        const io::RunInfo& run, bool png) {
  if (std::filesystem::exists(dir) && !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("--report " + dir.string() + ": exists and is not a directory");
  }
  std::filesystem::create_directories(dir);
  report::Page page("Closed-loop flight: " + title);
  const auto& m = r.tracking;
  page.addTable(
      {"Tracking (reference vs true position, cm)",
       {"RMSE XOY", "RMSE Z", "RMSE all", "max ‖E_P‖", "σ‖E_P‖", "crash"},
       {{fmt::format("{:.2f}", m.rmse_xy_m * 100), fmt::format("{:.2f}", m.rmse_z_m * 100),
         fmt::format("{:.2f}", m.rmse_all_m * 100), fmt::format("{:.2f}", m.max_m * 100),
         fmt::format("{:.2f}", m.std_m * 100), r.crash ? r.crash_description : std::string("none")}}});
  page.addTable(plots::provenanceTable(run));
  const std::vector<plots::Flown> flown = {{"flown (truth)", &series, plots::color(0)}};
  page.addPlot(plots::topView("Trajectory seen from above", flown));
  page.addPlot(plots::heightPlot("Height over time, terrain under the vehicle", flown));
  page.addPlot(plots::errorPlot("Position error over time", flown));
  page.addPlot(plots::attitudeErrorPlot("Attitude error (desired vs true) over time", flown));
  page.addPlot(plots::rotorPlot("Rotor speeds (truth)", series));
  page.addPlot(plots::torquePlot("Body torques: command τ_des and rotor estimate τ̂_B", series));
  const auto html = dir / "flight.html";
  page.write(html);
  if (png) report::exportPagePng(html, dir / "flight.png");
  return html;
}

}  // namespace geaware::experiments
