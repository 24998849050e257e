// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/flatness/flat_map.hpp"

#include <cmath>

#include "geaware/model/units.hpp"

namespace geaware::flatness {
namespace {

// Below these the construction divides by (nearly) zero; the values are far outside any
// flyable state (a collective acceleration of 1e-6 m/s² is free fall).
constexpr double kMinNorm = 1e-9;
constexpr double kMinCollectiveAcc = 1e-6;

}  // namespace

const char* toString(FlatMapStatus status) noexcept {
  switch (status) {
    case FlatMapStatus::kOk: return "ok";
    case FlatMapStatus::kNonFiniteInput: return "non-finite input";
    case FlatMapStatus::kNoThrust: return "no thrust (free fall or singular rates)";
    case FlatMapStatus::kYawSingular: return "yaw singular (heading parallel to thrust direction)";
  }
  return "unknown";
}

FlatMap::FlatMap(const model::VehicleModel& model, GroundEffectTerms terms)
    : terms_(terms),
      mass_kg_(model.params().mass_kg),
      ground_effect_(model.groundEffect()),
      drag_(model.drag()),
      mixer_(model.mixer()),
      inertia_kgm2_(model.params().inertia_kgm2),
      n_sq_min_rpm2_(model.throttleCurve().minSpeedRpm() * model.throttleCurve().minSpeedRpm()),
      n_sq_max_rpm2_(model.throttleCurve().maxSpeedRpm() * model.throttleCurve().maxSpeedRpm()) {}

namespace {

/// The body axes of the reference (Faessler et al. 2018, eq. 14–16): body x ⊥ α and ⊥ y_C,
/// body y ⊥ β. kOk with the axes in `R`, or why there are none.
FlatMapStatus bodyAxes(const Eigen::Vector3d& alpha, const Eigen::Vector3d& beta,
                       const Eigen::Vector3d& y_C, Eigen::Matrix3d& R) noexcept {
  if (alpha.norm() < kMinCollectiveAcc) return FlatMapStatus::kNoThrust;  // free fall
  Eigen::Vector3d x_B = y_C.cross(alpha);
  const double x_norm = x_B.norm();
  if (x_norm < kMinNorm) return FlatMapStatus::kYawSingular;
  x_B /= x_norm;
  Eigen::Vector3d y_B = beta.cross(x_B);
  const double y_norm = y_B.norm();
  if (y_norm < kMinNorm) return FlatMapStatus::kNoThrust;
  y_B /= y_norm;
  R.col(0) = x_B;
  R.col(1) = y_B;
  R.col(2) = x_B.cross(y_B);
  return FlatMapStatus::kOk;
}

/// The body-rate system A·ω = b (docs/flatness.md): projecting the derivative of the model onto
/// x_B, y_B and differentiating the yaw constraint y_Cᵀx_B = 0 gives
///   [ 0    B1  −C1 ] ω = [ x_Bᵀj + dx·x_Bᵀa      ]
///   [ B2   0    C2 ]     [ −(y_Bᵀj + dy·y_Bᵀa)   ]
///   [ 0   −f    e  ]     [ ψ̇·x_Cᵀx_B             ]
struct RateSystem {
  double xv, yv, zv, ddiff, B1, C1, B2, C2, e, f, den_y;

  RateSystem(const Eigen::Matrix3d& R, const Eigen::Vector3d& y_C, const Eigen::Vector3d& v,
             double c, double dx, double dy) noexcept
      : xv(R.col(0).dot(v)),
        yv(R.col(1).dot(v)),
        zv(R.col(2).dot(v)),
        ddiff(dx - dy),
        B1(c + dx * zv),
        C1(ddiff * yv),
        B2(c + dy * zv),
        C2(ddiff * xv),
        e(y_C.dot(R.col(1))),
        f(y_C.dot(R.col(2))),
        den_y(e * B1 - C1 * f) {}

  /// kOk, or why A is singular.
  [[nodiscard]] FlatMapStatus status() const noexcept {
    if (std::abs(den_y) < kMinNorm || std::abs(e) < kMinNorm || std::abs(B2) < kMinNorm) {
      return std::abs(e) < kMinNorm ? FlatMapStatus::kYawSingular : FlatMapStatus::kNoThrust;
    }
    return FlatMapStatus::kOk;
  }
  /// Elimination for the fixed sparsity of A: row 3 gives ω_z(ω_y), row 1 ω_y, row 2 ω_x.
  [[nodiscard]] Eigen::Vector3d solve(const Eigen::Vector3d& r) const noexcept {
    const double wy = (e * r.x() + C1 * r.z()) / den_y;
    const double wz = (r.z() + f * wy) / e;
    const double wx = (r.y() - C2 * wz) / B2;
    return Eigen::Vector3d(wx, wy, wz);
  }
};

/// Angular acceleration: A·ω = b differentiated once more, A·ω̇ = ḃ − Ȧ·ω, with
/// ẋ_B = ω_z·y_B − ω_y·z_B, ẏ_B = −ω_z·x_B + ω_x·z_B, ż_B = ω_y·x_B − ω_x·y_B,
/// ẋ_C = ψ̇·y_C, ẏ_C = −ψ̇·x_C, and ċ = z_Bᵀj − dx·(x_Bᵀv)·ω_y + dy·(y_Bᵀv)·ω_x.
Eigen::Vector3d angularAcceleration(const traj::FlatOutput& ref, const Eigen::Matrix3d& R,
                                    const Eigen::Vector3d& x_C, const Eigen::Vector3d& y_C,
                                    const RateSystem& A, const Eigen::Vector3d& w, double dx,
                                    double dy) noexcept {
  const Eigen::Vector3d& v = ref.v_W;
  const Eigen::Vector3d& a = ref.a_W;
  const Eigen::Vector3d& j = ref.j_W;
  const Eigen::Vector3d& s = ref.s_W;
  const Eigen::Vector3d x_B = R.col(0);
  const Eigen::Vector3d y_B = R.col(1);
  const Eigen::Vector3d z_B = R.col(2);
  const double xa = x_B.dot(a);
  const double ya = y_B.dot(a);
  const Eigen::Vector3d xd_B = w.z() * y_B - w.y() * z_B;
  const Eigen::Vector3d yd_B = -w.z() * x_B + w.x() * z_B;
  const Eigen::Vector3d zd_B = w.y() * x_B - w.x() * y_B;
  const double psid = ref.yaw_rate_radps;
  const Eigen::Vector3d xd_C = psid * y_C;
  const Eigen::Vector3d yd_C = -psid * x_C;
  const double c_dot = z_B.dot(j) - dx * A.xv * w.y() + dy * A.yv * w.x();
  const double zv_dot = zd_B.dot(v) + z_B.dot(a);
  const double B1_dot = c_dot + dx * zv_dot;
  const double B2_dot = c_dot + dy * zv_dot;
  const double C1_dot = A.ddiff * (yd_B.dot(v) + ya);
  const double C2_dot = A.ddiff * (xd_B.dot(v) + xa);
  const double e_dot = yd_C.dot(y_B) + y_C.dot(yd_B);
  const double f_dot = yd_C.dot(z_B) + y_C.dot(zd_B);
  const Eigen::Vector3d b_dot(
      xd_B.dot(j) + x_B.dot(s) + dx * (xd_B.dot(a) + x_B.dot(j)),
      -(yd_B.dot(j) + y_B.dot(s) + dy * (yd_B.dot(a) + y_B.dot(j))),
      ref.yaw_acc_radps2 * x_C.dot(x_B) + psid * (xd_C.dot(x_B) + x_C.dot(xd_B)));
  const Eigen::Vector3d A_dot_w(B1_dot * w.y() - C1_dot * w.z(), B2_dot * w.x() + C2_dot * w.z(),
                                -f_dot * w.y() + e_dot * w.z());
  return A.solve(b_dot - A_dot_w);
}

}  // namespace

// Steps 1–4 into `out` (default-constructed); evaluate() and evaluateRates() inline it.
inline void FlatMap::rates(const traj::FlatOutput& ref, double height_m, double cos_yaw, double sin_yaw,
                           FlatState& out) const noexcept {
  if (!ref.allFinite() || !std::isfinite(height_m)) {
    out.status = FlatMapStatus::kNonFiniteInput;
    return;
  }
  const Eigen::Vector3d& v = ref.v_W;
  const Eigen::Vector3d& a = ref.a_W;

  // Mass-normalised drag coefficients at this height (or the high-altitude ones).
  const Eigen::Vector2d d = (terms_.height_drag ? drag_.coefficients(height_m)
                                                : drag_.highAltitudeCoefficients()) / mass_kg_;
  const double dx = d.x();
  const double dy = d.y();

  // 1. Attitude.
  const Eigen::Vector3d x_C(cos_yaw, sin_yaw, 0.0);
  const Eigen::Vector3d y_C(-sin_yaw, cos_yaw, 0.0);
  const Eigen::Vector3d acc_g = a + Eigen::Vector3d(0.0, 0.0, model::kGravity);
  out.status = bodyAxes(acc_g + dx * v, acc_g + dy * v, y_C, out.R_WB);
  if (out.status != FlatMapStatus::kOk) return;
  const Eigen::Vector3d x_B = out.R_WB.col(0);
  const Eigen::Vector3d y_B = out.R_WB.col(1);
  const Eigen::Vector3d z_B = out.R_WB.col(2);

  // 2. Collective acceleration c = (1 + F_G)·T/m = z_Bᵀ(a + g·z_W) (the drag terms are ⊥ z_B),
  //    and the thrust (paper eq. 29).
  const double c = z_B.dot(acc_g);
  if (!(c > kMinCollectiveAcc)) {
    out.status = FlatMapStatus::kNoThrust;
    return;
  }
  // The ground effect fades in forward flight (exactly 1 without a fade in the vehicle file).
  const double fade = ground_effect_.forwardFade(v);
  const double ge_gain = terms_.additional_thrust ? 1.0 + fade * ground_effect_.thrustRatio(height_m) : 1.0;
  out.collective_acc_mps2 = c;
  out.thrust_N = mass_kg_ * c / ge_gain;

  // 3. Body rates from A·ω = b.
  const RateSystem A(out.R_WB, y_C, v, c, dx, dy);
  out.status = A.status();
  if (out.status != FlatMapStatus::kOk) return;
  const Eigen::Vector3d b(x_B.dot(ref.j_W) + dx * x_B.dot(a), -(y_B.dot(ref.j_W) + dy * y_B.dot(a)),
                          ref.yaw_rate_radps * x_C.dot(x_B));
  const Eigen::Vector3d w = A.solve(b);
  out.w_B = w;

  // 4. Angular acceleration.
  out.w_dot_B = angularAcceleration(ref, out.R_WB, x_C, y_C, A, w, dx, dy);
}

FlatState FlatMap::evaluateRates(const traj::FlatOutput& ref, double height_m, double cos_yaw,
                                 double sin_yaw) const noexcept {
  FlatState out;
  rates(ref, height_m, cos_yaw, sin_yaw, out);
  return out;
}

FlatState FlatMap::evaluate(const traj::FlatOutput& ref, double height_m) const noexcept {
  FlatState out;
  rates(ref, height_m, std::cos(ref.yaw_rad), std::sin(ref.yaw_rad), out);
  if (!out.ok()) return out;

  // 5. Torque with the leveling torque as an inertia change (paper eq. 30) and rotor speeds
  //    through the inverse mixer (paper eq. 2).
  const Eigen::Vector3d J = terms_.leveling_inertia
                                ? ground_effect_.levelingInertiaDiagonal(height_m, ground_effect_.forwardFade(ref.v_W))
                                : inertia_kgm2_;
  const Eigen::Vector3d& w = out.w_B;
  const Eigen::Vector3d Jw = J.cwiseProduct(w);
  out.tau_B = J.cwiseProduct(out.w_dot_B) + w.cross(Jw);
  out.q_WB = Eigen::Quaterniond(out.R_WB);

  const Eigen::Vector4d wrench(out.thrust_N, out.tau_B.x(), out.tau_B.y(), out.tau_B.z());
  out.n_sq_rpm2 = mixer_.squaredSpeeds(wrench);
  out.rotor_speeds_rpm = out.n_sq_rpm2.cwiseMax(0.0).cwiseSqrt();
  out.rotor_speeds_feasible = (out.n_sq_rpm2.array() >= n_sq_min_rpm2_).all() &&
                              (out.n_sq_rpm2.array() <= n_sq_max_rpm2_).all();
  return out;
}

}  // namespace geaware::flatness
