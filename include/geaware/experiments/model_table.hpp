// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `geaware model`: the controller-side ground-effect model tabulated over heights (F_G, M_G,
// J', drag, hover speed) as a text table, CSV or JSON, with the vehicle's parameters.

#include <string>
#include <vector>

#include "geaware/io/json.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::experiments {

struct ModelRow {
  double h_m, f_g, m_g_m, jx_kgm2, jy_kgm2, d_x_N_per_mps, d_y_N_per_mps, n_hover_rpm;
};

/// One row per rotor-plane height [m].
[[nodiscard]] std::vector<ModelRow> modelRows(const model::VehicleModel& vehicle,
                                              const std::vector<double>& heights_m);

/// The table for a terminal: a title line, the header, one line per row.
[[nodiscard]] std::string formatModelTable(const std::vector<ModelRow>& rows,
                                           const model::VehicleParams& p);
/// CSV: the header h_m,F_G,M_G_m,… and the rows, numbers in their shortest round-trip form.
[[nodiscard]] std::string formatModelCsv(const std::vector<ModelRow>& rows);
/// {"vehicle": name, "rows": [{"h_m", "F_G", …}], "parameters": {key: {"value", "unit"}}}; the
/// parameters come from the vehicle parameter schema (model::forEachParameter).
[[nodiscard]] io::Json modelJson(const std::vector<ModelRow>& rows, const model::VehicleParams& p);

}  // namespace geaware::experiments
