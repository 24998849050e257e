// SPDX-License-Identifier: BSD-3-Clause
/* The C interface used from C99 (include/geaware/c_api.h): creation from values and from a
 * file, a hover that settles on the closed-form hover throttle, garbage inputs that never reach
 * the motors, and every refusal with its status and message. Exit 0 when all checks hold. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <geaware/c_api.h>

static int failures = 0;

#define CHECK(cond, what)                                         \
  do {                                                            \
    if (!(cond)) {                                                \
      fprintf(stderr, "FAILED %s:%d: %s\n", __FILE__, __LINE__, what); \
      ++failures;                                                 \
    }                                                             \
  } while (0)

static void hover_input(geaware_controller_input* in, double h) {
  memset(in, 0, sizeof *in);
  in->ref_position_m[2] = h;
  in->position_m[2] = h;
  in->attitude_wxyz[0] = 1.0;
  in->accel_mps2[2] = 9.81;
  in->height_m = h;
  in->height_valid = 1;
}

static int throttles_ok(const geaware_controller_output* out) {
  int i;
  for (i = 0; i < 4; ++i) {
    if (!(out->throttle[i] >= 0.0 && out->throttle[i] <= 1.0)) return 0;
  }
  return 1;
}

/* Hover throttle from the closed forms: m g = 4 k_T n^2 (1 + F_G(h)), F_G = g2/(h^2 + g1),
 * n^2 = c2 t^2 + c1 t + c0 solved for t in [0, 1]. */
static double hover_throttle(const geaware_vehicle* v, double h) {
  const double f_g = v->g2_m2 / (h * h + v->g1_m2);
  const double n2 = v->mass_kg * 9.81 / (4.0 * v->k_T_N_per_rpm2 * (1.0 + f_g));
  const double a = v->throttle_c2_rpm2, b = v->throttle_c1_rpm2, c = v->throttle_c0_rpm2 - n2;
  return (-b + sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

/* The inverse throttle curve at the reference voltage: t with c2 t^2 + c1 t + c0 = n^2. */
static double curve_throttle(const geaware_vehicle* v, double n) {
  const double a = v->throttle_c2_rpm2, b = v->throttle_c1_rpm2, c = v->throttle_c0_rpm2 - n * n;
  return (-b + sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

int main(int argc, char** argv) {
  geaware_vehicle v;
  geaware_controller* ctl = NULL;
  geaware_controller_input in;
  geaware_controller_output out;
  char msg[512];
  int i, k;
  const double h = 0.3;
  double t_expected;

  CHECK(strcmp(geaware_version(), GEAWARE_EXPECTED_VERSION) == 0, "version");
  CHECK(geaware_vehicle_builtin(&v) == GEAWARE_OK, "built-in vehicle");
  CHECK(v.mass_kg > 1.0 && v.drag_rows >= 1, "built-in vehicle values");

  /* A hover at 0.3 m in a vertical plant of the vehicle's own closed forms (rotor thrust
   * k_T sum n^2 times 1 + F_G(z), motors that follow the command, the IMU's specific force
   * consistent with it), started 2 cm low: it climbs to 0.3 m and settles on the closed-form
   * hover throttle. */
  CHECK(geaware_controller_create(&v, "recommended", 200.0, &ctl, msg, sizeof msg) == GEAWARE_OK,
        msg);
  CHECK(ctl != NULL, "controller created");
  hover_input(&in, h);
  {
    double z = h - 0.02, vz = 0.0, n2 = 0.0;
    const double dt = 1.0 / 200.0;
    for (k = 0; k < 4; ++k) in.rotor_speeds_rpm[k] = 10000.0;
    for (i = 0; i < 1000; ++i) {
      const double f_g = v.g2_m2 / (z * z + v.g1_m2);
      double thrust = 0.0;
      for (k = 0; k < 4; ++k) thrust += v.k_T_N_per_rpm2 * in.rotor_speeds_rpm[k] * in.rotor_speeds_rpm[k];
      thrust *= 1.0 + f_g;
      in.t_s = i * dt;
      in.position_m[2] = z;
      in.velocity_mps[2] = vz;
      in.height_m = z;
      in.accel_mps2[2] = thrust / v.mass_kg;
      CHECK(geaware_controller_update(ctl, &in, &out) == GEAWARE_OK, "update");
      CHECK(throttles_ok(&out), "throttles in [0, 1]");
      for (k = 0; k < 4; ++k) in.rotor_speeds_rpm[k] = out.rotor_speeds_rpm[k];
      vz += (thrust / v.mass_kg - 9.81) * dt;
      z += vz * dt;
    }
    t_expected = hover_throttle(&v, h);
    n2 = v.mass_kg * 9.81 / (4.0 * v.k_T_N_per_rpm2 * (1.0 + v.g2_m2 / (h * h + v.g1_m2)));
    printf("hover at %.4f m: throttle %.5f (closed form %.5f), rotor thrust %.4f N (%.4f N)\n",
           z, out.throttle[0], t_expected, out.thrust_N, 4.0 * v.k_T_N_per_rpm2 * n2);
    CHECK(fabs(z - h) < 0.002, "settled at the reference height");
    for (k = 0; k < 4; ++k) {
      CHECK(fabs(out.throttle[k] - t_expected) < 0.01 * t_expected, "hover throttle (closed form)");
    }
    CHECK(fabs(out.thrust_N - 4.0 * v.k_T_N_per_rpm2 * n2) < 0.01 * out.thrust_N,
          "rotor thrust m g / (1 + F_G)");
    CHECK(out.flags == 0, "no flag in a clean hover");
  }

  /* Garbage never reaches the motors: NaN and infinity give finite throttles and a flag. */
  in.t_s += 0.005;
  in.gyro_radps[0] = NAN;
  CHECK(geaware_controller_update(ctl, &in, &out) == GEAWARE_OK, "update with NaN");
  CHECK(throttles_ok(&out), "finite throttles with a NaN gyro");
  CHECK((out.flags & GEAWARE_FLAG_NON_FINITE_INPUT) != 0, "non-finite flag");
  in.gyro_radps[0] = 0.0;
  in.ref_position_m[0] = INFINITY;
  in.t_s += 0.005;
  CHECK(geaware_controller_update(ctl, &in, &out) == GEAWARE_OK, "update with inf");
  CHECK(throttles_ok(&out), "finite throttles with an infinite reference");
  in.ref_position_m[0] = 0.0;
  in.height_valid = 0;
  in.t_s += 0.005;
  CHECK(geaware_controller_update(ctl, &in, &out) == GEAWARE_OK, "update without height");
  CHECK((out.flags & GEAWARE_FLAG_HEIGHT_INVALID) != 0, "height-invalid flag");

  CHECK(geaware_controller_update(ctl, NULL, &out) == GEAWARE_ERROR_NULL_ARGUMENT, "NULL input");
  CHECK(geaware_controller_update(NULL, &in, &out) == GEAWARE_ERROR_NULL_ARGUMENT, "NULL ctl");
  geaware_controller_reset(ctl);
  geaware_controller_destroy(ctl);
  geaware_controller_destroy(NULL);

  /* The battery voltage: with the curve's dependence (V_ref 16 V, p = 1) a fresh controller's
   * first throttles are those without a measurement at 16 V, bit for bit, and at 14 V they are
   * those of a rotor speed 16/14 times higher on the reference curve. */
  {
    double t_none[4], t_ref[4], t_low[4];
    geaware_vehicle vv = v;
    vv.throttle_reference_voltage_V = 16.0;
    vv.throttle_voltage_exponent = 1.0;
    hover_input(&in, h);
    for (k = 0; k < 4; ++k) in.rotor_speeds_rpm[k] = 10000.0;
    for (i = 0; i < 3; ++i) {
      const double volts[3] = {0.0, 16.0, 14.0};
      double* dst = i == 0 ? t_none : i == 1 ? t_ref : t_low;
      CHECK(geaware_controller_create(&vv, "model:model_indi", 200.0, &ctl, msg, sizeof msg) ==
                GEAWARE_OK, msg);
      in.battery_voltage_V = volts[i];
      CHECK(geaware_controller_update(ctl, &in, &out) == GEAWARE_OK, "update with a voltage");
      for (k = 0; k < 4; ++k) dst[k] = out.throttle[k];
      geaware_controller_destroy(ctl);
    }
    in.battery_voltage_V = 0.0;
    for (k = 0; k < 4; ++k) {
      /* Both ticks add the same PI correction (first tick, same measured speeds), so the
       * difference is that of the inverse curve at n·16/14 and at n. */
      const double n = out.rotor_speeds_rpm[k];
      CHECK(t_ref[k] == t_none[k], "the reference voltage changes nothing");
      CHECK(t_low[k] > t_ref[k] + 0.01, "a low battery needs more throttle");
      CHECK(fabs((t_low[k] - t_ref[k]) - (curve_throttle(&vv, n * 16.0 / 14.0) -
                                          curve_throttle(&vv, n))) < 1e-9,
            "low-voltage throttle is the inverse curve at 16/14 the speed");
    }
  }

  /* The paper's configuration; the neural one needs a network the C interface does not take. */
  CHECK(geaware_controller_create(&v, "model:model_indi", 0.0, &ctl, msg, sizeof msg) ==
            GEAWARE_OK, msg);
  geaware_controller_destroy(ctl);
  CHECK(geaware_controller_create(&v, "neural:none", 0.0, &ctl, msg, sizeof msg) ==
            GEAWARE_ERROR_INVALID_CONFIGURATION && ctl == NULL, "neural refused");
  CHECK(geaware_controller_create(&v, "best", 0.0, &ctl, msg, sizeof msg) ==
            GEAWARE_ERROR_INVALID_CONFIGURATION && strstr(msg, "'best'") != NULL, msg);
  CHECK(geaware_controller_create(&v, NULL, -5.0, &ctl, msg, sizeof msg) ==
            GEAWARE_ERROR_INVALID_CONFIGURATION && strstr(msg, "rate_hz") != NULL, msg);

  /* A bad vehicle is refused, naming the value. */
  v.mass_kg = -1.0;
  CHECK(geaware_controller_create(&v, NULL, 0.0, &ctl, msg, sizeof msg) ==
            GEAWARE_ERROR_INVALID_VEHICLE && ctl == NULL && strstr(msg, "mass_kg") != NULL, msg);
  geaware_vehicle_builtin(&v);
  v.drag_rows = 0;
  CHECK(geaware_controller_create(&v, NULL, 0.0, &ctl, msg, sizeof msg) ==
            GEAWARE_ERROR_INVALID_VEHICLE && strstr(msg, "drag_rows") != NULL, msg);
  geaware_vehicle_builtin(&v);
  v.g1_m2 = NAN;
  CHECK(geaware_controller_create(&v, NULL, 0.0, &ctl, msg, sizeof msg) ==
            GEAWARE_ERROR_INVALID_VEHICLE && strstr(msg, "g1") != NULL, msg);

  /* From a file: the repository's vehicle file, and a missing one named in the message. */
  if (argc > 1) {
    CHECK(geaware_controller_create_from_file(argv[1], NULL, 0.0, &ctl, msg, sizeof msg) ==
              GEAWARE_OK, msg);
    geaware_controller_destroy(ctl);
  }
  CHECK(geaware_controller_create_from_file("no/such/vehicle.yaml", NULL, 0.0, &ctl, msg,
                                            sizeof msg) == GEAWARE_ERROR_FILE &&
            strstr(msg, "no/such/vehicle.yaml") != NULL, msg);
  CHECK(geaware_controller_create_from_file(NULL, NULL, 0.0, &ctl, msg, sizeof msg) ==
            GEAWARE_ERROR_NULL_ARGUMENT, "NULL file name");

  /* With a controller-parameters file (argv[2], the shipped defaults): created; a file that is
   * not one (the vehicle file) is refused as a file error naming the file and its missing keys. */
  if (argc > 2) {
    CHECK(geaware_controller_create_from_files(NULL, argv[2], "recommended", 0.0, &ctl, msg,
                                               sizeof msg) == GEAWARE_OK, msg);
    geaware_controller_destroy(ctl);
    CHECK(geaware_controller_create_from_files(argv[1], argv[1], "recommended", 0.0, &ctl, msg,
                                               sizeof msg) == GEAWARE_ERROR_FILE &&
              ctl == NULL && strstr(msg, "paper_quad.yaml") != NULL && strstr(msg, "is missing") != NULL, msg);
  }
  CHECK(geaware_controller_create_from_files(NULL, "no/such/params.yaml", NULL, 0.0, &ctl, msg,
                                             sizeof msg) == GEAWARE_ERROR_FILE &&
            strstr(msg, "no/such/params.yaml") != NULL, msg);

  /* A small message buffer is filled and terminated, never overrun. */
  {
    char small[8];
    memset(small, 'x', sizeof small);
    geaware_controller_create(&v, "best", 0.0, &ctl, small, sizeof small);
    CHECK(small[7] == '\0' && strlen(small) == 7, "message truncated and terminated");
  }
  CHECK(strcmp(geaware_status_string(GEAWARE_ERROR_FILE), "file error") == 0, "status");

  if (failures == 0) printf("c_api: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
