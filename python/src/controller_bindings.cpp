// SPDX-License-Identifier: BSD-3-Clause
// geaware.Controller: the paper's controller (control::Controller) with the disturbance observer
// of paper eq. 6 on the same inputs, as the flight runner and the C interface drive it: built
// once from a vehicle (and a controller-parameters file), then one update per control tick with
// numpy arrays in and the throttles out.

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "geaware/control/controller.hpp"
#include "geaware/control/controller_params.hpp"
#include "geaware/estimation/disturbance_observer.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "python_types.hpp"

namespace geaware::python {
namespace {

control::ControllerParams paramsOf(const std::string& configuration,
                                   const std::optional<std::string>& params_file, double rate_hz) {
  control::ControllerParams p;
  if (!control::parseConfiguration(configuration, p) ||
      p.acceleration == control::AccelerationCompensation::kNeural) {
    throw py::value_error("configuration '" + configuration +
                          "': expected 'recommended' or ACC:TORQUE with ACC in none|indi|model "
                          "and TORQUE in none|model|indi|model_indi (neural needs a trained "
                          "network, which geaware.Controller does not take)");
  }
  if (params_file) p = io::withControllerParamsFile(p, *params_file);
  if (rate_hz != 0.0) p.rate_hz = rate_hz;
  return p;
}

estimation::DisturbanceObserverParams observerParamsOf(const control::ControllerParams& c) {
  estimation::DisturbanceObserverParams p;
  p.rate_hz = c.rate_hz;
  p.filter_cutoff_hz = c.filter_cutoff_hz;
  return p;
}

class PyController {
 public:
  PyController(const Vehicle& vehicle, const std::string& configuration,
               const std::optional<std::string>& params_file, double rate_hz)
      : controller_(vehicle.model(), paramsOf(configuration, params_file, rate_hz)),
        observer_(vehicle.model(), observerParamsOf(controller_.params())) {}

  DoubleArray update(double t_s, const py::object& position, const py::object& velocity,
                     const py::object& attitude, const py::object& gyro, const py::object& accel,
                     double height_m, const py::object& rotor_speeds,
                     const py::object& ref_position, const py::object& ref_velocity,
                     const py::object& ref_accel, const py::object& ref_jerk,
                     const py::object& ref_snap, double ref_yaw, double ref_yaw_rate,
                     double ref_yaw_accel, bool height_valid, double battery_voltage_V) {
    control::ControllerInput in;
    in.t_s = t_s;
    in.estimate.p_W = vec3(position, "position_m");
    in.estimate.v_W = vec3(velocity, "velocity_mps");
    const auto q = py::cast<DoubleArray>(attitude);
    const double* qd = expectCount(q, 4, "attitude_wxyz");
    in.estimate.q_WB = Eigen::Quaterniond(qd[0], qd[1], qd[2], qd[3]);
    in.gyro_B = vec3(gyro, "gyro_radps");
    in.accel_B = vec3(accel, "accel_mps2");
    in.height_m = height_m;
    in.height_valid = height_valid;
    const auto n = py::cast<DoubleArray>(rotor_speeds);
    const double* nd = expectCount(n, 4, "rotor_speeds_rpm");
    in.rotor_speeds_rpm = Eigen::Vector4d(nd[0], nd[1], nd[2], nd[3]);
    in.reference.p_W = vec3(ref_position, "ref_position_m");
    in.reference.v_W = vec3(ref_velocity, "ref_velocity_mps");
    in.reference.a_W = vec3(ref_accel, "ref_accel_mps2");
    in.reference.j_W = vec3(ref_jerk, "ref_jerk_mps3");
    in.reference.s_W = vec3(ref_snap, "ref_snap_mps4");
    in.reference.yaw_rad = ref_yaw;
    in.reference.yaw_rate_radps = ref_yaw_rate;
    in.reference.yaw_acc_radps2 = ref_yaw_accel;
    in.battery_voltage_V = battery_voltage_V;
    const estimation::DisturbanceEstimate d = observer_.update(
        {in.t_s, in.gyro_B, in.accel_B, in.rotor_speeds_rpm, in.estimate.q_WB});
    in.external_accel_W = d.a_ext_W;
    in.external_accel_valid = d.valid;
    last_ = controller_.update(in);
    const auto& t = last_.throttle;
    return array4({t[0], t[1], t[2], t[3]});
  }

  [[nodiscard]] py::dict output() const {
    py::dict d;
    const auto& t = last_.throttle;
    d["throttle"] = array4({t[0], t[1], t[2], t[3]});
    d["rotor_speeds_rpm"] = array4(last_.n_des_rpm);
    d["thrust_N"] = last_.thrust_des_N;
    d["torque_Nm"] = array3(last_.tau_des_B);
    d["accel_cmd_mps2"] = array3(last_.a_des_W);
    d["attitude_cmd_wxyz"] = quatArray(last_.q_des_WB);
    d["w_cmd_radps"] = array3(last_.w_des_B);
    d["height_used_m"] = last_.height_used_m;
    d["flags"] = last_.flags;
    return d;
  }

  void reset() noexcept {
    controller_.reset();
    observer_.reset();
    last_ = control::ControllerOutput{};
  }

  [[nodiscard]] double rateHz() const noexcept { return controller_.params().rate_hz; }
  [[nodiscard]] std::string configuration() const {
    return control::configurationName(controller_.params());
  }

 private:
  control::Controller controller_;
  estimation::DisturbanceObserver observer_;
  control::ControllerOutput last_;
};

}  // namespace

void bindController(py::module_& m) {
  py::class_<PyController>(
      m, "Controller",
      "The paper's ground-effect-aware controller (docs/controller.md) with the disturbance "
      "observer (paper eq. 6) on the same inputs, exactly as a simulated flight drives it. "
      "SI units, world z up, quaternions (w, x, y, z) body to world, rotor speeds in rpm, motor "
      "order the mixer's.")
      .def(py::init<const Vehicle&, const std::string&, const std::optional<std::string>&, double>(),
           py::arg("vehicle"), py::arg("configuration") = "recommended",
           py::arg("controller_params_file") = py::none(), py::arg("rate_hz") = 0.0,
           "configuration: 'recommended' (geaware's) or ACC:TORQUE (the paper's rows, e.g. "
           "'model:model_indi'). controller_params_file: a controller-parameters YAML file "
           "(docs/controller-params.md; None: the compiled defaults). rate_hz: the rate update() "
           "is called at (0: the configuration's, 200 Hz by default) [Hz]. Invalid values raise "
           "ValueError, a malformed file geaware.ConfigError.")
      .def("update", &PyController::update, py::arg("t_s"), py::arg("position_m"),
           py::arg("velocity_mps"), py::arg("attitude_wxyz"), py::arg("gyro_radps"),
           py::arg("accel_mps2"), py::arg("height_m"), py::arg("rotor_speeds_rpm"),
           py::arg("ref_position_m"), py::arg("ref_velocity_mps") = py::make_tuple(0, 0, 0),
           py::arg("ref_accel_mps2") = py::make_tuple(0, 0, 0),
           py::arg("ref_jerk_mps3") = py::make_tuple(0, 0, 0),
           py::arg("ref_snap_mps4") = py::make_tuple(0, 0, 0), py::arg("ref_yaw_rad") = 0.0,
           py::arg("ref_yaw_rate_radps") = 0.0, py::arg("ref_yaw_accel_radps2") = 0.0,
           py::arg("height_valid") = true,
           py::arg("battery_voltage_V") = std::numeric_limits<double>::quiet_NaN(),
           "One control step. t_s: time, strictly increasing [s]; the state estimate "
           "(position_m, velocity_mps, attitude_wxyz; never a simulator's truth); the "
           "bias-corrected IMU (gyro_radps, body rates [rad/s]; accel_mps2, specific force, "
           "body [m/s^2]); height_m: rotor-plane height from a ranger [m] (height_valid False: "
           "the last valid one is used); rotor_speeds_rpm: measured (4,) [rpm]; the reference's "
           "flat outputs; battery_voltage_V: measured [V] (NaN: not measured). Returns the four "
           "throttles in [0, 1], always finite (a non-finite input gives a level hover and a "
           "flag; see output()).")
      .def("output", &PyController::output,
           "The last update's commands: throttle, rotor_speeds_rpm [rpm], thrust_N [N], "
           "torque_Nm (body) [N m], accel_cmd_mps2 (world) [m/s^2], attitude_cmd_wxyz, "
           "w_cmd_radps [rad/s], height_used_m [m], flags (control::ControllerFlag bits, "
           "docs/c-api.md).")
      .def("reset", &PyController::reset, "Clears filters and integrators (before a new flight).")
      .def_property_readonly("rate_hz", &PyController::rateHz, "the control rate [Hz]")
      .def_property_readonly("configuration", &PyController::configuration,
                             "'recommended' or ACC:TORQUE");
}

}  // namespace geaware::python
