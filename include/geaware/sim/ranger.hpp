// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The simulated lattice time-of-flight ranger (the paper: 16×16 zones at 100 Hz,
// under the body, looking down along −z_B). Each zone is one ray from the mount point along
// model::RangerFrame::zoneDirection_B, cast against the Terrain; the frame is filled exactly as
// sensor_data.hpp documents (zone (i, j) at index i·N + j, i along x_B, j along y_B).
//
// A zone returns when its ray hits the surface between min_range_m and max_range_m and the
// angle between the ray and the surface normal is at most max_incidence_rad (grazing rays
// scatter away: no return). Its range is the true distance plus N(0, σ²) with
//   σ = noise_floor_m + noise_fraction·r        (noise proportional to range),
// clipped at 0. Outliers: each zone, with outlier_probability, reports instead a uniform range
// in [min_range_m, max_range_m] and is valid whether or not it saw the ground (multipath,
// crosstalk, sunlight). A zone without a return has valid = false and range_m = 0.
//
// Simplification: a real zone averages its whole solid angle (and reports the nearest or the
// strongest target in it); here each zone is its centre ray. Rays do not hit the vehicle.
//
// Defaults: a VL53L5CX-class sensor (45° field of view per axis, 4 m range) in the paper's
// 16×16 layout, mounted 3 cm under the rotor plane, 3 mm + 1 % noise, 80° grazing limit,
// one outlier per thousand zones.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/sensor_data.hpp"
#include "geaware/model/units.hpp"
#include "geaware/model/field_error.hpp"
#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/sampling.hpp"
#include "geaware/sim/terrain.hpp"

namespace geaware::sim {

struct RangerParams {
  double rate_Hz = 100.0;                                         ///< frame rate [Hz]
  int side = 16;                                                  ///< N, zones per side (1…16) [-]
  double fov_rad = 45.0 * model::kDegToRad;                       ///< full field of view per axis [rad]
  Eigen::Vector3d mount_B = Eigen::Vector3d(0.0, 0.0, -0.03);     ///< sensor origin rel. the geometric centre, body [m]
  double min_range_m = 0.01;                                      ///< nearer returns are lost [m]
  double max_range_m = 4.0;                                       ///< farther surfaces give no return [m]
  double max_incidence_rad = 80.0 * model::kDegToRad;             ///< ray-to-normal angle beyond which nothing returns [rad]
  double noise_floor_m = 0.003;                                   ///< range-independent noise, 1σ [m]
  double noise_fraction = 0.01;                                   ///< noise growth with range, 1σ per metre [-]
  double outlier_probability = 1.0e-3;                            ///< per zone and frame [-]

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

class LatticeRanger {
 public:
  /// Throws model::InvalidParameters listing every invalid field. Noise stream:
  /// (scenario_seed, salt::kRanger).
  LatticeRanger(const RangerParams& params, std::uint64_t scenario_seed);

  /// A frame when one is due at state.t_s, else nothing (also for a non-finite state, counted
  /// in rejected()). A null terrain means nothing to see: every zone invalid (outliers aside).
  /// No allocation.
  [[nodiscard]] std::optional<model::RangerFrame> sample(const PlantState& state, const Terrain* terrain) noexcept;

  /// The frame at `state` now, whatever the schedule (benchmarks, tests).
  [[nodiscard]] model::RangerFrame measure(const PlantState& state, const Terrain* terrain) noexcept;

  [[nodiscard]] const RangerParams& params() const noexcept { return params_; }
  [[nodiscard]] long rejected() const noexcept { return rejected_; }

 private:
  /// measure() into a frame that starts as a copy of blank_ (no 2.3 kB copy on the way out).
  void measureInto(model::RangerFrame& frame, const PlantState& state,
                   const Terrain* terrain) noexcept;

  RangerParams params_;
  NoiseSource noise_;
  SampleClock clock_;
  model::RangerFrame blank_;                                   // geometry filled, no returns
  std::array<Eigen::Vector3d, model::RangerFrame::kMaxZones> dir_B_{};  // zoneDirection_B, by index
  double min_cos_incidence_;
  std::int64_t zones_to_outlier_;  // countdown to the next outlier zone (geometric gaps)
  long rejected_ = 0;
};

}  // namespace geaware::sim
