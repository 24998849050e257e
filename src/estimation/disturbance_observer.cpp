// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/estimation/disturbance_observer.hpp"

#include <cmath>
#include <string>

#include "geaware/model/field_check.hpp"
#include "geaware/model/finite.hpp"
#include "geaware/model/imu_limits.hpp"
#include "geaware/model/units.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::estimation {

std::vector<model::FieldError> DisturbanceObserverParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e);
  c.positive("disturbance_observer.rate_hz", rate_hz);
  if (!(std::isfinite(filter_cutoff_hz) && filter_cutoff_hz > 0.0 &&
        filter_cutoff_hz < 0.5 * rate_hz)) {
    c.fail("disturbance_observer.filter_cutoff_hz", model::formatValue(filter_cutoff_hz),
           "a number in (0, rate_hz/2)");
  }
  c.positive("disturbance_observer.min_thrust_fraction", min_thrust_fraction);
  return e;
}

DisturbanceObserver::DisturbanceObserver(const model::VehicleModel& vehicle,
                                         DisturbanceObserverParams params)
    : params_(model::validated(params)),
      mass_kg_(vehicle.params().mass_kg),
      inertia_kgm2_(vehicle.params().inertia_kgm2),
      mixer_(vehicle.mixer()),
      w_filter_(params_.filter_cutoff_hz, params_.rate_hz),
      tau_filter_(params_.filter_cutoff_hz, params_.rate_hz),
      accel_filter_(params_.filter_cutoff_hz, params_.rate_hz),
      thrust_filter_(params_.filter_cutoff_hz, params_.rate_hz) {}

void DisturbanceObserver::reset() noexcept {
  const auto& p = params_;
  w_filter_ = model::LowPass2<3>(p.filter_cutoff_hz, p.rate_hz);
  tau_filter_ = model::LowPass2<3>(p.filter_cutoff_hz, p.rate_hz);
  accel_filter_ = model::LowPass2<3>(p.filter_cutoff_hz, p.rate_hz);
  thrust_filter_ = model::LowPass2<1>(p.filter_cutoff_hz, p.rate_hz);
  have_prev_ = false;
  last_ = DisturbanceEstimate{};
  status_ = ObserverStatus::kWarmingUp;
  rejected_ = 0;
  time_rejections_ = 0;
}

namespace {

bool estimateFinite(const DisturbanceEstimate& d) noexcept {
  return std::isfinite(d.t_s) && model::allFinite(d.a_ext_W) && model::allFinite(d.a_ext_B) &&
         model::allFinite(d.tau_ext_B) && std::isfinite(d.thrust_f_N) && model::allFinite(d.tau_B_f) &&
         model::allFinite(d.w_f_B) && model::allFinite(d.w_dot_f_B) && std::isfinite(d.f_g_ratio);
}

}  // namespace

DisturbanceEstimate DisturbanceObserver::update(const DisturbanceObserverInput& in) noexcept {
  const double qn = in.q_WB.norm();
  const auto refuse = [this](ObserverStatus status) {
    ++rejected_;
    status_ = status;
    DisturbanceEstimate out = last_;
    out.valid = false;
    return out;
  };
  // IMU values beyond any sensor's range are refused like NaN (model/imu_limits.hpp).
  if (!(std::isfinite(in.t_s) && model::plausibleImu(in.gyro_B, in.accel_B) &&
        model::allFinite(in.rotor_speeds_rpm) && model::allFinite(in.q_WB.coeffs()) && qn > 0.5 && qn < 2.0)) {
    return refuse(ObserverStatus::kNonFinite);
  }
  if (have_prev_ && !(in.t_s > t_prev_)) {
    // A garbage time far ahead would refuse every later sample: after kMaxTimeRejections in a
    // row the observer assumes its own time is wrong and warms up again from this sample.
    if (++time_rejections_ < kMaxTimeRejections) return refuse(ObserverStatus::kTimeNotIncreasing);
    const std::uint64_t rejected = rejected_ + 1;
    reset();
    rejected_ = rejected;
  }
  time_rejections_ = 0;
  // Inputs finite but huge (1e200 rpm) can overflow: such a sample leaves the observer as it was
  // (a copy of fixed-size members, no allocation).
  const DisturbanceObserver saved = *this;
  DisturbanceEstimate out = step(in);
  if (!estimateFinite(out)) {
    *this = saved;
    return refuse(ObserverStatus::kNonFinite);
  }
  return out;
}

DisturbanceEstimate DisturbanceObserver::step(const DisturbanceObserverInput& in) noexcept {

  // 1. Thrust and body torque from the measured rotor speeds through the mixer (paper eq. 2).
  const Eigen::Vector4d wrench = mixer_.wrench(in.rotor_speeds_rpm.cwiseAbs2());

  // 2. The same low-pass on every input.
  const Eigen::Vector3d w_f = w_filter_.update(in.gyro_B);
  const Eigen::Vector3d tau_f = tau_filter_.update(wrench.tail<3>());
  const Eigen::Vector3d f_f = accel_filter_.update(in.accel_B);
  const double thrust_f = thrust_filter_.update(Eigen::Matrix<double, 1, 1>(wrench(0)))(0);
  const Eigen::Quaterniond q = in.q_WB.normalized();
  // This call's filtered inputs become the previous sample of the next one.
  const auto remember = [&] {
    w_prev_ = w_f;
    tau_prev_ = tau_f;
    f_prev_ = f_f;
    thrust_prev_ = thrust_f;
    q_prev_ = q;
    t_prev_ = in.t_s;
  };

  if (!have_prev_) {
    remember();
    have_prev_ = true;
    status_ = ObserverStatus::kWarmingUp;
    last_ = DisturbanceEstimate{};
    last_.t_s = in.t_s;
    return last_;
  }

  // 3. Everything at the middle of the interval, where the difference quotient of ω_f is
  //    second-order accurate.
  const double dt = in.t_s - t_prev_;
  DisturbanceEstimate out;
  out.valid = true;
  out.t_s = in.t_s - 0.5 * dt;
  out.w_f_B = 0.5 * (w_f + w_prev_);
  out.w_dot_f_B = (w_f - w_prev_) / dt;
  out.tau_B_f = 0.5 * (tau_f + tau_prev_);
  out.thrust_f_N = 0.5 * (thrust_f + thrust_prev_);
  const Eigen::Vector3d f_mid = 0.5 * (f_f + f_prev_);
  const Eigen::Quaterniond q_mid = q_prev_.slerp(0.5, q);

  // 4. Paper eq. 6. Force: in the body frame, the specific force minus the rotors' T/m along
  //    z_B; rotated to the world. Torque: Euler's equation with the filtered rates.
  const Eigen::Vector3d& J = inertia_kgm2_;
  out.a_ext_B = f_mid - Eigen::Vector3d::UnitZ() * (out.thrust_f_N / mass_kg_);
  out.a_ext_W = q_mid * out.a_ext_B;
  out.tau_ext_B =
      J.cwiseProduct(out.w_dot_f_B) + out.w_f_B.cross(J.cwiseProduct(out.w_f_B)) - out.tau_B_f;

  // 5. F̃_G = m·z_Wᵀ·ã_ext / T̃ (the paper's hover-descent identification).
  if (out.thrust_f_N > params_.min_thrust_fraction * mass_kg_ * model::kGravity) {
    out.f_g_valid = true;
    out.f_g_ratio = mass_kg_ * out.a_ext_W.z() / out.thrust_f_N;
  }

  remember();
  status_ = ObserverStatus::kOk;
  last_ = out;
  return out;
}

}  // namespace geaware::estimation
