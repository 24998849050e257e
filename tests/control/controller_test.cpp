// SPDX-License-Identifier: BSD-3-Clause
// The controller on closed-form cases: hover equilibrium, feedback directions, attitude error,
// incremental-inversion algebra, allocation saturation, and guarded inputs.
#include "geaware/control/controller.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/model/units.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using namespace geaware::control;
using geaware::model::kGravity;
using geaware_test::paperVehicle;

ControllerParams paramsFor(AccelerationCompensation acc, TorqueCompensation torque) {
  ControllerParams p;
  p.acceleration = acc;
  p.torque = torque;
  return p;
}

/// Perfect hover at height h: estimate on the reference, IMU reading gravity, rotor speeds at
/// the hover speed with ground effect.
ControllerInput hoverInput(double h) {
  ControllerInput in;
  in.reference.p_W = Eigen::Vector3d(0.5, 0.5, h);
  in.estimate.p_W = in.reference.p_W;
  in.accel_B = Eigen::Vector3d(0.0, 0.0, kGravity);
  in.height_m = h;
  in.height_valid = true;
  in.rotor_speeds_rpm.setConstant(paperVehicle().hoverSpeedRpm(h));
  return in;
}

const AccelerationCompensation kAllAcc[] = {AccelerationCompensation::kNone, AccelerationCompensation::kIndi,
                                            AccelerationCompensation::kModel};
const TorqueCompensation kAllTorque[] = {TorqueCompensation::kNone, TorqueCompensation::kModel,
                                         TorqueCompensation::kIndi, TorqueCompensation::kModelIndi};

TEST(Controller, HoverIsAnEquilibriumForEveryConfiguration) {
  for (auto acc : kAllAcc) {
    for (auto torque : kAllTorque) {
      Controller c(paperVehicle(), paramsFor(acc, torque));
      // At 2 m the models agree with the measured hover; several ticks let the filters settle.
      ControllerOutput out;
      for (int k = 0; k < 20; ++k) out = c.update(hoverInput(2.0));
      SCOPED_TRACE(std::string(toString(acc)) + "/" + toString(torque));
      EXPECT_EQ(out.flags, kFlagNone);
      EXPECT_MATRIX_NEAR(out.attitude_error, Eigen::Vector3d::Zero(), 1e-12);
      EXPECT_MATRIX_NEAR(out.tau_des_B, Eigen::Vector3d::Zero(), 1e-9);
      EXPECT_NEAR(out.thrust_des_N, paperVehicle().params().mass_kg * kGravity, 0.05);
      const double t_hover = paperVehicle().throttleCurve().throttle(paperVehicle().hoverSpeedRpm(2.0));
      for (double t : out.throttle) EXPECT_NEAR(t, t_hover, 2e-3);
    }
  }
}

TEST(Controller, ModelCompensationTakesTheGroundsThrustOffTheCommand) {
  Controller model(paperVehicle(), paramsFor(AccelerationCompensation::kModel, TorqueCompensation::kNone));
  Controller none(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  const double h = 0.12;
  const auto& ge = paperVehicle().groundEffect();
  const ControllerOutput a = model.update(hoverInput(h));
  const ControllerOutput b = none.update(hoverInput(h));
  const double mg = paperVehicle().params().mass_kg * kGravity;
  // The paper's feed-forward: T = m·g/(1 + F_G(h)) at hover; without it, m·g.
  EXPECT_NEAR(a.thrust_des_N, mg / (1.0 + ge.thrustRatio(h)), 1e-9);
  EXPECT_NEAR(b.thrust_des_N, mg, 1e-9);
  EXPECT_LT(a.n_des_rpm(0), b.n_des_rpm(0));
}

TEST(Controller, PositionAndVelocityErrorsPushTowardsTheReference) {
  Controller c(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  ControllerInput in = hoverInput(2.0);
  in.estimate.p_W.x() -= 0.1;  // behind in x
  in.estimate.v_W.y() = 0.2;   // drifting in +y
  const ControllerOutput out = c.update(in);
  const auto& p = c.params();
  // a_des = K^P·e_p + K^V·e_v (+ zero drag at zero reference velocity).
  EXPECT_MATRIX_NEAR(out.a_des_W, Eigen::Vector3d(p.k_p_per_s2.x() * 0.1, -p.k_v_per_s.y() * 0.2, 0.0), 1e-12);
  // Desired attitude pitches forward (+x acceleration) and rolls towards −y.
  const Eigen::Vector3d z_des = out.q_des_WB.toRotationMatrix().col(2);
  EXPECT_GT(z_des.x(), 0.0);
  EXPECT_LT(z_des.y(), 0.0);
}

TEST(Controller, AttitudeErrorIsTheRotationAngleAndTakesTheShortWay) {
  Controller c(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  // Estimated attitude rolled by 0.3 rad, reference level: error = −0.3 about x (in the body).
  ControllerInput in = hoverInput(2.0);
  in.estimate.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  const ControllerOutput a = c.update(in);
  EXPECT_MATRIX_NEAR(a.attitude_error, Eigen::Vector3d(-0.3, 0.0, 0.0), 1e-9);
  // The same attitude given as −q gives the same error (antipodal quaternions).
  Controller c2(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  in.estimate.q_WB.coeffs() = -in.estimate.q_WB.coeffs();
  EXPECT_MATRIX_NEAR(c2.update(in).attitude_error, a.attitude_error, 1e-12);
  // Yaw error of 170° about z, beyond 90°, stays the shortest rotation.
  Controller c3(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  in = hoverInput(2.0);
  in.reference.yaw_rad = 170.0 * geaware::model::kDegToRad;
  EXPECT_MATRIX_NEAR(c3.update(in).attitude_error, Eigen::Vector3d(0, 0, 170.0 * geaware::model::kDegToRad), 1e-9);
}

TEST(Controller, IncrementalInversionWithMatchingAccelerationKeepsTheMeasuredTorque) {
  // τ = τ̂_B + J'(ω̇_des − ω̇_f): when the body already accelerates as desired the command is
  // the measured torque, whatever J' is (STYLE.md closed form).
  ControllerParams p = paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kModelIndi);
  Controller c(paperVehicle(), p);
  ControllerInput in = hoverInput(0.18);
  // Rotor speeds with a roll-torque difference, held long enough for τ̂ to settle.
  in.rotor_speeds_rpm += Eigen::Vector4d(-100, 100, 100, -100);
  ControllerOutput out;
  for (int k = 0; k < 100; ++k) out = c.update(in);
  const Eigen::Vector3d tau_meas = paperVehicle().mixer().wrench(in.rotor_speeds_rpm.cwiseAbs2()).tail<3>();
  EXPECT_MATRIX_NEAR(out.tau_hat_B, tau_meas, 1e-9);
  // Level, no rates, zero reference: ω̇_des = 0 = ω̇_f, so τ_des = τ̂_B.
  EXPECT_MATRIX_NEAR(out.tau_des_B, tau_meas, 1e-9);
}

TEST(Controller, MeasuredTorqueIncludesTheRotorInertiaReaction) {
  // Rotors 3, 4 (spin +1) speeding up and 1, 2 (spin −1) slowing down at 2000 rpm/s each:
  // J_R·ṅ adds 4·J_R·2000·(2π/60) N·m of yaw torque to k_I·Σs·n².
  Controller c(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kIndi));
  ControllerInput in = hoverInput(2.0);
  const double rate = c.params().rate_hz;
  const Eigen::Vector4d ramp(-2000.0, -2000.0, 2000.0, 2000.0);  // [rpm/s]
  ControllerOutput out;
  for (int k = 0; k < 200; ++k) {
    in.rotor_speeds_rpm = Eigen::Vector4d::Constant(10000.0) + ramp * (k / rate);
    out = c.update(in);
  }
  const auto& r = paperVehicle().params().rotor;
  const double steady = r.k_I_Nm_per_rpm2 * geaware::model::Mixer::yawSigns().dot(in.rotor_speeds_rpm.cwiseAbs2());
  const double inertia = r.J_R_kgm2 * geaware::model::kRpmToRadPerSec * 4.0 * 2000.0;
  // The filter lags a ramp by a constant; compare with the filtered steady part's lag allowed.
  EXPECT_NEAR(out.tau_hat_B.z(), steady + inertia, 0.02 * inertia);
  // Without the compensation only k_I·n² is seen.
  ControllerParams p = paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kIndi);
  p.compensate_rotor_inertia = false;
  Controller plain(paperVehicle(), p);
  for (int k = 0; k < 200; ++k) {
    in.rotor_speeds_rpm = Eigen::Vector4d::Constant(10000.0) + ramp * (k / rate);
    out = plain.update(in);
  }
  EXPECT_NEAR(out.tau_hat_B.z(), steady, 0.02 * inertia);
}

TEST(Controller, YawCommandIsLaggedByTheRotorInertiaTimeConstant) {
  // A constant yaw-torque demand reaches the allocation through 1/(1 + s·τ_R),
  // τ_R = J_R·(2π/60)/(2·k_I·n̄): 63 % after τ_R, all of it in steady state.
  Controller c(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  ControllerInput in = hoverInput(2.0);
  (void)c.update(in);  // start the lag at zero demand
  in.reference.yaw_acc_radps2 = 1.0;  // feed-forward: τ_z = J_z·ψ̈ once the error loop agrees
  const auto& r = paperVehicle().params().rotor;
  const double tau_r = r.J_R_kgm2 * geaware::model::kRpmToRadPerSec /
                       (2.0 * r.k_I_Nm_per_rpm2 * in.rotor_speeds_rpm.mean());
  EXPECT_GT(tau_r, 0.5);  // this vehicle: ≈ 0.85 s, far slower than the 30 ms motors
  const int steps_tau = static_cast<int>(std::lround(tau_r * c.params().rate_hz));
  ControllerOutput out;
  for (int k = 0; k < steps_tau; ++k) out = c.update(in);
  EXPECT_NEAR(out.yaw_torque_allocated_Nm / out.tau_des_B.z(), 1.0 - std::exp(-1.0), 0.03);
  for (int k = 0; k < 10 * steps_tau; ++k) out = c.update(in);
  EXPECT_NEAR(out.yaw_torque_allocated_Nm, out.tau_des_B.z(), 1e-3 * std::abs(out.tau_des_B.z()));
}

TEST(Controller, ModelTorqueUsesTheGroundEffectInertia) {
  ControllerInput in = hoverInput(0.186);
  in.estimate.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()));
  Controller plain(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  Controller model(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kModel));
  const ControllerOutput a = plain.update(in);
  const ControllerOutput b = model.update(in);
  const Eigen::Vector3d Jp = paperVehicle().groundEffect().levelingInertiaDiagonal(0.186);
  const Eigen::Vector3d J = paperVehicle().params().inertia_kgm2;
  // Same ω̇_des, torque scaled by J'x/Jx in roll.
  EXPECT_MATRIX_NEAR(a.w_dot_des_B, b.w_dot_des_B, 1e-12);
  EXPECT_NEAR(b.tau_des_B.x() / a.tau_des_B.x(), Jp.x() / J.x(), 1e-6);
  EXPECT_GT(Jp.x() / J.x(), 1.03);
}

TEST(Controller, AllocationKeepsThrustAndRollPitchBeforeYaw) {
  Controller c(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  ControllerInput in = hoverInput(2.0);
  // A huge yaw error asks for more yaw torque than the rotors can give at hover thrust.
  in.reference.yaw_rad = 3.0;
  in.reference.yaw_rate_radps = 20.0;
  const ControllerOutput out = c.update(in);
  EXPECT_TRUE(out.flags & kFlagYawSaturated);
  EXPECT_FALSE(out.flags & kFlagThrustSaturated);
  const Eigen::Vector4d w = paperVehicle().mixer().wrench(out.n_des_rpm.cwiseAbs2());
  EXPECT_NEAR(w(0), out.thrust_des_N, 1e-6 * out.thrust_des_N);  // thrust kept exactly
  EXPECT_NEAR(w(1), out.tau_des_B.x(), 1e-9);                    // roll kept
  EXPECT_NEAR(w(2), out.tau_des_B.y(), 1e-9);                    // pitch kept
  EXPECT_LT(std::abs(w(3)), std::abs(out.tau_des_B.z()));        // yaw reduced
  EXPECT_GT(w(3) * out.tau_des_B.z(), 0.0);                      // but same sign
  const double n_max = paperVehicle().throttleCurve().maxSpeedRpm();
  const double n_min = paperVehicle().throttleCurve().minSpeedRpm();
  for (int i = 0; i < 4; ++i) {
    EXPECT_LE(out.n_des_rpm(i), n_max + 1e-6);
    EXPECT_GE(out.n_des_rpm(i), n_min - 1e-6);
  }
}

TEST(Controller, ThrustBeyondTheMotorsIsClippedAndFlagged) {
  Controller c(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  ControllerInput in = hoverInput(2.0);
  in.reference.a_W.z() = 4.0 * kGravity;  // 5·m·g > the 62 N the rotors can give
  const ControllerOutput out = c.update(in);
  EXPECT_TRUE(out.flags & kFlagThrustSaturated);
  for (double t : out.throttle) EXPECT_LE(t, 1.0);
}

TEST(Controller, NonFiniteInputsNeverReachTheMotors) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (auto acc : kAllAcc) {
    for (auto torque : kAllTorque) {
      Controller c(paperVehicle(), paramsFor(acc, torque));
      for (int field = 0; field < 6; ++field) {
        ControllerInput in = hoverInput(0.5);
        switch (field) {
          case 0: in.estimate.p_W.x() = nan; break;
          case 1: in.estimate.q_WB.coeffs().setConstant(nan); break;
          case 2: in.gyro_B.y() = nan; break;
          case 3: in.accel_B.z() = std::numeric_limits<double>::infinity(); break;
          case 4: in.rotor_speeds_rpm(2) = nan; break;
          case 5: in.reference.j_W.x() = nan; break;
        }
        const ControllerOutput out = c.update(in);
        EXPECT_TRUE(out.flags & kFlagNonFiniteInput) << "field " << field;
        for (double t : out.throttle) {
          EXPECT_TRUE(std::isfinite(t)) << "field " << field;
          EXPECT_GE(t, 0.0);
          EXPECT_LE(t, 1.0);
        }
        // And the controller is not poisoned: the next good tick is clean.
        const ControllerOutput next = c.update(hoverInput(0.5));
        EXPECT_EQ(next.flags & kFlagNonFiniteInput, 0u);
        for (double t : next.throttle) EXPECT_TRUE(std::isfinite(t));
      }
    }
  }
}

TEST(Controller, GroundEffectIsPredictedAtTheDesiredHeight) {
  // The vehicle is 3 cm below its 0.15 m reference; the ranger reads 0.12 m over ground at z = 0.
  ControllerInput in = hoverInput(0.15);
  in.estimate.p_W.z() = 0.12;
  in.height_m = 0.12;
  Controller ref(paperVehicle(), paramsFor(AccelerationCompensation::kModel, TorqueCompensation::kModel));
  const ControllerOutput a = ref.update(in);
  EXPECT_NEAR(a.height_used_m, 0.15, 1e-12);  // z_ref − (ẑ − h) = 0.15 − 0
  // The same over a 0.5 m table: the ground the ranger sees is used, not z = 0.
  ControllerInput table = in;
  table.reference.p_W.z() += 0.5;
  table.estimate.p_W.z() += 0.5;
  Controller ref2(paperVehicle(), paramsFor(AccelerationCompensation::kModel, TorqueCompensation::kModel));
  EXPECT_NEAR(ref2.update(table).height_used_m, 0.15, 1e-12);
  // The measured-height variant uses the ranger's 0.12 m, so F_G — and the thrust cut — is larger.
  ControllerParams p = paramsFor(AccelerationCompensation::kModel, TorqueCompensation::kModel);
  p.ground_effect_height = GroundEffectHeight::kMeasured;
  Controller meas(paperVehicle(), p);
  const ControllerOutput b = meas.update(in);
  EXPECT_NEAR(b.height_used_m, 0.12, 1e-12);
  EXPECT_GT(paperVehicle().groundEffect().thrustRatio(b.height_used_m),
            paperVehicle().groundEffect().thrustRatio(a.height_used_m));
}

TEST(Controller, MissingHeightKeepsTheLastValidOneAndIsFlagged) {
  Controller c(paperVehicle(), paramsFor(AccelerationCompensation::kModel, TorqueCompensation::kModelIndi));
  (void)c.update(hoverInput(0.15));
  for (double bad : {-1.0, std::nan("")}) {
    ControllerInput in = hoverInput(0.15);
    in.height_m = bad;
    const ControllerOutput out = c.update(in);
    EXPECT_TRUE(out.flags & kFlagHeightInvalid);
    EXPECT_DOUBLE_EQ(out.height_used_m, 0.15);
    for (double t : out.throttle) EXPECT_TRUE(std::isfinite(t));
  }
  ControllerInput in = hoverInput(0.15);
  in.height_valid = false;
  EXPECT_TRUE(c.update(in).flags & kFlagHeightInvalid);
  // Before any valid height the models assume flight far from the ground.
  Controller fresh(paperVehicle(), paramsFor(AccelerationCompensation::kModel, TorqueCompensation::kModel));
  in.height_valid = false;
  const ControllerOutput out = fresh.update(in);
  EXPECT_NEAR(out.thrust_des_N, paperVehicle().params().mass_kg * kGravity, 1e-3);
}

TEST(Controller, ThrottleCorrectionClosesTheThrustGap) {
  // Motors turning slower than commanded (a weak battery): the shared PI raises every throttle.
  Controller c(paperVehicle(), paramsFor(AccelerationCompensation::kNone, TorqueCompensation::kNone));
  ControllerInput in = hoverInput(2.0);
  const ControllerOutput first = c.update(in);
  in.rotor_speeds_rpm *= 0.97;
  ControllerOutput later;
  for (int k = 0; k < 200; ++k) later = c.update(in);
  for (int i = 0; i < 4; ++i) EXPECT_GT(later.throttle[i], first.throttle[i]);
  // Bounded by thrust_pi_limit.
  EXPECT_LE(later.throttle[0] - first.throttle[0], c.params().thrust_pi_limit + 1e-12);
}

TEST(Controller, NeuralNeedsAModelAndUsesItsPrediction) {
  ControllerParams p = paramsFor(AccelerationCompensation::kNeural, TorqueCompensation::kNone);
  EXPECT_THROW(Controller(paperVehicle(), p), std::invalid_argument);
  struct ConstantUp final : ResidualForceModel {
    Eigen::Vector3d predict_W(const ResidualFeatures&) const noexcept override { return {0.0, 0.0, 2.0}; }
  };
  Controller c(paperVehicle(), p, std::make_shared<ConstantUp>());
  // A predicted 2 N of upward residual force is taken off the thrust command.
  EXPECT_NEAR(c.update(hoverInput(2.0)).thrust_des_N, paperVehicle().params().mass_kg * kGravity - 2.0, 1e-9);
}

TEST(ControllerParams, ValidationNamesTheField) {
  ControllerParams p;
  p.filter_cutoff_hz = 150.0;  // above Nyquist at 200 Hz
  p.k_p_per_s2.y() = -1.0;
  const auto errors = p.validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].field, "k_p_per_s2.y");
  EXPECT_EQ(errors[1].field, "filter_cutoff_hz");
  EXPECT_THROW(Controller(paperVehicle(), p), geaware::model::InvalidParameters);
  AccelerationCompensation a{};
  EXPECT_TRUE(parse("indi", a));
  EXPECT_EQ(a, AccelerationCompensation::kIndi);
  EXPECT_FALSE(parse("pid", a));
  TorqueCompensation t{};
  EXPECT_TRUE(parse("model_indi", t));
  EXPECT_EQ(t, TorqueCompensation::kModelIndi);
}

}  // namespace

namespace {

/// 200 ticks of a hover 2 cm low at 0.3 m, every output throttle collected.
std::vector<double> throttlesOf(const geaware::model::VehicleModel& vehicle, double voltage_V) {
  Controller c(vehicle, paramsFor(AccelerationCompensation::kModel, TorqueCompensation::kModelIndi));
  ControllerInput in = hoverInput(0.3);
  in.estimate.p_W.z() = 0.28;
  in.battery_voltage_V = voltage_V;
  std::vector<double> out;
  for (int k = 0; k < 200; ++k) {
    const ControllerOutput y = c.update(in);
    out.insert(out.end(), y.throttle.begin(), y.throttle.end());
    in.rotor_speeds_rpm = y.n_des_rpm;
  }
  return out;
}

TEST(Controller, BatteryVoltageIsUsedOnlyWithTheVehiclesVoltageDependence) {
  const auto none = throttlesOf(paperVehicle(), std::nan(""));
  // The paper's vehicle file has no voltage dependence: any reading changes nothing.
  EXPECT_EQ(throttlesOf(paperVehicle(), 13.9), none);
  auto p = paperVehicle().params();
  p.throttle.reference_voltage_V = 16.0;
  p.throttle.voltage_exponent = 1.0;
  const geaware::model::VehicleModel with(p);
  // With it: at the reference voltage or without a reading, the same throttles bit for bit.
  EXPECT_EQ(throttlesOf(with, 16.0), none);
  EXPECT_EQ(throttlesOf(with, std::nan("")), none);
  // At 14 V every throttle is higher: the same speeds need more of it.
  const auto low = throttlesOf(with, 14.0);
  for (std::size_t i = 0; i < low.size(); ++i) ASSERT_GT(low[i], none[i]) << i;
}

}  // namespace
