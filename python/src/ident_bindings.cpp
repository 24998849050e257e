// SPDX-License-Identifier: BSD-3-Clause
// geaware.identify_hover and geaware.identify_flight: identification (ident/identify.hpp) on a
// flight log file (CSV in `geaware identify flight`'s columns, docs/identification.md) or on a
// dict of arrays with the same column names — what geaware.fly returns. The GIL is released
// while the fits run.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "geaware/ident/identify.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "python_types.hpp"

namespace geaware::python {
namespace {

std::vector<double> columnOf(const py::dict& arrays, const std::string& name, py::ssize_t rows) {
  if (!arrays.contains(name)) {
    throw py::value_error("the log has no column '" + name + "'");
  }
  const auto a = py::cast<DoubleArray>(arrays[py::str(name)]);
  if (a.ndim() != 1 || (rows >= 0 && a.size() != rows)) {
    throw py::value_error("column '" + name + "': expected a 1-d array of " +
                          std::to_string(rows) + " values, got " + std::to_string(a.size()));
  }
  return {a.data(), a.data() + a.size()};
}

/// A flight log from arrays: every column of ident::FlightColumns (`hover`: t, h, z of the
/// external acceleration and the rotor speeds only, as readHoverLog reads).
ident::FlightLog logOf(const py::dict& arrays, bool hover) {
  const ident::FlightColumns c;
  ident::FlightLog log;
  log.source = "arrays";
  log.t_s = columnOf(arrays, c.t, -1);
  const auto rows = static_cast<py::ssize_t>(log.t_s.size());
  log.h_m = columnOf(arrays, c.h, rows);
  for (std::size_t i = 0; i < 4; ++i) log.n_rpm[i] = columnOf(arrays, c.n[i], rows);
  if (hover) {
    log.a_ext_W[2] = columnOf(arrays, c.a_ext[2], rows);
    return log;
  }
  for (std::size_t i = 0; i < 3; ++i) {
    log.v_W[i] = columnOf(arrays, c.v[i], rows);
    log.a_ext_W[i] = columnOf(arrays, c.a_ext[i], rows);
  }
  for (std::size_t i = 0; i < 4; ++i) log.q_WB[i] = columnOf(arrays, c.q[i], rows);
  return log;
}

py::dict resultOf(const ident::IdentifyResult& r) {
  py::dict parameters;
  for (const auto& p : r.parameters) {
    py::dict v;
    v["value"] = p.estimate.value;
    v["std_error"] = p.estimate.std_error;
    v["unit"] = p.unit;
    parameters[py::str(p.name)] = v;
  }
  py::dict residuals;
  for (const auto& f : r.residuals) {
    py::dict v;
    v["rms"] = f.stats.residual_rms;
    v["count"] = f.stats.count;
    v["outliers"] = f.stats.outliers;
    v["condition_number"] = f.stats.condition_number;
    v["unit"] = f.unit;
    residuals[py::str(f.name)] = v;
  }
  py::dict d;
  d["kind"] = r.kind;
  d["parameters"] = parameters;
  d["residuals"] = residuals;
  d["warnings"] = r.warnings;
  d["blocking"] = r.blocking;
  d["notes"] = r.notes;
  return d;
}

template <class Identify>
py::dict identify(const py::object& log, const Vehicle& base, const std::string& robust,
                  bool hover, Identify fit) {
  ident::IdentifyOptions options;
  options.robust = ident::robustLoss(robust);
  ident::FlightLog table;
  if (py::isinstance<py::dict>(log)) {
    table = logOf(log.cast<py::dict>(), hover);
  } else {
    const auto file = log.cast<std::string>();
    const py::gil_scoped_release no_gil;
    table = hover ? ident::readHoverLog(file) : ident::readFlightLog(file);
  }
  ident::IdentifyResult r;
  {
    const py::gil_scoped_release no_gil;
    r = fit(table, base.params(), options);
  }
  return resultOf(r);
}

}  // namespace

void bindIdentify(py::module_& m) {
  m.def(
      "identify_hover",
      [](const py::object& log, const Vehicle& base, const std::string& robust) {
        return identify(log, base, robust, true, [](const auto& t, const auto& v, const auto& o) {
          return ident::identifyHover(t, v, o);
        });
      },
      py::arg("log"), py::arg("vehicle"), py::arg("robust") = "huber",
      "k_T, and g1, g2 of F_G(h) = g2/(h^2 + g1) when the heights reach into ground effect "
      "(paper eq. 10), from a hover log: a CSV file (columns t_s, h_m, az_ext_mps2, "
      "n1_rpm..n4_rpm; docs/identification.md) or a dict of arrays with those names (e.g. "
      "what geaware.fly returns, rows of your choice). vehicle gives the mass and the propeller "
      "radius; robust: 'huber', 'cauchy' or 'none'. Returns a dict: kind, parameters {name: "
      "{value, std_error, unit}}, residuals {name: {rms, count, outliers, condition_number, "
      "unit}}, warnings, blocking (values outside their physical range), notes.");
  m.def(
      "identify_flight",
      [](const py::object& log, const Vehicle& base, const std::string& robust) {
        return identify(log, base, robust, false, [](const auto& t, const auto& v, const auto& o) {
          return ident::identifyFlight(t, v, o);
        });
      },
      py::arg("log"), py::arg("vehicle"), py::arg("robust") = "huber",
      "The rotor-drag table D(h) per height band from a flight log: a CSV file or a dict of "
      "arrays with the columns t_s, h_m, vx_mps.., qw.., ax_ext_mps2.., n1_rpm.. "
      "(docs/identification.md). Returns the same dict as identify_hover.");
}

}  // namespace geaware::python
