// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A regular grid of terrain heights: the value type between the height-map file (io/) and the
// simulator's height-map terrain (sim::HeightMap), so that neither depends on the other.

#include <vector>

namespace geaware::model {

/// Node (i, j) sits at (origin_x + i·cell, origin_y + j·cell); heights[j][i] in metres.
struct HeightGrid {
  double origin_x_m = 0.0;
  double origin_y_m = 0.0;
  double cell_m = 0.0;                       ///< node spacing [m]
  std::vector<std::vector<double>> heights;  ///< one row per j, one value per i [m]
};

}  // namespace geaware::model
