// SPDX-License-Identifier: BSD-3-Clause
// The C interface (include/geaware/c_api.h, docs/c-api.md): a thin shell over control::Controller
// and estimation::DisturbanceObserver. Every exception stops here; update() is noexcept and
// allocation-free like the controller it calls.
#include "geaware/c_api.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <string>

#include "geaware/control/controller.hpp"
#include "geaware/control/controller_schema.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "geaware/estimation/disturbance_observer.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_model.hpp"

#ifndef GEAWARE_C_API_VERSION
#error "GEAWARE_C_API_VERSION must be the project version (src/c_api/CMakeLists.txt)"
#endif

struct geaware_controller {
  geaware_controller(const geaware::model::VehicleModel& vehicle,
                     const geaware::control::ControllerParams& params,
                     const geaware::estimation::DisturbanceObserverParams& observer_params)
      : controller(vehicle, params), observer(vehicle, observer_params) {}
  geaware::control::Controller controller;
  geaware::estimation::DisturbanceObserver observer;
};

namespace {

using namespace geaware;

void say(char* message, std::size_t size, const std::string& text) noexcept {
  if (message == nullptr || size == 0) return;
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(message, text.data(), n);
  message[n] = '\0';
}

Eigen::Vector3d vec3(const double* v) { return {v[0], v[1], v[2]}; }

void put3(const Eigen::Vector3d& v, double* out) noexcept {
  for (int i = 0; i < 3; ++i) out[i] = v[i];
}

void putQuat(const Eigen::Quaterniond& q, double* out) noexcept {
  out[0] = q.w();
  out[1] = q.x();
  out[2] = q.y();
  out[3] = q.z();
}

model::VehicleParams toParams(const geaware_vehicle& v) {
  model::VehicleParams p;
  p.name = "C API vehicle";
  p.mass_kg = v.mass_kg;
  p.inertia_kgm2 = vec3(v.inertia_kgm2);
  p.diagonal_rotor_distance_m = v.diagonal_rotor_distance_m;
  p.propeller_radius_m = v.propeller_radius_m;
  p.min_rotor_plane_height_m = v.min_rotor_plane_height_m;
  p.rotor = {v.k_T_N_per_rpm2, v.k_TX_N_per_rpm2, v.k_TY_N_per_rpm2, v.k_I_Nm_per_rpm2,
             v.J_R_kgm2};
  p.throttle = {v.throttle_c2_rpm2, v.throttle_c1_rpm2, v.throttle_c0_rpm2,
                v.throttle_reference_voltage_V, v.throttle_voltage_exponent};
  p.additional_thrust.g1_m2 = v.g1_m2;
  p.additional_thrust.g2_m2 = v.g2_m2;
  p.leveling_torque.g3_m = v.g3_m;
  p.leveling_torque.g4_m2 = v.g4_m2;
  p.leveling_torque.scale_m4 = v.leveling_scale_m4;
  if (v.drag_rows < 1 || v.drag_rows > GEAWARE_MAX_DRAG_ROWS) {
    throw model::InvalidParameters({{"drag_rows", std::to_string(v.drag_rows),
                                     "1 to " + std::to_string(GEAWARE_MAX_DRAG_ROWS)}});
  }
  for (int i = 0; i < v.drag_rows; ++i) {
    p.drag.heights_m.push_back(v.drag_heights_m[i]);
    p.drag.d_x_N_per_mps.push_back(v.drag_d_x_N_per_mps[i]);
    p.drag.d_y_N_per_mps.push_back(v.drag_d_y_N_per_mps[i]);
  }
  return p;
}

/// Builds the controller; throws what the parts throw, tagged with the status to return.
struct Failure {
  geaware_status status;
  std::string message;
};

geaware_controller* build(const model::VehicleParams& vehicle, const char* configuration,
                          double rate_hz, const control::ControllerParams* values = nullptr) {
  if (const auto errors = vehicle.validate(); !errors.empty()) {
    throw Failure{GEAWARE_ERROR_INVALID_VEHICLE,
                  model::describeErrors("geaware: the vehicle is not usable:", errors)};
  }
  control::ControllerParams params = control::recommendedControllerParams();
  const std::string name = configuration == nullptr ? "recommended" : configuration;
  if (!control::parseConfiguration(name, params) ||
      params.acceleration == control::AccelerationCompensation::kNeural) {
    throw Failure{GEAWARE_ERROR_INVALID_CONFIGURATION,
                  "geaware: configuration '" + name +
                      "': expected 'recommended' or ACC:TORQUE with ACC in none|indi|model and "
                      "TORQUE in none|model|indi|model_indi (neural needs a trained network, "
                      "which the C interface does not take)"};
  }
  if (values != nullptr) params = control::applyParameters(params, *values);
  if (rate_hz != 0.0) params.rate_hz = rate_hz;
  if (const auto errors = params.validate(); !errors.empty()) {
    throw Failure{GEAWARE_ERROR_INVALID_CONFIGURATION,
                  model::describeErrors("geaware: the controller parameters are not usable:",
                                        errors)};
  }
  estimation::DisturbanceObserverParams observer;
  observer.rate_hz = params.rate_hz;
  observer.filter_cutoff_hz = params.filter_cutoff_hz;
  const model::VehicleModel model(vehicle);
  return new geaware_controller(model, params, observer);
}

/// The vehicle file, or the built-in vehicle for NULL; a file problem is GEAWARE_ERROR_FILE.
model::VehicleParams loadVehicle(const char* file) {
  try {
    return file == nullptr ? io::builtinVehicle() : io::loadVehicleFile(file);
  } catch (const std::exception& e) {
    throw Failure{GEAWARE_ERROR_FILE, e.what()};
  }
}

geaware_status create(const model::VehicleParams* vehicle, const char* file,
                      const char* configuration, double rate_hz, geaware_controller** out,
                      char* message, std::size_t size,
                      const char* params_file = nullptr) noexcept {
  if (out == nullptr) {
    say(message, size, "geaware: the controller pointer is NULL");
    return GEAWARE_ERROR_NULL_ARGUMENT;
  }
  *out = nullptr;
  try {
    std::optional<control::ControllerParams> values;
    if (params_file != nullptr) {
      try {
        values = io::loadControllerParamsFile(params_file);
      } catch (const std::exception& e) {
        throw Failure{GEAWARE_ERROR_FILE, e.what()};
      }
    }
    const control::ControllerParams* v = values ? &*values : nullptr;
    if (vehicle != nullptr) {
      *out = build(*vehicle, configuration, rate_hz, v);
    } else {
      *out = build(loadVehicle(file), configuration, rate_hz, v);
    }
    say(message, size, "");
    return GEAWARE_OK;
  } catch (const Failure& f) {
    say(message, size, f.message);
    return f.status;
  } catch (const model::InvalidParameters& e) {
    say(message, size, e.what());
    return GEAWARE_ERROR_INVALID_VEHICLE;
  } catch (const std::bad_alloc&) {
    say(message, size, "geaware: out of memory");
    return GEAWARE_ERROR_INTERNAL;
  } catch (const std::exception& e) {
    say(message, size, e.what());
    return GEAWARE_ERROR_INTERNAL;
  }
}

}  // namespace

extern "C" {

const char* geaware_version(void) { return GEAWARE_C_API_VERSION; }

const char* geaware_status_string(geaware_status status) {
  switch (status) {
    case GEAWARE_OK:
      return "ok";
    case GEAWARE_ERROR_NULL_ARGUMENT:
      return "null argument";
    case GEAWARE_ERROR_INVALID_VEHICLE:
      return "invalid vehicle";
    case GEAWARE_ERROR_INVALID_CONFIGURATION:
      return "invalid configuration";
    case GEAWARE_ERROR_FILE:
      return "file error";
    case GEAWARE_ERROR_INTERNAL:
      return "internal error";
  }
  return "unknown status";
}

geaware_status geaware_vehicle_builtin(geaware_vehicle* v) {
  if (v == nullptr) return GEAWARE_ERROR_NULL_ARGUMENT;
  try {
    const model::VehicleParams p = io::builtinVehicle();
    if (p.drag.heights_m.size() > GEAWARE_MAX_DRAG_ROWS) return GEAWARE_ERROR_INTERNAL;
    *v = geaware_vehicle{};
    v->mass_kg = p.mass_kg;
    put3(p.inertia_kgm2, v->inertia_kgm2);
    v->diagonal_rotor_distance_m = p.diagonal_rotor_distance_m;
    v->propeller_radius_m = p.propeller_radius_m;
    v->min_rotor_plane_height_m = p.min_rotor_plane_height_m;
    v->k_T_N_per_rpm2 = p.rotor.k_T_N_per_rpm2;
    v->k_TX_N_per_rpm2 = p.rotor.k_TX_N_per_rpm2;
    v->k_TY_N_per_rpm2 = p.rotor.k_TY_N_per_rpm2;
    v->k_I_Nm_per_rpm2 = p.rotor.k_I_Nm_per_rpm2;
    v->J_R_kgm2 = p.rotor.J_R_kgm2;
    v->throttle_c2_rpm2 = p.throttle.c2_rpm2;
    v->throttle_c1_rpm2 = p.throttle.c1_rpm2;
    v->throttle_c0_rpm2 = p.throttle.c0_rpm2;
    v->throttle_reference_voltage_V = p.throttle.reference_voltage_V;
    v->throttle_voltage_exponent = p.throttle.voltage_exponent;
    v->g1_m2 = p.additional_thrust.g1_m2;
    v->g2_m2 = p.additional_thrust.g2_m2;
    v->g3_m = p.leveling_torque.g3_m;
    v->g4_m2 = p.leveling_torque.g4_m2;
    v->leveling_scale_m4 = p.leveling_torque.scale_m4;
    v->drag_rows = static_cast<int>(p.drag.heights_m.size());
    for (std::size_t i = 0; i < p.drag.heights_m.size(); ++i) {
      v->drag_heights_m[i] = p.drag.heights_m[i];
      v->drag_d_x_N_per_mps[i] = p.drag.d_x_N_per_mps[i];
      v->drag_d_y_N_per_mps[i] = p.drag.d_y_N_per_mps[i];
    }
    return GEAWARE_OK;
  } catch (...) {
    return GEAWARE_ERROR_INTERNAL;
  }
}

geaware_status geaware_controller_create(const geaware_vehicle* vehicle, const char* configuration,
                                         double rate_hz, geaware_controller** controller,
                                         char* message, size_t message_size) {
  if (vehicle == nullptr) {
    if (controller != nullptr) *controller = nullptr;
    say(message, message_size, "geaware: the vehicle pointer is NULL");
    return GEAWARE_ERROR_NULL_ARGUMENT;
  }
  model::VehicleParams params;
  try {
    params = toParams(*vehicle);
  } catch (const std::exception& e) {
    if (controller != nullptr) *controller = nullptr;
    say(message, message_size, e.what());
    return GEAWARE_ERROR_INVALID_VEHICLE;
  }
  return create(&params, nullptr, configuration, rate_hz, controller, message, message_size);
}

geaware_status geaware_controller_create_from_file(const char* vehicle_file,
                                                   const char* configuration, double rate_hz,
                                                   geaware_controller** controller,
                                                   char* message, size_t message_size) {
  if (vehicle_file == nullptr) {
    if (controller != nullptr) *controller = nullptr;
    say(message, message_size, "geaware: the vehicle file name is NULL");
    return GEAWARE_ERROR_NULL_ARGUMENT;
  }
  return create(nullptr, vehicle_file, configuration, rate_hz, controller, message, message_size);
}

geaware_status geaware_controller_create_from_files(const char* vehicle_file,
                                                    const char* controller_params_file,
                                                    const char* configuration, double rate_hz,
                                                    geaware_controller** controller,
                                                    char* message, size_t message_size) {
  return create(nullptr, vehicle_file, configuration, rate_hz, controller, message, message_size,
                controller_params_file);
}

geaware_status geaware_controller_update(geaware_controller* c,
                                         const geaware_controller_input* in,
                                         geaware_controller_output* out) {
  if (c == nullptr || in == nullptr || out == nullptr) return GEAWARE_ERROR_NULL_ARGUMENT;
  control::ControllerInput x;
  x.t_s = in->t_s;
  x.reference.p_W = vec3(in->ref_position_m);
  x.reference.v_W = vec3(in->ref_velocity_mps);
  x.reference.a_W = vec3(in->ref_accel_mps2);
  x.reference.j_W = vec3(in->ref_jerk_mps3);
  x.reference.s_W = vec3(in->ref_snap_mps4);
  x.reference.yaw_rad = in->ref_yaw_rad;
  x.reference.yaw_rate_radps = in->ref_yaw_rate_radps;
  x.reference.yaw_acc_radps2 = in->ref_yaw_accel_radps2;
  x.estimate.p_W = vec3(in->position_m);
  x.estimate.v_W = vec3(in->velocity_mps);
  x.estimate.q_WB = Eigen::Quaterniond(in->attitude_wxyz[0], in->attitude_wxyz[1],
                                       in->attitude_wxyz[2], in->attitude_wxyz[3]);
  x.gyro_B = vec3(in->gyro_radps);
  x.accel_B = vec3(in->accel_mps2);
  x.height_m = in->height_m;
  x.height_valid = in->height_valid != 0;
  x.rotor_speeds_rpm = Eigen::Vector4d(in->rotor_speeds_rpm[0], in->rotor_speeds_rpm[1],
                                       in->rotor_speeds_rpm[2], in->rotor_speeds_rpm[3]);
  x.battery_voltage_V = in->battery_voltage_V;  // 0 or NaN: not measured (ThrottleCurve)
  // The disturbance observer (paper eq. 6) on exactly the controller's inputs, as in flight.
  const estimation::DisturbanceEstimate d =
      c->observer.update({x.t_s, x.gyro_B, x.accel_B, x.rotor_speeds_rpm, x.estimate.q_WB});
  x.external_accel_W = d.a_ext_W;
  x.external_accel_valid = d.valid;
  const control::ControllerOutput y = c->controller.update(x);
  for (int i = 0; i < 4; ++i) {
    out->throttle[i] = y.throttle[static_cast<std::size_t>(i)];
    out->rotor_speeds_rpm[i] = y.n_des_rpm[i];
  }
  out->thrust_N = y.thrust_des_N;
  put3(y.tau_des_B, out->torque_Nm);
  put3(y.a_des_W, out->accel_cmd_mps2);
  putQuat(y.q_des_WB, out->attitude_cmd_wxyz);
  out->flags = y.flags;
  return GEAWARE_OK;
}

void geaware_controller_reset(geaware_controller* c) {
  if (c == nullptr) return;
  c->controller.reset();
  c->observer.reset();
}

void geaware_controller_destroy(geaware_controller* c) { delete c; }

}  // extern "C"
