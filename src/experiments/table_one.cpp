// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/table_one.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace geaware::experiments {

const std::vector<TableOneExperiment>& tableOneExperiments() {
  using A = control::AccelerationCompensation;
  using T = control::TorqueCompensation;
  constexpr double kN = std::numeric_limits<double>::quiet_NaN();
  const TableMetrics kNoPaper{kN, kN, kN, kN, kN};
  // docs/paper-facts.md, "Table I: the paper's flights"; cm.
  static const std::vector<TableOneExperiment> kTable = {
      {1, A::kNone, T::kNone, 0.12, 1.0, 1.5, 0.8, {6.54, 8.64, 10.85, 18.04, 2.19}},
      {2, A::kIndi, T::kNone, 0.12, 1.0, 1.5, 0.8, {5.51, 6.83, 8.77, 16.07, 2.06}},
      {3, A::kNeural, T::kNone, 0.12, 1.0, 1.5, 0.8, {6.81, 4.94, 8.41, 16.75, 2.73}},
      {4, A::kModel, T::kNone, 0.12, 1.0, 1.5, 0.8, {7.12, 1.94, 7.38, 16.45, 3.05}},
      {5, A::kModel, T::kModelIndi, 0.12, 1.0, 1.5, 0.8, {4.35, 0.97, 4.45, 11.97, 2.32}},
      {6, A::kModel, T::kNone, 0.18, 3.0, 4.0, 1.7, {12.63, 1.71, 12.74, 26.27, 5.36}},
      {7, A::kModel, T::kModelIndi, 0.18, 3.0, 4.0, 1.7, {6.67, 2.84, 6.97, 14.66, 2.72}},
      {8, A::kModel, T::kModelIndi, 1.75, 5.0, 6.0, 2.5, {4.77, 1.41, 4.98, 9.75, 1.64}},
      // geaware's `recommended` (docs/controller.md) on the flights of exps 1–5 and 6–7.
      {9, A::kModel, T::kModelIndi, 0.12, 1.0, 1.5, 0.8, kNoPaper, true},
      {10, A::kModel, T::kModelIndi, 0.18, 3.0, 4.0, 1.7, kNoPaper, true},
  };
  return kTable;
}

control::ControllerParams TableOneExperiment::controller() const {
  control::ControllerParams p;
  if (recommended) return control::recommendedControllerParams();
  p.acceleration = acceleration;
  p.torque = torque;
  return p;
}

const TableOneExperiment& tableOneExperiment(int number) {
  for (const auto& e : tableOneExperiments()) {
    if (e.number == number) return e;
  }
  throw std::out_of_range("Table I has experiments 1 to 8 (the paper's) and 9, 10 (recommended), not " +
                          std::to_string(number));
}

traj::LemniscateParams lemniscateFor(const TableOneExperiment& e) {
  traj::LemniscateParams p;
  p.half_extent_x_m = e.half_extent_x_m;
  p.half_extent_y_m = e.half_extent_y_m;
  p.height_m = e.height_m;
  p.peak_speed_mps = e.speed_mps;
  p.laps = 1;
  return p;
}

TableMetrics toCentimetres(const TrackingMetrics& m) noexcept {
  return {m.rmse_xy_m * 100.0, m.rmse_z_m * 100.0, m.rmse_all_m * 100.0, m.max_m * 100.0,
          m.std_m * 100.0};
}

namespace {
MeanStd meanStd(const std::vector<TableMetrics>& rows, double TableMetrics::*field) {
  MeanStd r;
  if (rows.empty()) return r;
  for (const auto& row : rows) r.mean += row.*field;
  r.mean /= static_cast<double>(rows.size());
  double ss = 0.0;
  for (const auto& row : rows) ss += (row.*field - r.mean) * (row.*field - r.mean);
  r.std = std::sqrt(ss / static_cast<double>(rows.size()));
  return r;
}
}  // namespace

ExperimentSummary summarise(const TableOneExperiment& e, const std::vector<std::uint64_t>& seeds,
                            const std::vector<FlightResult>& flights) {
  if (seeds.size() != flights.size()) {
    throw std::invalid_argument("summarise: one flight per seed expected");
  }
  ExperimentSummary s;
  s.experiment = e;
  s.seeds = seeds;
  for (const auto& f : flights) {
    s.per_seed.push_back(toCentimetres(f.tracking));
    s.crashed.push_back(f.crash.has_value());
    s.crash_t_s.push_back(f.crash ? f.crash->t_s : std::numeric_limits<double>::quiet_NaN());
    if (f.crash) ++s.crashes;
    if (f.guard_active_s) {
      s.guard_active_s = (std::isnan(s.guard_active_s) ? 0.0 : s.guard_active_s) + *f.guard_active_s;
    }
  }
  s.rmse_xy_cm = meanStd(s.per_seed, &TableMetrics::rmse_xy_cm);
  s.rmse_z_cm = meanStd(s.per_seed, &TableMetrics::rmse_z_cm);
  s.rmse_all_cm = meanStd(s.per_seed, &TableMetrics::rmse_all_cm);
  s.max_cm = meanStd(s.per_seed, &TableMetrics::max_cm);
  s.std_cm = meanStd(s.per_seed, &TableMetrics::std_cm);
  return s;
}

}  // namespace geaware::experiments
