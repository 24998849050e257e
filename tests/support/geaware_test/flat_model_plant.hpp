// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A small test integrator of the rigid-body model the flat map inverts (paper eq. 27):
//   m·a = −m·g·z_W + (1 + F_G(h))·T·z_B − R·D(h)·Rᵀ·v,   J'(h)·ω̇ = −ω × J'(h)·ω + τ_B,
// with h = p_z (flat ground at z = 0) and each ground-effect term switched like the map's.
// Classic RK4 on (p, v, q, ω) with the quaternion renormalised after every step. It is the
// oracle of the flatness tests only; the real simulator (sim/) has its own, richer physics.

#include <functional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geaware/flatness/flat_map.hpp"
#include "geaware/model/units.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware_test {

struct PlantState {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
};

/// Thrust [N] and body torque [N·m] as functions of time.
struct PlantInput {
  double thrust_N;
  Eigen::Vector3d tau_B;
};

class FlatModelPlant {
 public:
  FlatModelPlant(const geaware::model::VehicleModel& model, geaware::flatness::GroundEffectTerms terms)
      : model_(model), terms_(terms) {}

  /// One RK4 step of length dt from time t; `input(t)` is evaluated at t, t + dt/2 and t + dt.
  void step(PlantState& x, double t, double dt, const std::function<PlantInput(double)>& input) const {
    using Vec13 = Eigen::Matrix<double, 13, 1>;
    const auto pack = [](const PlantState& s) {
      Vec13 y;
      y << s.p, s.v, s.q.w(), s.q.x(), s.q.y(), s.q.z(), s.w;
      return y;
    };
    const auto unpack = [](const Vec13& y) {
      PlantState s;
      s.p = y.segment<3>(0);
      s.v = y.segment<3>(3);
      s.q = Eigen::Quaterniond(y(6), y(7), y(8), y(9));
      s.w = y.segment<3>(10);
      return s;
    };
    const auto f = [&](double ti, const Vec13& y) {
      const PlantState s = unpack(y);
      const PlantInput u = input(ti);
      const Eigen::Quaterniond qn = s.q.normalized();
      const Eigen::Matrix3d R = qn.toRotationMatrix();
      const double h = s.p.z();
      const double m = model_.params().mass_kg;
      const double fg = terms_.additional_thrust ? model_.groundEffect().thrustRatio(h) : 0.0;
      const Eigen::Vector2d d = terms_.height_drag ? model_.drag().coefficients(h)
                                                   : model_.drag().highAltitudeCoefficients();
      const Eigen::Vector3d J = terms_.leveling_inertia ? model_.groundEffect().levelingInertiaDiagonal(h)
                                                        : model_.params().inertia_kgm2;
      const Eigen::Vector3d acc = Eigen::Vector3d(0, 0, -geaware::model::kGravity) +
                                  (1.0 + fg) * u.thrust_N / m * R.col(2) +
                                  geaware::model::RotorDragModel::force_W(R, s.v, d) / m;
      const Eigen::Quaterniond wq(0.0, s.w.x(), s.w.y(), s.w.z());
      const Eigen::Quaterniond qdot = qn * wq;
      const Eigen::Vector3d wdot = (u.tau_B - s.w.cross(J.cwiseProduct(s.w))).cwiseQuotient(J);
      Vec13 dy;
      dy << s.v, acc, 0.5 * qdot.w(), 0.5 * qdot.x(), 0.5 * qdot.y(), 0.5 * qdot.z(), wdot;
      return dy;
    };
    const Vec13 y = pack(x);
    const Vec13 k1 = f(t, y);
    const Vec13 k2 = f(t + 0.5 * dt, y + 0.5 * dt * k1);
    const Vec13 k3 = f(t + 0.5 * dt, y + 0.5 * dt * k2);
    const Vec13 k4 = f(t + dt, y + dt * k3);
    x = unpack(y + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4));
    x.q.normalize();
  }

 private:
  const geaware::model::VehicleModel& model_;
  geaware::flatness::GroundEffectTerms terms_;
};

}  // namespace geaware_test
