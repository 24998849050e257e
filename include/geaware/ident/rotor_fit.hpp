// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Single-rotor stand identification (paper, supplementary section 3; eq. 6):
//   thrust  T = k_T·n²                          linear least squares → k_T
//   torque  M = k_I·n² + J_R·ṅ                  linear least squares → k_I, J_R
//   ESC     n² = c2·t² + c1·t + c0              linear least squares → throttle curve
//           × (V/V_ref)^(2p) with a voltage column (ident/voltage_fit.hpp)
// with n in rpm, ṅ in rpm/s (J_R in kg·m², so ṅ is converted to rad/s² as in model/motor.hpp).
// ṅ comes from the time series, by a local linear regression of n over ±rate_window_s/2.

#include <optional>
#include <string>
#include <vector>

#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/rig_logs.hpp"

namespace geaware::ident {

enum class RotorInertiaTerm {
  kAuto,    ///< fit J_R; leave it out (with a warning) when the log does not determine it
  kAlways,
  kNever,
};

struct RotorFitOptions {
  RobustOptions robust;
  RotorInertiaTerm rotor_inertia = RotorInertiaTerm::kAuto;
  double rate_window_s = 0.02;  ///< width of the window ṅ is estimated on [s]
  /// The throttle curve is a steady-state map: samples whose speed changes faster than this
  /// are left out of its fit (+inf keeps all) [rpm/s].
  double throttle_max_rate_rpm_per_s = 2000.0;
  /// With a voltage column: the battery voltage the fitted curve holds at; ≤ 0: the median
  /// voltage of the steady samples [V].
  double reference_voltage_V = 0.0;
};

struct RotorFit {
  Estimate k_T_N_per_rpm2;                  ///< thrust coefficient
  FitStats thrust;                          ///< residuals in N
  Estimate k_I_Nm_per_rpm2;                 ///< reaction-torque coefficient
  std::optional<Estimate> J_R_kgm2;         ///< rotor inertia, when fitted
  FitStats torque;                          ///< residuals in N·m
  Estimate c2_rpm2, c1_rpm2, c0_rpm2;       ///< throttle curve
  FitStats throttle;                        ///< residuals in rpm² (weighted by 1/n², see .cpp)
  /// With a voltage column (ident/voltage_fit.hpp): the curve's reference voltage and the
  /// exponent p of n ∝ (V/V_ref)^p; c2, c1, c0 are then the curve at that voltage.
  std::optional<double> reference_voltage_V;
  std::optional<Estimate> voltage_exponent;
  std::vector<std::string> warnings;        ///< problems that did not stop the fit
  /// Problems that block `--out` unless accepted: the voltage exponent at a bound of [0, 4].
  std::vector<std::string> blocking;
};

/// Fits the stand log. Throws IdentError when k_T, k_I or the throttle curve cannot be fitted.
[[nodiscard]] RotorFit fitRotorStand(const RotorStandLog& log, const RotorFitOptions& options = {});

/// ṅ at every sample by a local linear regression of n(t) on the samples within ±window/2
/// (at least one neighbour each side where there is one) [rpm/s].
[[nodiscard]] std::vector<double> rotorAcceleration(const std::vector<double>& t_s,
                                                    const std::vector<double>& n_rpm,
                                                    double window_s);

}  // namespace geaware::ident
