// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A trajectory gives the flat outputs p…snap and ψ, ψ̇, ψ̈ analytically at any time in
// [0, duration()]. Before 0 and after duration() it rests at its first or last point (all
// derivatives zero); every trajectory here starts and ends at rest, so only snap may jump
// there (minimum-snap ends, see min_snap.hpp).

#include "geaware/traj/flat_output.hpp"

namespace geaware::traj {

class Trajectory {
 public:
  virtual ~Trajectory() = default;

  /// Flat outputs at time t [s].
  [[nodiscard]] virtual FlatOutput sample(double t_s) const noexcept = 0;

  /// Length of the trajectory [s].
  [[nodiscard]] virtual double duration() const noexcept = 0;
};

}  // namespace geaware::traj
