// SPDX-License-Identifier: BSD-3-Clause
// geaware.fly: one closed-loop flight (experiments::runFlight), set up as `geaware fly` sets it
// up (apps/geaware/fly_command.cpp), returned as a dict of numpy arrays: the flight log's
// columns (experiments/flight_log.hpp, docs/closed-loop.md) in float64, each a view into one
// (ticks × columns) array, plus the controller's reference derivatives the log leaves out. The
// GIL is released while the flight runs; with `out` the CSV log is written too, byte for byte
// what `geaware fly --out` writes after its comment lines.

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_log.hpp"
#include "geaware/experiments/flight_series.hpp"
#include "geaware/experiments/flight_setup.hpp"
#include "geaware/experiments/scenario_file.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/provenance.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/units.hpp"
#include "python_types.hpp"

namespace geaware::python {
namespace {

/// Columns after the log's: what the controller was given and the log does not hold.
const std::vector<std::string> kExtraColumns = {
    "ref_jx_mps3", "ref_jy_mps3",       "ref_jz_mps3",       "ref_sx_mps4",
    "ref_sy_mps4", "ref_sz_mps4",       "ref_yaw_rate_radps", "ref_yaw_accel_radps2"};

/// Every control tick as one row of doubles, in the log's column order (CsvFlightLog::onTick).
class ArrayLog final : public experiments::FlightObserver {
 public:
  ArrayLog(const model::VehicleParams& vehicle, std::size_t expected_ticks)
      : k_T_N_per_rpm2_(vehicle.rotor.k_T_N_per_rpm2), mass_kg_(vehicle.mass_kg) {
    values_.reserve(expected_ticks * columns());
  }
  static std::size_t columns() {
    return experiments::flightLogColumns().size() + kExtraColumns.size();
  }
  std::vector<double>& values() noexcept { return values_; }

  void onTick(const experiments::FlightTick& k) noexcept override {
    const control::ControllerInput& in = k.input;
    const control::ControllerOutput& out = k.output;
    const traj::FlatOutput& ref = in.reference;
    const sim::PlantState& x = k.truth;
    num(k.t_s);
    num(k.t_traj_s);
    num(k.controller_active ? 1 : 0);
    num(k.in_trajectory ? 1 : 0);
    vec(ref.p_W);
    vec(ref.v_W);
    vec(ref.a_W);
    num(ref.yaw_rad);
    vec(in.estimate.p_W);
    vec(in.estimate.v_W);
    quat(in.estimate.q_WB);
    vec(in.gyro_B);
    vec(in.accel_B);
    vec(x.p_W);
    vec(x.v_W);
    quat(x.q_WB);
    vec(x.w_B);
    const Eigen::Vector3d err = ref.p_W - x.p_W;
    vec(err);
    num(err.norm());
    num(k.true_height_m);
    num(in.height_m);
    num(in.height_valid ? 1 : 0);
    num(out.height_used_m);
    vec(out.a_des_W);
    num(out.thrust_des_N);
    quat(out.q_des_WB);
    num(k.attitude_error_rad / model::kDegToRad);
    vec(out.w_des_B);
    vec(out.tau_des_B);
    vec(out.tau_hat_B);
    for (int i = 0; i < 4; ++i) num(out.n_des_rpm(i));
    for (int i = 0; i < 4; ++i) num(in.rotor_speeds_rpm(i));
    for (double n : x.n_rpm) num(n);
    for (double t : k.throttle) num(t);
    num(in.battery_voltage_V);
    num(out.flags);
    const estimation::DisturbanceEstimate& d = k.disturbance;
    num(d.valid ? 1 : 0);
    vec(d.a_ext_W);
    vec(d.tau_ext_B);
    num(d.f_g_valid ? d.f_g_ratio : 0.0);
    vec(out.a_dob_W);
    vec(out.a_int_W);
    num(out.z_cmd_m);
    num(out.guard_min_accel_z_mps2);
    num((out.flags & control::kFlagClearanceGuard) != 0 ? 1 : 0);
    num(in.height_m);
    vec(in.estimate.v_W);
    quat(in.estimate.q_WB);
    const Eigen::Matrix3d R = in.estimate.q_WB.toRotationMatrix();
    const double thrust_N = k_T_N_per_rpm2_ * in.rotor_speeds_rpm.squaredNorm();
    vec(R * in.accel_B - R.col(2) * (thrust_N / mass_kg_));
    for (int i = 0; i < 4; ++i) num(in.rotor_speeds_rpm(i));
    num(k.eskf_flags);
    num(k.fault_bits);
    vec(ref.j_W);
    vec(ref.s_W);
    num(ref.yaw_rate_radps);
    num(ref.yaw_acc_radps2);
  }

 private:
  void num(double v) noexcept { values_.push_back(v); }
  void vec(const Eigen::Vector3d& v) noexcept {
    for (int i = 0; i < 3; ++i) num(v[i]);
  }
  void quat(const Eigen::Quaterniond& q) noexcept {
    num(q.w());
    num(q.x());
    num(q.y());
    num(q.z());
  }

  std::vector<double> values_;
  double k_T_N_per_rpm2_;
  double mass_kg_;
};

}  // namespace

experiments::FlightScenario scenarioOf(const FlyArgs& a) {
  experiments::FlightScenario s;
  std::optional<sim::World> world;
  if (a.truth) world = io::resolveTruth(*a.truth, std::filesystem::current_path());
  if (a.scenario) {
    if (a.vehicle || a.trajectory || a.controller) {
      throw py::value_error("fly: give a scenario file or vehicle/trajectory/controller, not both");
    }
    s = experiments::loadScenarioFile(*a.scenario, world ? &*world : nullptr);
  } else {
    if (!a.trajectory || !std::isfinite(a.height_m) || !a.controller) {
      throw py::value_error("fly: give scenario=FILE, or trajectory=, height_m= and controller=");
    }
    if (*a.trajectory != "lemniscate" && *a.trajectory != "hover-descent") {
      throw py::value_error("fly: trajectory '" + *a.trajectory +
                            "': expected 'lemniscate' or 'hover-descent'");
    }
    if (*a.trajectory == "lemniscate" && !std::isfinite(a.speed_mps)) {
      throw py::value_error("fly: trajectory 'lemniscate' needs speed_mps (peak speed) [m/s]");
    }
    s.vehicle = a.vehicle ? io::loadVehicleFile(*a.vehicle) : io::builtinVehicle();
    experiments::applyWorld(s, world ? *world
                                     : experiments::defaultWorld(s.vehicle, !a.vehicle,
                                                                 a.vehicle.value_or("")));
    if (!control::parseConfiguration(*a.controller, s.controller) ||
        s.controller.acceleration == control::AccelerationCompensation::kNeural) {
      throw py::value_error("fly: controller '" + *a.controller +
                            "': expected 'recommended' or ACC:TORQUE with ACC in "
                            "none|indi|model and TORQUE in none|model|indi|model_indi");
    }
    experiments::TrajectoryOptions t;
    t.lemniscate = *a.trajectory == "lemniscate";
    t.height_m = a.height_m;
    t.speed_mps = a.speed_mps;
    t.extent_x_m = a.extent_x_m;
    t.extent_y_m = a.extent_y_m;
    t.laps = a.laps;
    t.from_height_m = a.from_height_m;
    s.trajectory = experiments::makeTrajectory(t);
    if (a.no_turbulence) s.disturbances.turbulence = false;
  }
  if (a.seed) s.seed = *a.seed;
  if (a.controller_params) s.controller = io::withControllerParamsFile(s.controller, *a.controller_params);
  s.start_hover_s = a.start_hover_s;
  experiments::applyTouchdown(s);  // a scenario file's landing or take-off
  if (s.controller.acceleration == control::AccelerationCompensation::kNeural) {
    throw py::value_error("fly: the Neural-Lander baseline (neural:…) is not available from Python");
  }
  return s;
}

namespace {

/// The arrays as a dict of column views into one (rows × columns) array that owns the values.
py::dict arraysOf(std::vector<double>&& values) {
  const auto ncols = static_cast<py::ssize_t>(ArrayLog::columns());
  const auto rows = static_cast<py::ssize_t>(values.size()) / ncols;
  auto* owned = new std::vector<double>(std::move(values));
  const py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  const DoubleArray all({rows, ncols}, owned->data(), free_when_done);
  py::dict d;
  py::ssize_t j = 0;
  const auto column = [&](const std::string& name) {
    d[py::str(name)] = all[py::make_tuple(py::slice(0, rows, 1), j++)];
  };
  for (const auto name : experiments::flightLogColumns()) column(std::string(name));
  for (const auto& name : kExtraColumns) column(name);
  return d;
}

py::dict fly(const FlyArgs& a) {
  const experiments::FlightScenario s = scenarioOf(a);
  io::OutputChecks files;
  files.input("scenario", a.scenario.value_or(""));
  files.input("vehicle", a.vehicle.value_or(""));
  files.input("controller_params", a.controller_params.value_or(""));
  files.output("out", a.out.value_or(""), false);
  files.check();
  ArrayLog arrays(s.vehicle, experiments::expectedTicks(s));
  experiments::ObserverList observers;
  observers.add(&arrays);
  std::unique_ptr<experiments::CsvFlightLog> log;
  if (a.out) {
    io::RunInfo run;
    run.command_line = "geaware.fly (Python)";
    run.seeds = {s.seed};
    log = std::make_unique<experiments::CsvFlightLog>(*a.out, s.vehicle, io::provenanceComment(run));
    observers.add(log.get());
  }
  experiments::FlightResult r;
  {
    const py::gil_scoped_release no_gil;
    r = experiments::runFlight(s, &observers);
  }
  py::dict d = arraysOf(std::move(arrays.values()));
  d["completed"] = py::bool_(r.completed);
  d["crash"] = py::str(r.crash_description);
  return d;
}

}  // namespace

void bindFlight(py::module_& m) {
  m.def(
      "fly",
      [](const std::optional<std::string>& scenario, const std::optional<std::string>& vehicle,
         const std::optional<std::string>& truth, const std::optional<std::string>& trajectory,
         double height_m, double speed_mps, double extent_x_m, double extent_y_m, int laps,
         double from_height_m, const std::optional<std::string>& controller,
         std::optional<std::uint64_t> seed, bool no_turbulence,
         const std::optional<std::string>& controller_params, double start_hover_s,
         const std::optional<std::string>& out) {
        FlyArgs a{scenario,  vehicle,    truth,      trajectory, controller, controller_params,
                  out,       height_m,   speed_mps,  extent_x_m, extent_y_m, laps,
                  from_height_m, seed,   no_turbulence, start_hover_s};
        return fly(a);
      },
      py::arg("scenario") = py::none(), py::kw_only(), py::arg("vehicle") = py::none(),
      py::arg("truth") = py::none(), py::arg("trajectory") = py::none(),
      py::arg("height_m") = std::nan(""), py::arg("speed_mps") = std::nan(""),
      py::arg("extent_x_m") = 1.5, py::arg("extent_y_m") = 0.8, py::arg("laps") = 1,
      py::arg("from_height_m") = 1.5, py::arg("controller") = py::none(),
      py::arg("seed") = py::none(), py::arg("no_turbulence") = false,
      py::arg("controller_params") = py::none(), py::arg("start_hover_s") = 1.0,
      py::arg("out") = py::none(),
      "One closed-loop flight in the simulator, as `geaware fly` flies it (docs/closed-loop.md): "
      "a scenario file (docs/scenario-file.md), or trajectory ('lemniscate' or "
      "'hover-descent'), height_m (lemniscate height / final descent height, rotor plane above "
      "the ground [m]), speed_mps (lemniscate peak speed / descent rate [m/s]), extent_x_m, "
      "extent_y_m (lemniscate half extents [m]), laps, from_height_m (descent start [m]) and "
      "controller ('recommended' or ACC:TORQUE); vehicle: a vehicle file (default: the built-in "
      "quadrotor); truth: a truth file or built-in world; seed (a scenario file's own by "
      "default, else 1); controller_params: a controller-parameters file; start_hover_s [s]; "
      "out: also write the CSV log there. The same arguments and seed give the same flight as "
      "the command line. Returns a dict: every log column (names with units, as in the CSV "
      "log) as a float64 array with one value per control tick (views into one array), the "
      "reference's jerk, snap, yaw rate and yaw acceleration the controller was given "
      "(ref_jx_mps3 … ref_yaw_accel_radps2), 'completed' (bool) and 'crash' (str, empty when "
      "none). The GIL is released while the flight runs.");
}

}  // namespace geaware::python
