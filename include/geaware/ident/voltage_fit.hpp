// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The throttle curve's battery-voltage dependence from a stand log with a voltage column
// (issue 11 item 4, issue 12 item 4; the vehicle file's throttle_curve.reference_voltage_V and
// voltage_exponent, model/vehicle_params.hpp):
//   n(t, V)² = (c2·t² + c1·t + c0)·(V/V_ref)^(2p)
// V_ref is a choice (the curve's coefficients are those at V_ref), p and the coefficients are
// fitted: for each p the coefficients are a weighted linear fit (weights 1/n², as the curve
// without voltage), p minimises the residuals (golden section on [0, 4]), and the standard errors
// come from the full Jacobian in (c2, c1, c0, p) at the optimum, σ²·(JᵀWJ)⁻¹.

#include <vector>

#include "geaware/ident/least_squares.hpp"

namespace geaware::ident {

struct ThrottleVoltageFit {
  LeastSquaresFit fit;             ///< x = (c2 [rpm²], c1 [rpm²], c0 [rpm²], p [-])
  double reference_voltage_V = 0;  ///< V_ref the coefficients hold at [V]
};

/// Fits the samples i with use[i] != 0. `reference_voltage_V` ≤ 0: the median voltage of those
/// samples. fit.ok is false (with the reason) for fewer than 8 samples, voltages that vary by
/// less than 2 % (p is then not determined) or a singular design.
[[nodiscard]] ThrottleVoltageFit fitThrottleVoltage(const std::vector<double>& throttle,
                                                    const std::vector<double>& n_rpm,
                                                    const std::vector<double>& voltage_V,
                                                    const std::vector<char>& use,
                                                    double reference_voltage_V = 0.0);

}  // namespace geaware::ident
