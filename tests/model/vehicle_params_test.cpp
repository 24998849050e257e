// SPDX-License-Identifier: BSD-3-Clause
// Validation of parameter sets (the file-level messages are tested in tests/io/).
#include "geaware/model/vehicle_params.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "geaware/model/vehicle_model.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using geaware::model::FieldError;
using geaware::model::VehicleParams;

bool hasField(const std::vector<FieldError>& errors, const std::string& field) {
  return std::any_of(errors.begin(), errors.end(), [&](const FieldError& e) { return e.field == field; });
}

TEST(VehicleParams, PaperVehicleIsValid) {
  const auto errors = geaware_test::paperParams().validate();
  EXPECT_TRUE(errors.empty()) << errors.front().field << ": " << errors.front().expected;
}

TEST(VehicleParams, EveryOffendingFieldIsListed) {
  VehicleParams p = geaware_test::paperParams();
  p.mass_kg = -1.0;
  p.rotor.k_T_N_per_rpm2 = std::nan("");
  p.drag.heights_m[3] = p.drag.heights_m[2];
  const auto errors = p.validate();
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_TRUE(hasField(errors, "mass_kg"));
  EXPECT_TRUE(hasField(errors, "rotor.k_T_N_per_rpm2"));
  EXPECT_TRUE(hasField(errors, "drag.heights_m[3]"));
  EXPECT_EQ(errors.front().value, "-1");
}

TEST(VehicleParams, PhysicalConsistencyChecks) {
  {
    VehicleParams p = geaware_test::paperParams();
    p.inertia_kgm2.z() = 1.0;  // larger than xx + yy: not a rigid body
    EXPECT_TRUE(hasField(p.validate(), "inertia_kgm2.zz"));
  }
  {
    VehicleParams p = geaware_test::paperParams();
    p.propeller_radius_m = 0.2;  // adjacent rotors 0.247 m apart: discs overlap
    EXPECT_TRUE(hasField(p.validate(), "geometry.propeller_radius_m"));
  }
  {
    VehicleParams p = geaware_test::paperParams();
    p.throttle.c2_rpm2 = -4e8;  // n² falls before full throttle
    EXPECT_TRUE(hasField(p.validate(), "throttle_curve"));
  }
  {
    VehicleParams p = geaware_test::paperParams();
    p.leveling_torque.g4_m2 = 0.02;  // g3² > 4·g4: M_G has a pole at positive height
    EXPECT_TRUE(hasField(p.validate(), "ground_effect.leveling_torque"));
  }
  {
    VehicleParams p = geaware_test::paperParams();
    p.drag.d_y_N_per_mps.pop_back();
    EXPECT_TRUE(hasField(p.validate(), "drag"));
  }
}

// The rotors carry the weight between idle and full throttle: the paper's vehicle hovers at
// 10,187 rpm, between √c0 = 3,214 and √(c2 + c1 + c0) = 19,707 rpm.
TEST(VehicleParams, AVehicleThatCannotHoverOnItsCurveIsRefused) {
  const auto hoverError = [](const VehicleParams& p) {
    for (const FieldError& e : p.validate()) {
      if (e.field == "rotor.k_T_N_per_rpm2") return e.value + " | " + e.expected;
    }
    return std::string();
  };
  VehicleParams p = geaware_test::paperParams();
  EXPECT_EQ(hoverError(p), "");
  p.mass_kg = 1.696 * 3.75;  // hover at 19,727 rpm, just above the top
  EXPECT_NE(hoverError(p).find("below the throttle curve's full-throttle speed"), std::string::npos) << hoverError(p);
  p.mass_kg = 1.696 * 3.7;  // 19,595 rpm: it can (barely)
  EXPECT_EQ(hoverError(p), "");
  p = geaware_test::paperParams();
  p.rotor.k_T_N_per_rpm2 *= 91.19;  // k_T in N/(rad/s)² typed as N/rpm², (60/2π)² too large: 1,067 rpm
  EXPECT_NE(hoverError(p).find("above the throttle curve's idle speed"), std::string::npos) << hoverError(p);
  p.rotor.k_T_N_per_rpm2 = geaware_test::paperParams().rotor.k_T_N_per_rpm2 * 9.0;  // 3,396 rpm: flies
  EXPECT_EQ(hoverError(p), "");
}

// A ground-effect table reaching beyond 100 propeller radii (8.9 m here) holds heights in
// centimetres: refused at its last height; the same table in metres is fine.
TEST(VehicleParams, AGroundEffectTableInCentimetresIsRefused) {
  VehicleParams p = geaware_test::paperParams();
  p.additional_thrust.table.heights_m = {0.08, 0.12, 0.2, 0.5};
  p.additional_thrust.table.values = {0.3, 0.2, 0.1, 0.02};
  EXPECT_TRUE(p.validate().empty());
  p.additional_thrust.table.heights_m = {8.0, 12.0, 20.0, 50.0};
  EXPECT_TRUE(hasField(p.validate(), "ground_effect.additional_thrust.table.heights_m[3]"));
  p = geaware_test::paperParams();
  p.leveling_torque.table.heights_m = {7.0, 18.0, 40.0};
  p.leveling_torque.table.values = {0.01, 0.02, 0.001};
  EXPECT_TRUE(hasField(p.validate(), "ground_effect.leveling_torque.table.heights_m[2]"));
}

TEST(VehicleModel, RefusesInvalidParameters) {
  VehicleParams p = geaware_test::paperParams();
  p.mass_kg = 0.0;
  try {
    const geaware::model::VehicleModel v(p);
    FAIL() << "an invalid parameter set built a VehicleModel";
  } catch (const geaware::model::InvalidParameters& e) {
    ASSERT_EQ(e.errors().size(), 1u);
    EXPECT_EQ(e.errors()[0].field, "mass_kg");
    EXPECT_NE(std::string(e.what()).find("mass_kg"), std::string::npos);
  }
}

}  // namespace
