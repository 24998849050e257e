// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Plot builders shared by the single-flight report (`geaware fly --report`) and the campaign's
// (`geaware bench --report`): the same series (experiments/flight_series.hpp) drawn the same
// way. Each flown curve keeps one colour on every plot; x–y views are drawn at equal aspect;
// height plots show the terrain under the vehicle.

#include <string>
#include <vector>

#include "geaware/experiments/flight_series.hpp"
#include "geaware/io/provenance.hpp"
#include "geaware/report/page.hpp"

namespace geaware::experiments::plots {

/// One flight on a plot: its legend name, its series and its colour.
struct Flown {
  std::string name;
  const FlightSeries* series = nullptr;
  std::string color;
};

/// The colour of curve `index` (a fixed palette, cycled): the same index, the same colour on
/// every plot of a page.
[[nodiscard]] std::string color(std::size_t index);

[[nodiscard]] report::Series line(std::string name, std::vector<double> x, std::vector<double> y,
                                  std::string dash = "", std::string color = "");

/// Only the points of the trajectory (t ≥ 0) of one component of `s`.
[[nodiscard]] std::vector<double> trajectoryPart(const FlightSeries& s, const std::vector<double>& v);

/// x–y seen from above, at equal aspect: the reference of the first flight, then each flight.
[[nodiscard]] report::Plot topView(const std::string& title, const std::vector<Flown>& flown);
/// x–z seen from the side: the reference, each flight and the terrain under the first.
[[nodiscard]] report::Plot sideView(const std::string& title, const std::vector<Flown>& flown);
/// z over time: the reference, each flight, the first flight's ranger height and the terrain
/// under it.
[[nodiscard]] report::Plot heightPlot(const std::string& title, const std::vector<Flown>& flown);
/// ‖E_P‖ over time for each flight; with one flight also E_z.
[[nodiscard]] report::Plot errorPlot(const std::string& title, const std::vector<Flown>& flown);
/// Angle between desired and true attitude over time, for each flight.
[[nodiscard]] report::Plot attitudeErrorPlot(const std::string& title, const std::vector<Flown>& flown);
/// The four true rotor speeds of one flight.
[[nodiscard]] report::Plot rotorPlot(const std::string& title, const FlightSeries& s);
/// τ_des and τ̂_B of one flight, per axis.
[[nodiscard]] report::Plot torquePlot(const std::string& title, const FlightSeries& s);

/// Where the page came from: version, commit, command line, seeds, SHA-256 of the inputs.
[[nodiscard]] report::Table provenanceTable(const io::RunInfo& run);

}  // namespace geaware::experiments::plots
