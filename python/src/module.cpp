// SPDX-License-Identifier: BSD-3-Clause
// geaware._geaware: the compiled half of the Python package geaware (python/geaware/,
// docs/python.md). The C++ library's errors arrive as Python exceptions: a malformed file as
// geaware.ConfigError (a ValueError naming the file, line and key), unusable parameters or an
// impossible flight as ValueError, a file that cannot be read or written as RuntimeError.

#include <string>

#include "bindings.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/io/config_error.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::python {

DoubleArray newArray(std::initializer_list<py::ssize_t> shape) {
  return DoubleArray(std::vector<py::ssize_t>(shape));
}

const double* expectCount(const DoubleArray& a, py::ssize_t n, const char* what) {
  if (a.size() != n) {
    throw py::value_error(std::string(what) + ": expected " + std::to_string(n) +
                          " numbers, got an array of " + std::to_string(a.size()));
  }
  return a.data();
}

Eigen::Vector3d vec3(const py::handle& v, const char* what) {
  const auto a = py::cast<DoubleArray>(v);
  const double* d = expectCount(a, 3, what);
  return {d[0], d[1], d[2]};
}

DoubleArray array3(const Eigen::Vector3d& v) {
  DoubleArray a = newArray({3});
  for (int i = 0; i < 3; ++i) a.mutable_data()[i] = v[i];
  return a;
}

DoubleArray array4(const Eigen::Vector4d& v) {
  DoubleArray a = newArray({4});
  for (int i = 0; i < 4; ++i) a.mutable_data()[i] = v[i];
  return a;
}

DoubleArray quatArray(const Eigen::Quaterniond& q) { return array4({q.w(), q.x(), q.y(), q.z()}); }

}  // namespace geaware::python

PYBIND11_MODULE(_geaware, m) {
  namespace py = pybind11;
  m.doc() = "geaware: ground-effect-aware modelling and control of multicopters (C++ core).";
  static py::exception<geaware::io::ConfigError> config_error(m, "ConfigError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const geaware::io::ConfigError& e) {
      config_error(e.what());
    } catch (const geaware::model::InvalidParameters& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const geaware::experiments::InvalidScenario& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  geaware::python::bindVehicle(m);
  geaware::python::bindController(m);
  geaware::python::bindFlight(m);
  geaware::python::bindIdentify(m);
  geaware::python::bindSim(m);
  geaware::python::bindSweep(m);
}
