// SPDX-License-Identifier: BSD-3-Clause
// The controller in someone else's program: build it from a vehicle file (argument) or from
// values, give it a state estimate, the IMU, the height and the rotor speeds, get throttles.
#include <cmath>
#include <cstdio>

#include <geaware/control/controller.hpp>
#include <geaware/io/vehicle_file.hpp>

int main(int argc, char** argv) {
  using namespace geaware;
  // The vehicle: a file (strictly checked, errors name the key and line), or values in code.
  model::VehicleParams vehicle = argc > 1 ? io::loadVehicleFile(argv[1]) : io::builtinVehicle();
  if (argc <= 1) vehicle.mass_kg = 1.696;  // e.g. the scale's reading instead of the file's
  control::Controller controller(model::VehicleModel(vehicle),
                                 control::recommendedControllerParams());

  control::ControllerInput in;
  in.reference.p_W = {0.0, 0.0, 0.15};  // hold 15 cm above the floor
  in.estimate.p_W = {0.0, 0.0, 0.14};   // from your estimator
  in.accel_B = {0.0, 0.0, 9.81};        // IMU, bias-corrected [m/s²]
  in.height_m = 0.14;                   // ranger, rotor plane above the ground [m]
  in.height_valid = true;
  const double hover_rpm = std::sqrt(vehicle.mass_kg * 9.81 / (4.0 * vehicle.rotor.k_T_N_per_rpm2));
  in.rotor_speeds_rpm.setConstant(hover_rpm);  // telemetry [rpm]

  for (int tick = 0; tick < 200; ++tick) {  // one second at the controller's 200 Hz
    in.t_s = tick / controller.params().rate_hz;
    const control::ControllerOutput out = controller.update(in);
    if (tick % 50 == 0 || tick == 199) {
      std::printf("t = %.3f s  throttles %.4f %.4f %.4f %.4f  flags 0x%x\n", in.t_s,
                  out.throttle[0], out.throttle[1], out.throttle[2], out.throttle[3], out.flags);
    }
    for (double t : out.throttle) {
      if (!(t >= 0.0 && t <= 1.0)) return 1;
    }
    in.rotor_speeds_rpm = out.n_des_rpm;  // here: motors that follow; yours: ESC telemetry
  }
  return 0;
}
