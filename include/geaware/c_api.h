// SPDX-License-Identifier: BSD-3-Clause
/* geaware's controller for firmware and other languages: a C99 interface (docs/c-api.md).
 *
 * The shape a PX4 module, an ArduPilot library or a Crazyflie out-of-tree controller calls:
 * create a controller once (from values or from a vehicle file; this is where memory is
 * allocated and parameters are checked), then call geaware_controller_update() at the control
 * rate with the sensors and the reference, and send the throttles to the motors. update()
 * neither allocates nor throws; invalid inputs never reach the motors as NaN (the controller
 * holds a level hover and sets a flag). The paper's disturbance observer (eq. 6) runs inside,
 * on the same inputs, for the configurations that use it (`recommended`).
 *
 * Units: SI everywhere, rotor speeds in rpm. Frames: world z up (ENU-like, as the library),
 * body z along the thrust; quaternions are (w, x, y, z), body to world. Motor order: the
 * mixer's (docs/vehicle-file.md). Thread safety: one controller per thread.
 */
#ifndef GEAWARE_C_API_H
#define GEAWARE_C_API_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Result of every call that can fail. */
typedef enum geaware_status {
  GEAWARE_OK = 0,
  GEAWARE_ERROR_NULL_ARGUMENT = 1,      /**< a required pointer was NULL */
  GEAWARE_ERROR_INVALID_VEHICLE = 2,    /**< a vehicle value out of range (message names it) */
  GEAWARE_ERROR_INVALID_CONFIGURATION = 3, /**< unknown configuration name or bad controller value */
  GEAWARE_ERROR_FILE = 4,               /**< a vehicle or controller-parameters file cannot be read or is malformed */
  GEAWARE_ERROR_INTERNAL = 5            /**< anything else (message says what) */
} geaware_status;

/** Most drag-table rows geaware_vehicle holds. */
#define GEAWARE_MAX_DRAG_ROWS 16

/** The controller's vehicle model (the vehicle file's keys, docs/vehicle-file.md). */
typedef struct geaware_vehicle {
  double mass_kg;                    /**< flying mass [kg] */
  double inertia_kgm2[3];            /**< principal inertia Ixx, Iyy, Izz [kg m^2] */
  double diagonal_rotor_distance_m;  /**< b, between diagonal rotor axes [m] */
  double propeller_radius_m;         /**< [m] */
  double min_rotor_plane_height_m;   /**< rotor plane on the ground (landing gear) [m] */
  double k_T_N_per_rpm2;             /**< thrust coefficient [N/rpm^2] */
  double k_TX_N_per_rpm2;            /**< roll torque-by-thrust coefficient [N/rpm^2] */
  double k_TY_N_per_rpm2;            /**< pitch torque-by-thrust coefficient [N/rpm^2] */
  double k_I_Nm_per_rpm2;            /**< reaction-torque coefficient [N m/rpm^2] */
  double J_R_kgm2;                   /**< rotor inertia [kg m^2] */
  double throttle_c2_rpm2;           /**< throttle curve n^2 = c2 t^2 + c1 t + c0 [rpm^2] */
  double throttle_c1_rpm2;
  double throttle_c0_rpm2;
  double g1_m2;                      /**< F_G(h) = g2/(h^2 + g1) [m^2] */
  double g2_m2;                      /**< [m^2] */
  double g3_m;                       /**< M_G(h) = scale h/(h^2 + g3 h + g4)^2 [m] */
  double g4_m2;                      /**< [m^2] */
  double leveling_scale_m4;          /**< [m^4] */
  int drag_rows;                     /**< rows used in the drag table, 1..GEAWARE_MAX_DRAG_ROWS */
  double drag_heights_m[GEAWARE_MAX_DRAG_ROWS];        /**< increasing heights [m] */
  double drag_d_x_N_per_mps[GEAWARE_MAX_DRAG_ROWS];    /**< rotor drag along body x [N/(m/s)] */
  double drag_d_y_N_per_mps[GEAWARE_MAX_DRAG_ROWS];    /**< rotor drag along body y [N/(m/s)] */
  /* Added in 0.2.0, at the end so that code filling the fields above still compiles: the
   * throttle curve's battery-voltage dependence, speed scaled by (V/V_ref)^p. Zero-initialise
   * the struct (or start from geaware_vehicle_builtin()): V_ref = 0 means none. */
  double throttle_reference_voltage_V;  /**< V_ref the curve holds at; 0: no dependence [V] */
  double throttle_voltage_exponent;     /**< p [-] (1: speed proportional to voltage) */
} geaware_vehicle;

/** Everything the controller reads in one update. */
typedef struct geaware_controller_input {
  double t_s;                    /**< time, strictly increasing [s] */
  /* The reference (flat outputs of the trajectory at t). */
  double ref_position_m[3];      /**< [m] */
  double ref_velocity_mps[3];    /**< [m/s] */
  double ref_accel_mps2[3];      /**< [m/s^2] */
  double ref_jerk_mps3[3];       /**< [m/s^3] */
  double ref_snap_mps4[3];       /**< [m/s^4] */
  double ref_yaw_rad;            /**< [rad] */
  double ref_yaw_rate_radps;     /**< [rad/s] */
  double ref_yaw_accel_radps2;   /**< [rad/s^2] */
  /* The state estimate (never a simulator's truth). */
  double position_m[3];          /**< [m] */
  double velocity_mps[3];        /**< [m/s] */
  double attitude_wxyz[4];       /**< unit quaternion, body to world */
  /* Sensors. */
  double gyro_radps[3];          /**< bias-corrected body rates [rad/s] */
  double accel_mps2[3];          /**< bias-corrected specific force, body frame [m/s^2] */
  double height_m;               /**< rotor-plane height above the ground, from a ranger [m] */
  int height_valid;              /**< 0: no reading this tick (the last valid height is used) */
  double rotor_speeds_rpm[4];    /**< measured (ESC telemetry), mixer order [rpm] */
  /* Added in 0.2.0, at the end: zero-initialised inputs keep the old behaviour. */
  double battery_voltage_V;      /**< measured battery voltage; 0 or NaN: not measured (the
                                      throttle curve at its reference voltage) [V] */
} geaware_controller_input;

/** The commands of one update. */
typedef struct geaware_controller_output {
  double throttle[4];            /**< per motor, [0, 1], always finite */
  double rotor_speeds_rpm[4];    /**< the rotor-speed command [rpm] */
  double thrust_N;               /**< collective thrust command [N] */
  double torque_Nm[3];           /**< body torque command [N m] */
  double accel_cmd_mps2[3];      /**< acceleration command, world frame [m/s^2] */
  double attitude_cmd_wxyz[4];   /**< desired attitude */
  uint32_t flags;                /**< GEAWARE_FLAG_* bits */
} geaware_controller_output;

/** Conditions met in an update (geaware_controller_output.flags). */
#define GEAWARE_FLAG_NON_FINITE_INPUT 0x001u     /**< NaN/inf in the input: hover output */
#define GEAWARE_FLAG_HEIGHT_INVALID 0x002u       /**< height missing: last valid one used */
#define GEAWARE_FLAG_REFERENCE_INVALID 0x004u    /**< the flat map refused the reference */
#define GEAWARE_FLAG_TILT_LIMITED 0x008u         /**< commanded tilt clipped */
#define GEAWARE_FLAG_YAW_SATURATED 0x010u        /**< yaw torque reduced to fit */
#define GEAWARE_FLAG_ROLL_PITCH_SATURATED 0x020u /**< roll/pitch torque reduced to fit */
#define GEAWARE_FLAG_THRUST_SATURATED 0x040u     /**< thrust clipped */
#define GEAWARE_FLAG_CLEARANCE_GUARD 0x080u      /**< the clearance guard acted */
#define GEAWARE_FLAG_INTEGRAL_HELD 0x100u        /**< anti-windup held the integral */

/** An opaque controller. */
typedef struct geaware_controller geaware_controller;

/** The library's version, e.g. "0.2.0". */
const char* geaware_version(void);

/** A short English name of a status. */
const char* geaware_status_string(geaware_status status);

/** Fills `vehicle` with the built-in paper quadrotor (config/vehicles/paper_quad.yaml). */
geaware_status geaware_vehicle_builtin(geaware_vehicle* vehicle);

/** Creates a controller for `vehicle` in `configuration`: "recommended" (geaware's, default
 *  when NULL) or "ACC:TORQUE" with ACC in none|indi|model and TORQUE in
 *  none|model|indi|model_indi (the paper's rows). `rate_hz` is the rate update() will be
 *  called at (0: the default 200 Hz). On failure `*controller` is NULL and `message` (when
 *  not NULL, `message_size` bytes, always terminated) says what was wrong. */
geaware_status geaware_controller_create(const geaware_vehicle* vehicle, const char* configuration,
                                         double rate_hz, geaware_controller** controller,
                                         char* message, size_t message_size);

/** The same from a vehicle file (YAML, docs/vehicle-file.md); errors name the file and key. */
geaware_status geaware_controller_create_from_file(const char* vehicle_file,
                                                   const char* configuration, double rate_hz,
                                                   geaware_controller** controller,
                                                   char* message, size_t message_size);

/** The same with a controller-parameters file (YAML, docs/controller-params.md): the gains,
 *  rate, filter cut-off, limits and the settings of the additions `configuration` switches on
 *  are the file's. `vehicle_file` NULL: the built-in paper quadrotor; `controller_params_file`
 *  NULL: the compiled defaults (config/controller-params/default.yaml). `rate_hz` 0: the
 *  file's loop.rate_hz; otherwise it replaces it. Errors name the file and key. */
geaware_status geaware_controller_create_from_files(const char* vehicle_file,
                                                    const char* controller_params_file,
                                                    const char* configuration, double rate_hz,
                                                    geaware_controller** controller,
                                                    char* message, size_t message_size);

/** One control step. No allocation, no exception; NULL pointers give
 *  GEAWARE_ERROR_NULL_ARGUMENT and leave `output` untouched. */
geaware_status geaware_controller_update(geaware_controller* controller,
                                         const geaware_controller_input* input,
                                         geaware_controller_output* output);

/** Clears filters and integrators (before a new flight). */
void geaware_controller_reset(geaware_controller* controller);

/** Frees the controller; NULL is ignored. */
void geaware_controller_destroy(geaware_controller* controller);

#ifdef __cplusplus
}
#endif

#endif /* GEAWARE_C_API_H */
