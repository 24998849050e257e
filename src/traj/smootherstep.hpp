// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The smootherstep σ(x) = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷ on x ∈ [0, 1], its integral Σ and its
// derivatives, each in Horner form (SmoothProfile and the touchdown references build on it).
// σ' = 140x³(1 − x)³, so σ', σ'', σ''' vanish at 0 and 1; σ(1 − x) = 1 − σ(x), hence
// Σ(1) = ∫₀¹σ = 1/2.

namespace geaware::traj::detail {

inline double sigmaIntegral(double x) noexcept {  // Σ(x) = 7x⁵ − 14x⁶ + 10x⁷ − 5/2·x⁸
  const double x2 = x * x;
  return x2 * x2 * x * (7.0 + x * (-14.0 + x * (10.0 - 2.5 * x)));
}
inline double sigma(double x) noexcept {
  const double x2 = x * x;
  return x2 * x2 * (35.0 + x * (-84.0 + x * (70.0 - 20.0 * x)));
}
inline double sigmaD1(double x) noexcept {
  const double y = x * (1.0 - x);
  return 140.0 * y * y * y;
}
inline double sigmaD2(double x) noexcept {  // 420x² − 1680x³ + 2100x⁴ − 840x⁵
  return x * x * (420.0 + x * (-1680.0 + x * (2100.0 - 840.0 * x)));
}
inline double sigmaD3(double x) noexcept {  // 840x − 5040x² + 8400x³ − 4200x⁴
  return x * (840.0 + x * (-5040.0 + x * (8400.0 - 4200.0 * x)));
}

}  // namespace geaware::traj::detail
