// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Identification as a library (docs/identification.md): one call per kind of log — the
// single-rotor stand, the quadrotor platform, a flight (drag table), a hover descent (F_G in
// flight) and the platform's correlation table — each returning everything a caller shows or
// keeps: the parameters with their standard errors, the fits' residuals, warnings, the vehicle
// update (what gets merged into a vehicle file), the fits themselves, and the curves to plot.
//
// The inputs are the log tables (ident/rig_logs.hpp), read by the caller or built in memory
// (the campaign's calibration); nothing here opens a file or prints. The command line
// (`geaware identify`), the campaign's calibration and the Python module call these.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/ident/fade_fit.hpp"
#include "geaware/ident/fits.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/ident/vehicle_update.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::ident {

/// How F_G and M_G are fitted on the platform.
enum class CurveForm {
  kPaper,  ///< the paper's closed forms g2/(h² + g1) and scale·h/(h² + g3·h + g4)²
  kTable,  ///< values at knot heights (ident/table_fit.hpp)
};

struct IdentifyOptions {
  RobustOptions robust;            ///< loss of every fit (robustLoss("huber") by default)
  int height_bands = 6;            ///< platform: mixing bands; flight: drag bands
  double tilt_limit_deg = 10.0;    ///< platform: largest board tilt for the leveling torque
  CurveForm ground_effect = CurveForm::kPaper;
  double table_top_m = 0.5;        ///< tables: automatic F_G knots up to this height [m]
  std::vector<double> table_heights_m;  ///< tables: explicit knots for both curves (empty: automatic)
  /// rotor, with a voltage column: the voltage the fitted throttle curve holds at; ≤ 0: the
  /// median voltage of the log [V].
  double reference_voltage_V = 0.0;
  /// platform: k_T alone from every level sample as one height band, F_G taken as 0 and not
  /// fitted (a stand at one height or out of ground effect; `--k-T-only`).
  bool k_T_only = false;
};

/// The loss by name: "huber" (default scale), "cauchy" (scale 2.385) or "none"; throws
/// std::invalid_argument for another name.
[[nodiscard]] RobustOptions robustLoss(std::string_view name);

/// One identified value: the vehicle-file key (or a descriptive name), estimate and unit.
struct IdentifiedValue {
  std::string name;
  Estimate estimate;
  std::string unit;
};

/// The residuals of one fit.
struct FitResiduals {
  std::string name;
  FitStats stats;
  std::string unit;
};

/// A curve to plot, as x–y samples (mode "markers", "lines" or "lines+markers"; dash "" or
/// "dash"), and a plot of several.
struct CurveData {
  std::string name;
  std::string mode;
  std::string dash;
  std::vector<double> x;
  std::vector<double> y;
};
struct PlotData {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<CurveData> curves;
};

/// A table of text cells for a report (the parameters, residuals, height bands, correlations).
struct TextTable {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

/// A ground-effect curve fitted as a table, with the names it goes by in the vehicle file.
struct FittedTable {
  std::string section;     ///< below ground_effect: "additional_thrust" or "leveling_torque"
  std::string values_key;  ///< "F_G" or "M_G_m"
  TableCurve curve;
};

/// The fits behind a result (only those of its kind are set).
struct Fits {
  std::optional<RotorFit> rotor;
  std::optional<AdditionalThrustFit> additional_thrust;  ///< platform (paper form) or hover
  std::optional<AdditionalThrustTableFit> additional_thrust_table;
  std::optional<MixingFit> mixing;
  std::optional<LevelingFit> leveling;
  std::optional<LevelingTableFit> leveling_table;
  std::optional<DragFit> drag;
  std::optional<HoverThrustFit> hover_thrust;  ///< hover out of ground effect: k_T alone
  std::optional<ForwardFadeFit> forward_fade;  ///< flight near the ground at several speeds
  std::optional<CorrelationTable> correlations;
};

struct IdentifyResult {
  std::string kind;  ///< "rotor", "platform", "flight", "hover", "correlations"
  std::vector<IdentifiedValue> parameters;
  std::vector<FitResiduals> residuals;
  std::vector<std::string> warnings;
  /// Warnings that block `--out` unless the user accepts them (`--accept-warnings`): a fitted
  /// value outside its physical range (a drag band fitted negative, k_T ≤ 0, g1 or g2 ≤ 0).
  std::vector<std::string> blocking;
  std::vector<std::string> notes;  ///< what the fit decided by itself (e.g. F_G not fitted), said plainly
  io::VehicleUpdate update;  ///< empty for the correlations; provenance left to the caller
  Fits fits;
  std::vector<FittedTable> tables;  ///< platform with CurveForm::kTable: F_G, then M_G
  std::vector<TextTable> report_tables;  ///< parameters, residuals and the kind's own tables
  std::vector<PlotData> plots;
};

/// Single-rotor stand: k_T, k_I, J_R (when the speed steps determine it), the throttle curve.
[[nodiscard]] IdentifyResult identifyRotorStand(const RotorStandLog& log,
                                                const IdentifyOptions& options = {});

/// Quadrotor platform: k_T and F_G (level board), the mixing coefficients (rpm differences),
/// M_G (tilted board, when the log has such samples). `base` gives b, the k_TY prior when the
/// log has no pitch excitation, and the curves drawn for comparison.
[[nodiscard]] IdentifyResult identifyPlatform(const PlatformLog& log,
                                              const model::VehicleParams& base,
                                              const IdentifyOptions& options = {});

/// Flight log: the drag table D(h) per height band (`base` gives the mass).
[[nodiscard]] IdentifyResult identifyFlight(const FlightLog& log, const model::VehicleParams& base,
                                            const IdentifyOptions& options = {});

/// Hover: k_T always, and g1, g2 (eq. 10) only when the logged heights reach below
/// kHoverGroundEffectRadii·base.propeller_radius_m; a hover that never comes that near the ground
/// gives k_T alone (F_G taken as 0) and says so in `notes`. `base` gives the mass, the propeller
/// radius and the k_T the log's external acceleration was computed with.
[[nodiscard]] IdentifyResult identifyHover(const FlightLog& log, const model::VehicleParams& base,
                                           const IdentifyOptions& options = {});

/// Flight near the ground at two or more speeds: the ground effect's forward-flight fade v_i
/// (ident/fade_fit.hpp) against `base`'s F_G(h); --out merges
/// ground_effect.forward_fade.induced_velocity_mps only.
[[nodiscard]] IdentifyResult identifyForwardFade(const FlightLog& log, const model::VehicleParams& base,
                                                 const IdentifyOptions& options = {});

/// The platform log's Spearman rank-correlation table (no parameters, no update).
[[nodiscard]] IdentifyResult identifyCorrelations(const PlatformLog& log,
                                                  const model::VehicleParams& base);

/// The result as text: the correlation matrix (if any), one line per parameter with its
/// standard error and unit, one per fit with its residual RMS, one per note ("note: …";
/// warnings are not included).
[[nodiscard]] std::string resultText(const IdentifyResult& result);

}  // namespace geaware::ident
