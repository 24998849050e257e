// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The parts of the Python module geaware._geaware (docs/python.md), one function per source
// file, called in order by module.cpp; and the conversions they share.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // std::optional, std::string and std::vector arguments and results

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "geaware/experiments/flight.hpp"

namespace geaware::python {

namespace py = pybind11;

/// A C-contiguous float64 array (any array-like converted, ints and float32 included).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// vehicle and truth files, the model functions, the flat map (vehicle_bindings.cpp).
void bindVehicle(py::module_& m);
/// The controller (controller_bindings.cpp).
void bindController(py::module_& m);
/// A whole flight (flight_bindings.cpp).
void bindFlight(py::module_& m);
/// Identification on arrays or log files (ident_bindings.cpp).
void bindIdentify(py::module_& m);
/// The stepped simulator, one vehicle or a batch (sim_bindings.cpp).
void bindSim(py::module_& m);

/// The arguments of geaware.fly that set up a flight (the stepped simulators take them too).
struct FlyArgs {
  std::optional<std::string> scenario, vehicle, truth, trajectory, controller, controller_params,
      out;
  double height_m = std::nan(""), speed_mps = std::nan(""), extent_x_m = 1.5, extent_y_m = 0.8;
  int laps = 1;
  double from_height_m = 1.5;
  std::optional<std::uint64_t> seed;
  bool no_turbulence = false;
  double start_hover_s = 1.0;
};

/// The scenario `geaware fly` would fly with these arguments (flight_bindings.cpp); ValueError
/// or geaware.ConfigError naming what is wrong.
experiments::FlightScenario scenarioOf(const FlyArgs& a);
/// Sweeps: keys, one key's flight, the results directory (sweep_bindings.cpp).
void bindSweep(py::module_& m);

/// A new float64 array of the given shape.
DoubleArray newArray(std::initializer_list<py::ssize_t> shape);

/// `a` as exactly `n` numbers (any shape with n elements); ValueError naming `what` otherwise.
const double* expectCount(const DoubleArray& a, py::ssize_t n, const char* what);

/// A 3-vector from an array-like of 3 numbers (ValueError naming `what` otherwise).
Eigen::Vector3d vec3(const py::handle& v, const char* what);
/// A float64 array of 3 / 4 numbers.
DoubleArray array3(const Eigen::Vector3d& v);
DoubleArray array4(const Eigen::Vector4d& v);
/// A quaternion as (w, x, y, z).
DoubleArray quatArray(const Eigen::Quaterniond& q);

}  // namespace geaware::python
