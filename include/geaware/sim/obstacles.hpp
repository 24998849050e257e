// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Surfaces around the vehicle besides the ground under it (issue 13 item 4, docs/world.md §10):
// solid boxes at any orientation — a slab overhead is a ceiling, a thin upright box a wall, a
// tilted slab a plane at any angle. The floor stays the Terrain (terrain.hpp) with its ground
// effect; the boxes bring
//   - the ceiling and wall effects on each rotor by the image method
//     (model/proximity_effect.hpp), applied by ProximityContribution: each rotor's distance to
//     each box is measured from its disc centre to the box's nearest point, and the box acts
//     through the mirror image of the rotor's inflow across the face it shows the rotor;
//   - strikes: a rotor-rim point, a landing foot or the body centre inside a box ends the
//     flight (Plant::setObstacles);
//   - returns for the single-beam rangers (BeamRanger) that look up and sideways.
// Boxes do not enter the downward lattice ranger or the ground effect: a table under the
// vehicle is terrain (a step or a height map).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/field_error.hpp"
#include "geaware/model/sensor_data.hpp"
#include "geaware/model/units.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/sampling.hpp"
#include "geaware/sim/terrain.hpp"

namespace geaware::sim {

/// A solid box: centre, half extents along its own axes, and the rotation of its axes to the
/// world (columns: the box's x, y, z axes in world coordinates).
struct Box {
  std::string name;                                           ///< for messages ("ceiling")
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();         ///< [m]
  Eigen::Vector3d half_extent_m = Eigen::Vector3d::Ones();    ///< > 0 each [m]
  Eigen::Matrix3d R_WO = Eigen::Matrix3d::Identity();         ///< box axes → world (rotation)
};

/// Where a point is relative to a box: the distance to its nearest point (0 inside) and the
/// unit normal from that point toward the point (undefined inside).
struct BoxProximity {
  double distance_m = 0.0;
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();
  bool inside = false;
};

/// A box from its lowest and highest corner along the world axes (axis-aligned), with a yaw
/// about its centre's vertical [rad]. Throws std::invalid_argument unless max > min on every
/// axis and all values are finite.
[[nodiscard]] Box boxFromCorners(const Eigen::Vector3d& min_W, const Eigen::Vector3d& max_W,
                                 double yaw_rad = 0.0, std::string name = {});

class Obstacles {
 public:
  Obstacles() = default;
  /// Throws std::invalid_argument naming the box when a half extent is not positive and finite,
  /// the centre is not finite or R_WO is not a rotation (within 1e-9).
  explicit Obstacles(std::vector<Box> boxes);

  [[nodiscard]] const std::vector<Box>& boxes() const noexcept { return boxes_; }
  [[nodiscard]] bool empty() const noexcept { return boxes_.empty(); }

  /// Nearest point of box k to p_W.
  [[nodiscard]] BoxProximity proximity(std::size_t k, const Eigen::Vector3d& p_W) const noexcept;
  /// Index of a box that contains p_W, or nothing.
  [[nodiscard]] std::optional<std::size_t> containing(const Eigen::Vector3d& p_W) const noexcept;
  /// The nearest distance from p_W to any box (∞ without boxes; 0 inside one) [m].
  [[nodiscard]] double clearance(const Eigen::Vector3d& p_W) const noexcept;
  /// First hit of the ray from origin_W along the unit direction within max_range_m (a ray
  /// starting inside a box hits at 0), and the cosine of its incidence (−d·n, 1 head-on).
  struct Hit {
    double distance_m = 0.0;
    double cos_incidence = 1.0;
  };
  [[nodiscard]] std::optional<Hit> rayCast(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W,
                                           double max_range_m) const noexcept;

 private:
  std::vector<Box> boxes_;
  std::vector<Eigen::Matrix3d> R_OW_;  // transposes, for the local frames
};

/// The ceiling and wall effects of the boxes on the four rotors (model/proximity_effect.hpp):
/// per rotor, the image velocities of every box summed, the thrust scaled along the rotor's
/// axis and the side force, both at the rotor's disc centre. Free-air thrust k_T,i·n_i².
class ProximityContribution final : public Contribution {
 public:
  ProximityContribution(const TruthParams& truth, std::shared_ptr<const Obstacles> obstacles);
  [[nodiscard]] const char* name() const noexcept override { return "proximity"; }
  [[nodiscard]] bool readsSurroundings() const noexcept override { return false; }
  [[nodiscard]] Wrench wrench(const ContributionContext& ctx) noexcept override;

 private:
  std::shared_ptr<const Obstacles> obstacles_;
  RotorGeometry geometry_;
};

/// The first strike of a rotor-rim point (one per `rim_unit` vector, rimUnitCircle()), a landing
/// foot or the body centre inside a box, or nothing. `p_W` is the geometric centre.
[[nodiscard]] std::optional<Crash> obstacleStrike(const Obstacles& obstacles, const TruthParams& truth,
                                                  const Eigen::Vector3d& p_W, const Eigen::Matrix3d& R_WB,
                                                  double t_s,
                                                  const std::vector<Eigen::Vector2d>& rim_unit) noexcept;

/// One single-zone time-of-flight ranger looking along a fixed body direction (up at a ceiling,
/// sideways at a wall). Defaults: the same VL53 family as the lattice ranger (ranger.hpp), one
/// zone at 50 Hz, 4 m range, 3 mm + 1 % noise, no return beyond 80° incidence, one outlier per
/// thousand readings, mounted at the geometric centre.
struct BeamRangerParams {
  Eigen::Vector3d direction_B = Eigen::Vector3d::UnitZ();  ///< unit beam direction, body [-]
  Eigen::Vector3d mount_B = Eigen::Vector3d::Zero();       ///< origin rel. the geometric centre, body [m]
  double rate_Hz = 50.0;                                   ///< [Hz]
  double min_range_m = 0.01;                               ///< [m]
  double max_range_m = 4.0;                                ///< [m]
  double max_incidence_rad = 80.0 * model::kDegToRad;  ///< [rad]
  double noise_floor_m = 0.003;                            ///< 1σ [m]
  double noise_fraction = 0.01;                            ///< 1σ per metre [-]
  double outlier_probability = 1.0e-3;                     ///< per reading [-]

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// The default set with obstacles: one beam up (+z_B) and four sideways (±x_B, ±y_B).
[[nodiscard]] std::vector<BeamRangerParams> defaultBeamRangers();

class BeamRanger {
 public:
  /// Throws model::InvalidParameters. Noise stream: (scenario_seed, salt::kBeamRanger + index).
  BeamRanger(const BeamRangerParams& params, std::uint64_t scenario_seed, std::uint64_t index);
  /// A reading when one is due at state.t_s; rays meet the boxes and the terrain (either may
  /// be null). No allocation.
  [[nodiscard]] std::optional<model::BeamReading> sample(const PlantState& state, const Obstacles* obstacles,
                                                         const Terrain* terrain) noexcept;
  [[nodiscard]] const BeamRangerParams& params() const noexcept { return params_; }

 private:
  BeamRangerParams params_;
  NoiseSource noise_;
  SampleClock clock_;
};

}  // namespace geaware::sim
