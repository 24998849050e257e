// SPDX-License-Identifier: BSD-3-Clause
// geaware.Vehicle (a vehicle file, docs/vehicle-file.md), geaware.Truth (a truth file,
// docs/truth-file.md), the controller-side model functions of the vehicle (ground effect, drag,
// rotor thrust, throttle curve) and geaware.FlatMap (the flat map with ground effect). The
// model functions take a number or an array of any shape and return the same shape.

#include <filesystem>
#include <memory>
#include <string>
#include <utility>

#include "bindings.hpp"
#include "geaware/flatness/flat_map.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/motor.hpp"
#include "geaware/model/vehicle_model.hpp"
#include "geaware/sim/world.hpp"
#include "python_types.hpp"

namespace geaware::python {
namespace {

/// f applied to every element of `x` (a number or an array of any shape): a float for a
/// number, an array of x's shape otherwise.
template <class F>
py::object elementwise(const py::object& x, F f) {
  const auto in = py::cast<DoubleArray>(x);
  DoubleArray out(std::vector<py::ssize_t>(in.shape(), in.shape() + in.ndim()));
  const double* a = in.data();
  double* b = out.mutable_data();
  for (py::ssize_t i = 0; i < in.size(); ++i) b[i] = f(a[i]);
  if (in.ndim() == 0) return py::float_(b[0]);
  return out;
}

/// f (returning an Eigen vector of N) at every element of `x`: shape x.shape + (N,).
template <int N, class F>
DoubleArray elementwiseVector(const py::object& x, F f) {
  const auto in = py::cast<DoubleArray>(x);
  std::vector<py::ssize_t> shape(in.shape(), in.shape() + in.ndim());
  shape.push_back(N);
  DoubleArray out(shape);
  const double* a = in.data();
  double* b = out.mutable_data();
  for (py::ssize_t i = 0; i < in.size(); ++i) {
    const auto v = f(a[i]);
    for (int k = 0; k < N; ++k) b[i * N + k] = v[k];
  }
  return out;
}

DoubleArray fromVector(const std::vector<double>& v) {
  DoubleArray a = newArray({static_cast<py::ssize_t>(v.size())});
  for (std::size_t i = 0; i < v.size(); ++i) a.mutable_data()[i] = v[i];
  return a;
}

DoubleArray fromMatrix3(const Eigen::Matrix3d& m) {
  DoubleArray a = newArray({3, 3});
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a.mutable_data()[r * 3 + c] = m(r, c);
  }
  return a;
}

void bindVehicleParams(py::class_<Vehicle>& c) {
  using P = model::VehicleParams;
  const auto get = [](auto member) {
    return [member](const Vehicle& v) { return v.params().*member; };
  };
  c.def_property_readonly("name", get(&P::name), "free text, e.g. 'paper_quad'")
      .def_property_readonly("mass_kg", get(&P::mass_kg), "total flying mass [kg]")
      .def_property_readonly(
          "inertia_kgm2", [](const Vehicle& v) { return array3(v.params().inertia_kgm2); },
          "principal inertia (Ixx, Iyy, Izz) [kg m^2]")
      .def_property_readonly("diagonal_rotor_distance_m", get(&P::diagonal_rotor_distance_m),
                             "b, distance between diagonal rotor axes [m]")
      .def_property_readonly("propeller_radius_m", get(&P::propeller_radius_m), "[m]")
      .def_property_readonly("min_rotor_plane_height_m", get(&P::min_rotor_plane_height_m),
                             "rotor-plane height on the ground (landing gear) [m]")
      .def_property_readonly(
          "k_T_N_per_rpm2", [](const Vehicle& v) { return v.params().rotor.k_T_N_per_rpm2; },
          "thrust coefficient, T_i = k_T n_i^2 [N/rpm^2]")
      .def_property_readonly(
          "k_TX_N_per_rpm2", [](const Vehicle& v) { return v.params().rotor.k_TX_N_per_rpm2; },
          "roll torque-by-thrust coefficient [N/rpm^2]")
      .def_property_readonly(
          "k_TY_N_per_rpm2", [](const Vehicle& v) { return v.params().rotor.k_TY_N_per_rpm2; },
          "pitch torque-by-thrust coefficient [N/rpm^2]")
      .def_property_readonly(
          "k_I_Nm_per_rpm2", [](const Vehicle& v) { return v.params().rotor.k_I_Nm_per_rpm2; },
          "reaction-torque coefficient, M_i = k_I n_i^2 [N m/rpm^2]")
      .def_property_readonly(
          "J_R_kgm2", [](const Vehicle& v) { return v.params().rotor.J_R_kgm2; },
          "rotor inertia about its axis [kg m^2]")
      .def_property_readonly(
          "throttle_curve_rpm2",
          [](const Vehicle& v) {
            const auto& t = v.params().throttle;
            return array3({t.c2_rpm2, t.c1_rpm2, t.c0_rpm2});
          },
          "(c2, c1, c0) of n^2 = c2 t^2 + c1 t + c0 at the reference voltage [rpm^2]")
      .def_property_readonly(
          "throttle_reference_voltage_V",
          [](const Vehicle& v) { return v.params().throttle.reference_voltage_V; },
          "battery voltage the throttle curve holds at; 0: no voltage dependence [V]")
      .def_property_readonly(
          "g1_m2", [](const Vehicle& v) { return v.params().additional_thrust.g1_m2; },
          "F_G(h) = g2/(h^2 + g1) [m^2]")
      .def_property_readonly(
          "g2_m2", [](const Vehicle& v) { return v.params().additional_thrust.g2_m2; }, "[m^2]")
      .def_property_readonly(
          "g3_m", [](const Vehicle& v) { return v.params().leveling_torque.g3_m; },
          "M_G(h) = scale h/(h^2 + g3 h + g4)^2 [m]")
      .def_property_readonly(
          "g4_m2", [](const Vehicle& v) { return v.params().leveling_torque.g4_m2; }, "[m^2]")
      .def_property_readonly(
          "leveling_scale_m4", [](const Vehicle& v) { return v.params().leveling_torque.scale_m4; },
          "[m^4]")
      .def_property_readonly(
          "drag_heights_m", [](const Vehicle& v) { return fromVector(v.params().drag.heights_m); },
          "heights of the rotor-drag table, increasing [m]")
      .def_property_readonly(
          "drag_d_x_N_per_mps",
          [](const Vehicle& v) { return fromVector(v.params().drag.d_x_N_per_mps); },
          "rotor drag along body x at each height [N/(m/s)]")
      .def_property_readonly(
          "drag_d_y_N_per_mps",
          [](const Vehicle& v) { return fromVector(v.params().drag.d_y_N_per_mps); },
          "rotor drag along body y at each height [N/(m/s)]");
}

void bindModelFunctions(py::class_<Vehicle>& c) {
  c.def(
       "thrust_ratio",
       [](const Vehicle& v, const py::object& h) {
         const auto& ge = v.model().groundEffect();
         return elementwise(h, [&](double x) { return ge.thrustRatio(x); });
       },
       py::arg("h_m"),
       "Additional-thrust ratio F_G(h) = g2/(h^2 + g1) (paper eq. 5) [-] at rotor-plane "
       "height h [m] (a number or an array; clamped up to the landing gear's height).")
      .def(
          "thrust_ratio_slope",
          [](const Vehicle& v, const py::object& h) {
            const auto& ge = v.model().groundEffect();
            return elementwise(h, [&](double x) { return ge.thrustRatioSlope(x); });
          },
          py::arg("h_m"), "dF_G/dh [1/m] at height h [m]; 0 below the landing gear's height.")
      .def(
          "leveling_coefficient",
          [](const Vehicle& v, const py::object& h) {
            const auto& ge = v.model().groundEffect();
            return elementwise(h, [&](double x) { return ge.levelingCoefficient(x); });
          },
          py::arg("h_m"),
          "Leveling coefficient M_G(h) = scale h/(h^2 + g3 h + g4)^2 (paper eq. 13-14) [m]: "
          "leveling torque per newton of thrust per unit sin(tilt), at height h [m].")
      .def(
          "leveling_inertia_increment",
          [](const Vehicle& v, const py::object& h) {
            const auto& ge = v.model().groundEffect();
            return elementwise(h, [&](double x) { return ge.levelingInertiaIncrement(x); });
          },
          py::arg("h_m"),
          "q(h) = m M_G^2/(1 + F_G)^2 (paper eq. 25-26, hover approximation) [kg m^2] at h [m].")
      .def_property_readonly(
          "leveling_peak_height_m",
          [](const Vehicle& v) { return v.model().groundEffect().levelingPeakHeight(); },
          "height of the maximum of M_G [m]")
      .def(
          "hover_speed_rpm",
          [](const Vehicle& v, const py::object& h) {
            return elementwise(h, [&](double x) { return v.model().hoverSpeedRpm(x); });
          },
          py::arg("h_m"),
          "Rotor speed holding a level hover at height h [m], with ground effect: "
          "sqrt(m g/(4 k_T (1 + F_G(h)))) [rpm].")
      .def(
          "drag_coefficients",
          [](const Vehicle& v, const py::object& h) {
            const auto& d = v.model().drag();
            return elementwiseVector<2>(h, [&](double x) { return d.coefficients(x); });
          },
          py::arg("h_m"),
          "Rotor drag (d_x, d_y) [N/(m/s)] at height h [m], linear in the table, held outside: "
          "shape h.shape + (2,).")
      .def(
          "rotor_thrust_N",
          [](const Vehicle& v, const py::object& n) {
            const auto& r = v.params().rotor;
            return elementwise(n, [&](double x) { return model::rotorThrust(r, x); });
          },
          py::arg("n_rpm"), "Thrust of one rotor out of ground effect, k_T n^2 [N], n [rpm].")
      .def(
          "throttle_to_speed_rpm",
          [](const Vehicle& v, const py::object& t) {
            const auto& curve = v.model().throttleCurve();
            return elementwise(t, [&](double x) { return curve.speedRpm(x); });
          },
          py::arg("throttle"),
          "Rotor speed [rpm] at throttle t in [0, 1] (clamped), the ESC curve at its reference "
          "voltage.")
      .def(
          "speed_to_throttle",
          [](const Vehicle& v, const py::object& n) {
            const auto& curve = v.model().throttleCurve();
            return elementwise(n, [&](double x) { return curve.throttle(x); });
          },
          py::arg("n_rpm"),
          "Throttle in [0, 1] giving rotor speed n [rpm] (clamped to the curve's range).")
      .def_property_readonly(
          "speed_range_rpm",
          [](const Vehicle& v) {
            const auto& curve = v.model().throttleCurve();
            return py::make_tuple(curve.minSpeedRpm(), curve.maxSpeedRpm());
          },
          "(n at throttle 0, n at throttle 1) [rpm]");
}

void bindTruth(py::module_& m) {
  py::class_<sim::World>(m, "Truth",
                         "The simulated world of a truth file (docs/truth-file.md): the vehicle "
                         "as built, its sensors and disturbances. Only the simulator flies it; "
                         "the controller never sees it. Load with geaware.load_truth().")
      .def_property_readonly("source", [](const sim::World& w) { return w.source; },
                             "the truth file's path or the built-in's name")
      .def_property_readonly(
          "vehicle", [](const sim::World& w) { return Vehicle(w.vehicle); },
          "the file's vehicle part (the nominal body the truth was built from)")
      .def_property_readonly("mass_kg", [](const sim::World& w) { return w.truth.mass_kg; },
                             "true flying mass [kg]")
      .def_property_readonly(
          "inertia_kgm2", [](const sim::World& w) { return fromMatrix3(w.truth.inertia_kgm2); },
          "true inertia about the centre of mass, body axes, 3x3 [kg m^2]")
      .def_property_readonly(
          "cog_offset_m", [](const sim::World& w) { return array3(w.truth.cog_offset_B); },
          "centre of mass relative to the geometric centre, body frame [m]")
      .def_property_readonly(
          "thrust_multiplier",
          [](const sim::World& w) {
            const auto& t = w.truth.thrust_multiplier;
            return array4({t[0], t[1], t[2], t[3]});
          },
          "per-motor k_T scale, mixer order [-]")
      .def_property_readonly("k_T_N_per_rpm2",
                             [](const sim::World& w) { return w.truth.k_T_N_per_rpm2; },
                             "true thrust coefficient out of ground effect [N/rpm^2]")
      .def_property_readonly(
          "motor_time_constant_s", [](const sim::World& w) { return w.truth.motor.time_constant_s; },
          "first-order rotor-speed time constant [s]")
      .def_property_readonly(
          "motor_dead_time_s", [](const sim::World& w) { return w.truth.motor.dead_time_s; },
          "ESC/link dead time [s]")
      .def_property_readonly("battery_enabled",
                             [](const sim::World& w) { return w.truth.battery.enabled; },
                             "whether the battery sags (else the curve holds exactly)")
      .def_property_readonly("ground_turbulence",
                             [](const sim::World& w) { return w.ground_turbulence; },
                             "near-ground recirculation buffeting on")
      .def_property_readonly("room_air", [](const sim::World& w) { return w.room_air; },
                             "room air (mean and gusts) on")
      .def_property_readonly("varies_per_flight",
                             [](const sim::World& w) { return w.variesPerFlight(); },
                             "whether the truth is perturbed per flight (seeded)")
      .def_property_readonly("team_scale_error_std_kg",
                             [](const sim::World& w) { return w.team_scale_error_std_kg; },
                             "1 sigma of the team's scale reading of the mass [kg]");
  m.def(
      "load_truth",
      [](const std::string& reference) {
        return io::resolveTruth(reference, std::filesystem::current_path());
      },
      py::arg("reference"),
      "A truth file (docs/truth-file.md; any vehicle file is one) or a built-in world "
      "('ideal', 'as_built'; geaware.builtin_truth_names()). ConfigError names the file, line "
      "and key of a malformed file.");
  m.def("builtin_truth_names", &io::builtinTruthNames, "Names of the built-in worlds.");
}

void bindFlatMap(py::module_& m) {
  py::class_<FlatMapHandle>(m, "FlatMap",
                            "The flat map with ground effect (docs/flatness.md): flat outputs and "
                            "rotor-plane height -> thrust, attitude, body rates, torque, rotor "
                            "speeds of the controller's model.")
      .def(py::init<const Vehicle&, bool, bool, bool>(), py::arg("vehicle"),
           py::arg("additional_thrust") = true, py::arg("height_drag") = true,
           py::arg("leveling_inertia") = true,
           "Each ground-effect term can be switched off alone (all off: the plain drag-aware "
           "map with the high-altitude drag).")
      .def("evaluate", &FlatMapHandle::evaluate, py::arg("position_m"), py::arg("velocity_mps"),
           py::arg("accel_mps2"), py::arg("jerk_mps3"), py::arg("snap_mps4"),
           py::arg("yaw_rad"), py::arg("yaw_rate_radps"), py::arg("yaw_accel_radps2"),
           py::arg("height_m"),
           "Evaluates the map at N instants: vectors as arrays of shape (N, 3) or (3,), scalars "
           "as (N,) or numbers; N = 1 when every input is a single instant. Returns a dict of "
           "arrays with N rows: status (0 ok, 1 non-finite input, 2 no thrust, 3 yaw singular), "
           "thrust_N, collective_acc_mps2 ((1 + F_G) T/m), q_wxyz (N, 4; body to world), "
           "w_radps and w_dot_radps2 (body rates and their derivative), torque_Nm (body), "
           "n_sq_rpm2 (N, 4; unclamped), rotor_speeds_rpm (N, 4), feasible (bool: every n^2 "
           "within the throttle curve's range).");
}

}  // namespace

Vehicle::Vehicle(model::VehicleParams params)
    : model_(std::make_shared<const model::VehicleModel>(std::move(params))) {}

FlatMapHandle::FlatMapHandle(const Vehicle& v, bool additional_thrust, bool height_drag,
                             bool leveling_inertia)
    : map_(std::make_shared<const flatness::FlatMap>(
          v.model(), flatness::GroundEffectTerms{additional_thrust, height_drag, leveling_inertia})) {}

void bindVehicle(py::module_& m) {
  py::class_<Vehicle> c(m, "Vehicle",
                        "The controller's vehicle (a vehicle file, docs/vehicle-file.md), "
                        "validated. SI units, rotor speeds in rpm. Load with "
                        "geaware.load_vehicle() or geaware.builtin_vehicle().");
  bindVehicleParams(c);
  bindModelFunctions(c);
  c.def("__repr__", [](const Vehicle& v) {
    return "<geaware.Vehicle '" + v.params().name + "', " + std::to_string(v.params().mass_kg) +
           " kg>";
  });
  m.def(
      "load_vehicle", [](const std::string& file) { return Vehicle(io::loadVehicleFile(file)); },
      py::arg("file"),
      "Reads and validates a vehicle file (YAML, docs/vehicle-file.md); ConfigError names the "
      "file, line and key of any problem.");
  m.def(
      "builtin_vehicle", []() { return Vehicle(io::builtinVehicle()); },
      "The built-in paper quadrotor (config/vehicles/paper_quad.yaml).");
  bindTruth(m);
  bindFlatMap(m);
}

}  // namespace geaware::python
