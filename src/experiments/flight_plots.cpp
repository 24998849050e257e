// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/flight_plots.hpp"

#include <fmt/format.h>

#include <array>
#include <string_view>
#include <utility>

namespace geaware::experiments::plots {
namespace {

/// Terrain height under the vehicle: true z − true height above the terrain [m].
std::vector<double> terrainUnder(const FlightSeries& s, bool trajectory_only) {
  std::vector<double> z;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!trajectory_only || s.t_s[i] >= 0.0) z.push_back(s.true_m[2][i] - s.h_true_m[i]);
  }
  return z;
}

report::Series terrain(std::vector<double> x, std::vector<double> z) {
  report::Series t = line("terrain under the vehicle", std::move(x), std::move(z), "", "#8c6d46");
  t.fill = "tozeroy";
  return t;
}

}  // namespace

std::string color(std::size_t index) {
  // plotly's default sequence, so that pages look as before where colours did not matter.
  static constexpr std::array<std::string_view, 10> kPalette = {
      "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
      "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return std::string(kPalette[index % kPalette.size()]);
}

report::Series line(std::string name, std::vector<double> x, std::vector<double> y,
                    std::string dash, std::string color) {
  report::Series s;
  s.name = std::move(name);
  s.x = std::move(x);
  s.y = std::move(y);
  s.mode = "lines";
  s.dash = std::move(dash);
  s.color = std::move(color);
  return s;
}

std::vector<double> trajectoryPart(const FlightSeries& s, const std::vector<double>& v) {
  std::vector<double> out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.t_s[i] >= 0.0) out.push_back(v[i]);
  }
  return out;
}

report::Plot topView(const std::string& title, const std::vector<Flown>& flown) {
  report::Plot p{title, "x [m]", "y [m]", {}};
  p.equal_aspect = true;
  if (flown.empty()) return p;
  const FlightSeries& first = *flown.front().series;
  p.series.push_back(line("reference", trajectoryPart(first, first.ref_m[0]),
                          trajectoryPart(first, first.ref_m[1]), "dash", "#000000"));
  for (const auto& f : flown) {
    const FlightSeries& s = *f.series;
    p.series.push_back(
        line(f.name, trajectoryPart(s, s.true_m[0]), trajectoryPart(s, s.true_m[1]), "", f.color));
  }
  return p;
}

report::Plot sideView(const std::string& title, const std::vector<Flown>& flown) {
  report::Plot p{title, "x [m]", "z [m]", {}};
  if (flown.empty()) return p;
  const FlightSeries& first = *flown.front().series;
  p.series.push_back(terrain(trajectoryPart(first, first.true_m[0]), terrainUnder(first, true)));
  p.series.back().mode = "markers";
  p.series.back().fill.clear();
  p.series.push_back(line("reference", trajectoryPart(first, first.ref_m[0]),
                          trajectoryPart(first, first.ref_m[2]), "dash", "#000000"));
  for (const auto& f : flown) {
    const FlightSeries& s = *f.series;
    p.series.push_back(
        line(f.name, trajectoryPart(s, s.true_m[0]), trajectoryPart(s, s.true_m[2]), "", f.color));
  }
  return p;
}

report::Plot heightPlot(const std::string& title, const std::vector<Flown>& flown) {
  report::Plot p{title, "t [s]", "z [m]", {}};
  if (flown.empty()) return p;
  const FlightSeries& first = *flown.front().series;
  p.series.push_back(terrain(first.t_s, terrainUnder(first, false)));
  p.series.push_back(line("reference", first.t_s, first.ref_m[2], "dash", "#000000"));
  for (const auto& f : flown) p.series.push_back(line(f.name, f.series->t_s, f.series->true_m[2], "", f.color));
  if (flown.size() == 1) {
    p.series.push_back(line("ranger height", first.t_s, first.h_meas_m, "dot", color(1)));
  }
  return p;
}

report::Plot errorPlot(const std::string& title, const std::vector<Flown>& flown) {
  report::Plot p{title, "t [s]", "error [cm]", {}};
  for (const auto& f : flown) {
    const FlightSeries& s = *f.series;
    p.series.push_back(line(flown.size() == 1 ? "‖E_P‖" : f.name, trajectoryPart(s, s.t_s),
                            trajectoryPart(s, s.err_cm), "", f.color));
  }
  if (flown.size() == 1) {
    const FlightSeries& s = *flown.front().series;
    p.series.push_back(
        line("E_z", trajectoryPart(s, s.t_s), trajectoryPart(s, s.err_z_cm), "dot", color(1)));
  }
  return p;
}

report::Plot attitudeErrorPlot(const std::string& title, const std::vector<Flown>& flown) {
  report::Plot p{title, "t [s]", "E [deg]", {}};
  for (const auto& f : flown) {
    const FlightSeries& s = *f.series;
    p.series.push_back(
        line(f.name, trajectoryPart(s, s.t_s), trajectoryPart(s, s.att_err_deg), "", f.color));
  }
  return p;
}

report::Plot rotorPlot(const std::string& title, const FlightSeries& s) {
  report::Plot p{title, "t [s]", "n [rpm]", {}};
  for (std::size_t i = 0; i < 4; ++i) {
    p.series.push_back(line(fmt::format("rotor {}", i + 1), s.t_s, s.n_rpm[i], "", color(i)));
  }
  return p;
}

report::Plot torquePlot(const std::string& title, const FlightSeries& s) {
  report::Plot p{title, "t [s]", "τ [N·m]", {}};
  const char* axis[3] = {"x", "y", "z"};
  for (std::size_t i = 0; i < 3; ++i) {
    p.series.push_back(line(fmt::format("τ_des,{}", axis[i]), s.t_s, s.tau_des_Nm[i], "", color(i)));
    p.series.push_back(line(fmt::format("τ̂_B,{}", axis[i]), s.t_s, s.tau_hat_Nm[i], "dot", color(i)));
  }
  return p;
}

report::Table provenanceTable(const io::RunInfo& run) {
  const io::Json p = io::provenanceJson(run);
  report::Table t{"Provenance", {"", ""}, {}};
  t.rows.push_back({"geaware", p["geaware_version"].get<std::string>() + " (" +
                                   p["commit"].get<std::string>() + ")"});
  t.rows.push_back({"command line", run.command_line});
  std::string seeds;
  for (const auto s : run.seeds) seeds += (seeds.empty() ? "" : " ") + std::to_string(s);
  t.rows.push_back({"seeds", seeds.empty() ? "none" : seeds});
  for (const auto& in : p["inputs"]) {
    t.rows.push_back({"input " + in["path"].get<std::string>(),
                      in["sha256"].is_null() ? "unreadable" : "SHA-256 " + in["sha256"].get<std::string>()});
  }
  return t;
}

}  // namespace geaware::experiments::plots
