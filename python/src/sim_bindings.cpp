// SPDX-License-Identifier: BSD-3-Clause
// geaware.Sim and geaware.VecSim: the truth side of a flight (experiments::SteppedWorld) stepped
// one control period at a time with throttles from Python (a learning agent, a controller
// written in Python, a sweep), for one vehicle or a batch on threads (vec_sim.hpp). The world is
// set up from the same arguments as geaware.fly; observations are the sensors' latest samples,
// the reference and the TRUE state (for rewards and metrics), as float64 arrays.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "bindings.hpp"
#include "vec_sim.hpp"

namespace geaware::python {
namespace {

const std::set<std::string> kWorldArgs = {
    "vehicle",    "truth",         "trajectory",    "height_m",          "speed_mps",
    "extent_x_m", "extent_y_m",    "laps",          "from_height_m",     "controller",
    "no_turbulence", "controller_params", "start_hover_s"};

/// The flight set-up of geaware.fly from keyword arguments (TypeError for any other name).
experiments::FlightScenario scenarioFrom(const char* who, const std::optional<std::string>& scenario,
                                         std::optional<std::uint64_t> seed, const py::kwargs& kw) {
  FlyArgs a;
  a.scenario = scenario;
  a.seed = seed;
  for (const auto& [key, value] : kw) {
    const auto name = py::cast<std::string>(key);
    if (kWorldArgs.count(name) == 0) {
      std::string known;
      for (const auto& k : kWorldArgs) known += (known.empty() ? "" : ", ") + k;
      throw py::type_error(std::string(who) + ": unexpected argument '" + name + "' (expected " + known + ")");
    }
    if (value.is_none()) continue;
    if (name == "vehicle") a.vehicle = py::cast<std::string>(value);
    if (name == "truth") a.truth = py::cast<std::string>(value);
    if (name == "trajectory") a.trajectory = py::cast<std::string>(value);
    if (name == "controller") a.controller = py::cast<std::string>(value);
    if (name == "controller_params") a.controller_params = py::cast<std::string>(value);
    if (name == "height_m") a.height_m = py::cast<double>(value);
    if (name == "speed_mps") a.speed_mps = py::cast<double>(value);
    if (name == "extent_x_m") a.extent_x_m = py::cast<double>(value);
    if (name == "extent_y_m") a.extent_y_m = py::cast<double>(value);
    if (name == "from_height_m") a.from_height_m = py::cast<double>(value);
    if (name == "start_hover_s") a.start_hover_s = py::cast<double>(value);
    if (name == "laps") a.laps = py::cast<int>(value);
    if (name == "no_turbulence") a.no_turbulence = py::cast<bool>(value);
  }
  // The controller only sets the control rate here (the throttles are the caller's).
  if (!a.scenario && !a.controller) a.controller = "recommended";
  return scenarioOf(a);
}

std::vector<std::uint64_t> seedsFrom(std::size_t n, const py::object& seeds, std::uint64_t first) {
  std::vector<std::uint64_t> out;
  if (seeds.is_none()) {
    for (std::size_t i = 0; i < n; ++i) out.push_back(first + i);
    return out;
  }
  for (const auto& s : seeds) {
    const auto v = py::cast<py::int_>(s);
    if (v < py::int_(0) || v > py::int_(UINT64_MAX)) {
      throw py::value_error("seeds: " + std::string(py::repr(v)) + " is not in [0, 2^64)");
    }
    out.push_back(py::cast<std::uint64_t>(v));
  }
  if (out.size() != n) {
    throw py::value_error("seeds: " + std::to_string(out.size()) + " seeds for " + std::to_string(n) + " vehicles");
  }
  return out;
}

/// The batch's observations as a dict of views into one new (n × width) array (or, for one
/// vehicle alone, views into one row: scalars as floats).
py::dict observations(const WorldBatch& b, bool batch) {
  const auto n = static_cast<py::ssize_t>(b.size());
  const auto width = static_cast<py::ssize_t>(b.obsWidth());
  DoubleArray all = newArray({n, width});
  std::copy(b.observations().begin(), b.observations().end(), all.mutable_data());
  py::dict d;
  py::array_t<bool> done(n), crashed(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    done.mutable_at(i) = b.done(static_cast<std::size_t>(i));
    crashed.mutable_at(i) = b.done(static_cast<std::size_t>(i)) && b.crashed(static_cast<std::size_t>(i));
  }
  for (const ObsField& f : b.fields()) {
    const auto at = static_cast<py::ssize_t>(f.offset);
    const auto w = static_cast<py::ssize_t>(f.width);
    if (batch) {
      d[py::str(f.name)] = f.width == 1 && f.name != "ranger_range_m"
                               ? all[py::make_tuple(py::slice(0, n, 1), at)]
                               : all[py::make_tuple(py::slice(0, n, 1), py::slice(at, at + w, 1))];
    } else if (f.width == 1 && f.name != "ranger_range_m") {
      d[py::str(f.name)] = py::float_(*all.data(0, at));
    } else {
      d[py::str(f.name)] = all[py::make_tuple(0, py::slice(at, at + w, 1))];
    }
  }
  if (batch) {
    d["done"] = done;
    d["crashed"] = crashed;
  } else {
    d["done"] = py::bool_(done.at(0));
    d["crashed"] = py::bool_(crashed.at(0));
  }
  return d;
}

py::dict resultOf(WorldBatch& b, std::size_t i) {
  const experiments::FlightResult r = b.result(i);
  py::dict d;
  d["completed"] = r.completed;
  d["crash"] = r.crash_description;
  d["rmse_all_m"] = r.tracking.rmse_all_m;
  d["rmse_xy_m"] = r.tracking.rmse_xy_m;
  d["rmse_z_m"] = r.tracking.rmse_z_m;
  d["max_m"] = r.tracking.max_m;
  d["samples"] = r.tracking.samples;
  d["control_ticks"] = r.control_ticks;
  d["simulated_s"] = r.simulated_s;
  return d;
}

void checkThrottles(const double* t, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(t[i])) {
      throw py::value_error("throttles: vehicle " + std::to_string(i / 4) + ", motor " +
                            std::to_string(i % 4 + 1) + " is not finite");
    }
  }
}

std::vector<ObsField> fieldsOf(const WorldBatch& b) { return b.fields(); }

/// geaware.Sim: a batch of one, observed without the batch axis.
struct SingleSim {
  std::unique_ptr<WorldBatch> b;
};

const char* kWorldDoc =
    "The world is set up as geaware.fly sets it up: a scenario file, or keyword arguments "
    "vehicle, truth, trajectory ('lemniscate' or 'hover-descent'), height_m, speed_mps, "
    "extent_x_m, extent_y_m, laps, from_height_m, controller (only its control rate is used: "
    "the throttles are yours; default 'recommended'), no_turbulence, controller_params, "
    "start_hover_s. No fault injection, closed loop only. Each step() holds the throttles "
    "(mixer order, [0, 1]; the motors clamp) for one control period (control_period_s) and "
    "returns the observation at the next control tick: the sensors' latest samples (imu_*, "
    "mocap_*, rotor_*, ranger_*; NaN before a sensor's first sample), battery_V, the reference "
    "(ref_*) and the TRUE state (true_*, for rewards and metrics; a controller should not read "
    "it), plus done (the scenario's duration flown, or struck) and crashed. A vehicle that is "
    "done keeps its last observation until reset. fields lists every name with its width and "
    "unit.";

}  // namespace

void bindSim(py::module_& m) {
  py::class_<ObsField>(m, "ObservationField", "One named part of an observation row.")
      .def_readonly("name", &ObsField::name)
      .def_readonly("offset", &ObsField::offset)
      .def_readonly("width", &ObsField::width)
      .def_readonly("doc", &ObsField::doc)
      .def("__repr__", [](const ObsField& f) { return "<" + f.name + " [" + std::to_string(f.width) + "]: " + f.doc + ">"; });

  py::class_<WorldBatch>(m, "VecSim",
                         (std::string("VecSim(n, scenario=None, *, seeds=None, first_seed=None, threads=0, "
                                      "**world): n vehicles in the same world, vehicle i seeded with "
                                      "seeds[i] (default first_seed + i; first_seed defaults to the "
                                      "scenario's seed, else 1), stepped together on `threads` threads "
                                      "(0: every core). Vehicle i of a batch gives exactly what a "
                                      "geaware.Sim with its seed gives, whatever the thread count. ") +
                          kWorldDoc)
                             .c_str())
      .def(py::init([](std::size_t n, const std::optional<std::string>& scenario, const py::object& seeds,
                       std::optional<std::uint64_t> first_seed, int threads, const py::kwargs& kw) {
             if (n < 1 || n > 1000000) throw py::value_error("VecSim: n = " + std::to_string(n) + " (expected 1 to 10^6)");
             if (threads < 0 || threads > 1024) throw py::value_error("VecSim: threads = " + std::to_string(threads) + " (expected 0 to 1024)");
             const experiments::FlightScenario s = scenarioFrom("VecSim", scenario, std::nullopt, kw);
             const std::vector<std::uint64_t> list = seedsFrom(n, seeds, first_seed.value_or(s.seed));
             const int t = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
             return std::make_unique<WorldBatch>(s, list, std::min<int>(t, static_cast<int>(n)));
           }),
           py::arg("n"), py::arg("scenario") = py::none(), py::kw_only(), py::arg("seeds") = py::none(),
           py::arg("first_seed") = py::none(), py::arg("threads") = 0)
      .def("__len__", &WorldBatch::size)
      .def_property_readonly("n", &WorldBatch::size)
      .def_property_readonly("threads", &WorldBatch::threads)
      .def_property_readonly("control_period_s", &WorldBatch::controlPeriod_s, "time per step() [s]")
      .def_property_readonly("fields", &fieldsOf, "the observation's fields (name, offset, width, doc)")
      .def_property_readonly("seeds", [](const WorldBatch& b) {
        std::vector<std::uint64_t> s;
        for (std::size_t i = 0; i < b.size(); ++i) s.push_back(b.seed(i));
        return s;
      })
      .def("observe", [](const WorldBatch& b) { return observations(b, true); },
           "the current observations, as step() returns them")
      .def(
          "reset",
          [](WorldBatch& b, const py::object& seeds, const py::object& which) {
            std::vector<std::size_t> idx;
            if (which.is_none()) {
              for (std::size_t i = 0; i < b.size(); ++i) idx.push_back(i);
            } else {
              for (const auto& i : which) {
                const auto k = py::cast<long long>(i);
                if (k < 0 || static_cast<std::size_t>(k) >= b.size()) {
                  throw py::index_error("reset: vehicle " + std::to_string(k) + " (expected 0 to " + std::to_string(b.size() - 1) + ")");
                }
                idx.push_back(static_cast<std::size_t>(k));
              }
            }
            std::vector<std::uint64_t> s;
            if (seeds.is_none()) {
              for (const std::size_t i : idx) s.push_back(b.seed(i));
            } else {
              s = seedsFrom(idx.size(), seeds, 0);
            }
            for (std::size_t k = 0; k < idx.size(); ++k) b.reset(idx[k], s[k]);
            return observations(b, true);
          },
          py::arg("seeds") = py::none(), py::arg("which") = py::none(),
          "Restarts the vehicles `which` (default: all) at the scenario's start, with `seeds` "
          "(one per vehicle restarted; default: each vehicle's current seed). Returns the "
          "observations.")
      .def(
          "step",
          [](WorldBatch& b, const DoubleArray& throttles) {
            const double* t = expectCount(throttles, static_cast<py::ssize_t>(4 * b.size()), "throttles (n x 4)");
            checkThrottles(t, 4 * b.size());
            {
              const py::gil_scoped_release no_gil;
              b.step(t);
            }
            return observations(b, true);
          },
          py::arg("throttles"),
          "One control period for every vehicle that is not done; throttles: (n, 4) in [0, 1], "
          "mixer order. Returns the observations (dict of (n, …) arrays). The GIL is released "
          "while the vehicles step.")
      .def("result", [](WorldBatch& b, std::size_t i) {
             if (i >= b.size()) throw py::index_error("result: vehicle " + std::to_string(i));
             return resultOf(b, i);
           }, py::arg("i"),
           "Vehicle i's flight so far: completed, crash, tracking RMSE against the reference "
           "over the trajectory [m], control_ticks, simulated_s [s].");

  py::class_<SingleSim>(m, "Sim",
                        (std::string("Sim(scenario=None, *, seed=None, **world): one vehicle, stepped "
                                     "by you (seed: the scenario's, else 1). ") +
                         kWorldDoc)
                            .c_str())
      .def(py::init([](const std::optional<std::string>& scenario, std::optional<std::uint64_t> seed,
                       const py::kwargs& kw) {
             const experiments::FlightScenario s = scenarioFrom("Sim", scenario, seed, kw);
             return SingleSim{std::make_unique<WorldBatch>(s, std::vector<std::uint64_t>{s.seed}, 1)};
           }),
           py::arg("scenario") = py::none(), py::kw_only(), py::arg("seed") = py::none())
      .def_property_readonly("seed", [](const SingleSim& s) { return s.b->seed(0); })
      .def_property_readonly("control_period_s", [](const SingleSim& s) { return s.b->controlPeriod_s(); },
                             "time per step() [s]")
      .def_property_readonly("fields", [](const SingleSim& s) { return fieldsOf(*s.b); },
                             "the observation's fields (name, offset, width, doc)")
      .def_property_readonly("done", [](const SingleSim& s) { return s.b->done(0); })
      .def("observe", [](const SingleSim& s) { return observations(*s.b, false); },
           "the current observation, as step() returns it")
      .def(
          "reset",
          [](SingleSim& s, std::optional<std::uint64_t> seed) {
            s.b->reset(0, seed.value_or(s.b->seed(0)));
            return observations(*s.b, false);
          },
          py::arg("seed") = py::none(),
          "Restarts at the scenario's start (seed: default the current one); returns the observation.")
      .def(
          "step",
          [](SingleSim& s, const DoubleArray& throttle) {
            const double* t = expectCount(throttle, 4, "throttle (4,)");
            checkThrottles(t, 4);
            {
              const py::gil_scoped_release no_gil;
              s.b->step(t);
            }
            return observations(*s.b, false);
          },
          py::arg("throttle"),
          "Holds `throttle` (4 values in [0, 1], mixer order) for one control period; returns "
          "the observation at the next control tick (a dict: scalars as floats, vectors as "
          "arrays).")
      .def("result", [](SingleSim& s) { return resultOf(*s.b, 0); },
           "The flight so far: completed, crash, tracking RMSE against the reference over the "
           "trajectory [m], control_ticks, simulated_s [s].");
}

}  // namespace geaware::python
