// SPDX-License-Identifier: BSD-3-Clause
// The Neural-Lander baseline's training rows from flight logs (`geaware train-residual`): the
// labels prepareNeuralBaseline builds in the simulator, from a log's own channels.
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "geaware/experiments/neural_baseline.hpp"
#include "geaware/model/rotor_drag.hpp"

namespace geaware::experiments {

std::size_t addLogRows(neural::TrainingSet& set, const ident::FlightLog& log,
                       const model::VehicleParams& vehicle) {
  const std::size_t n = log.size();
  for (const auto* c : {&log.v_W[0], &log.v_W[1], &log.v_W[2], &log.q_WB[0], &log.q_WB[1], &log.q_WB[2],
                        &log.q_WB[3], &log.a_ext_W[0], &log.a_ext_W[1], &log.a_ext_W[2]}) {
    if (c->size() != n) {
      throw std::invalid_argument(log.source + ": training the residual needs the velocity, the attitude and all "
                                  "three components of the external acceleration (a flight log, not a hover log)");
    }
  }
  const Eigen::Vector2d d_high = model::RotorDragModel(vehicle.drag).highAltitudeCoefficients();
  std::size_t added = 0;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Quaterniond q(log.q_WB[0][i], log.q_WB[1][i], log.q_WB[2][i], log.q_WB[3][i]);
    if (!(q.norm() > 0.5)) continue;  // not an attitude (NaN, zeros)
    q.normalize();
    const Eigen::Matrix3d R = q.toRotationMatrix();
    const Eigen::Vector3d v(log.v_W[0][i], log.v_W[1][i], log.v_W[2][i]);
    const Eigen::Vector3d a(log.a_ext_W[0][i], log.a_ext_W[1][i], log.a_ext_W[2][i]);
    const Eigen::Vector3d label = vehicle.mass_kg * a - model::RotorDragModel::force_W(R, v, d_high);
    control::ResidualFeatures f;
    f.height_m = log.h_m[i];
    f.v_W = v;
    f.q_WB = q;
    f.rotor_speeds_rpm = Eigen::Vector4d(log.n_rpm[0][i], log.n_rpm[1][i], log.n_rpm[2][i], log.n_rpm[3][i]);
    added += set.add(f, label) ? 1 : 0;
  }
  return added;
}

double labelMeanSquare(const neural::TrainingSet& set) {
  if (set.size() == 0) return std::nan("");
  double s = 0.0;
  for (const auto& l : set.labels()) s += l.squaredNorm();
  return s / (3.0 * static_cast<double>(set.size()));
}

}  // namespace geaware::experiments
