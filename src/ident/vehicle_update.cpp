// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/vehicle_update.hpp"

namespace geaware::ident {

void addRotorFit(io::VehicleUpdate& u, const RotorFit& f) {
  setEstimate(u, "rotor.k_T_N_per_rpm2", f.k_T_N_per_rpm2);
  setEstimate(u, "rotor.k_I_Nm_per_rpm2", f.k_I_Nm_per_rpm2);
  if (f.J_R_kgm2) setEstimate(u, "rotor.J_R_kgm2", *f.J_R_kgm2);
  setEstimate(u, "throttle_curve.c2_rpm2", f.c2_rpm2);
  setEstimate(u, "throttle_curve.c1_rpm2", f.c1_rpm2);
  setEstimate(u, "throttle_curve.c0_rpm2", f.c0_rpm2);
  if (f.reference_voltage_V && f.voltage_exponent) {
    u.set("throttle_curve.reference_voltage_V", *f.reference_voltage_V);
    setEstimate(u, "throttle_curve.voltage_exponent", *f.voltage_exponent);
  }
}

void addAdditionalThrust(io::VehicleUpdate& u, const AdditionalThrustFit& f, bool include_k_T) {
  if (include_k_T) setEstimate(u, "rotor.k_T_N_per_rpm2", f.k_T_N_per_rpm2);
  setEstimate(u, "ground_effect.additional_thrust.g1_m2", f.g1_m2);
  setEstimate(u, "ground_effect.additional_thrust.g2_m2", f.g2_m2);
}

void addMixing(io::VehicleUpdate& u, const MixingFit& f) {
  if (f.k_TX_N_per_rpm2) setEstimate(u, "rotor.k_TX_N_per_rpm2", *f.k_TX_N_per_rpm2);
  if (f.k_TY_N_per_rpm2) setEstimate(u, "rotor.k_TY_N_per_rpm2", *f.k_TY_N_per_rpm2);
  if (f.k_I_Nm_per_rpm2) setEstimate(u, "rotor.k_I_Nm_per_rpm2", *f.k_I_Nm_per_rpm2);
}

void addLeveling(io::VehicleUpdate& u, const LevelingFit& f) {
  setEstimate(u, "ground_effect.leveling_torque.g3_m", f.g3_m);
  setEstimate(u, "ground_effect.leveling_torque.g4_m2", f.g4_m2);
  setEstimate(u, "ground_effect.leveling_torque.scale_m4", f.scale_m4);
}

void addDrag(io::VehicleUpdate& u, const DragFit& f) {
  const model::DragTableParams t = dragTable(f);
  if (t.heights_m.empty()) return;  // every band fitted negative: nothing to write
  u.setList("drag.heights_m", t.heights_m);
  u.setList("drag.d_x_N_per_mps", t.d_x_N_per_mps);
  u.setList("drag.d_y_N_per_mps", t.d_y_N_per_mps);
}

}  // namespace geaware::ident
