// SPDX-License-Identifier: BSD-3-Clause
// Fits as vehicle-file updates: the keys each fit determines are set, and the merged file
// carries values close to the parameters the synthetic log was generated with.

#include "geaware/ident/vehicle_update.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "geaware/io/vehicle_file.hpp"
#include "synthetic.hpp"

namespace {

namespace fs = std::filesystem;

TEST(VehicleUpdate, FitResultsBecomeUpdates) {
  const auto dir = ident_test::tempDir("vehicle_update_fits");
  const auto base = dir / "base.yaml";
  {
    std::ofstream os(base, std::ios::binary);
    os << geaware::io::builtinVehicleYaml();
  }
  ident_test::PlatformSpec spec;
  spec.level_samples = 5000;
  spec.tilted_samples = 5000;
  const auto log = ident_test::syntheticPlatform(spec, 2);
  const auto& p = geaware_test::paperParams();
  geaware::io::VehicleUpdate u;
  geaware::ident::addAdditionalThrust(u, geaware::ident::fitAdditionalThrust(log));
  geaware::ident::addMixing(u, geaware::ident::fitMixing(log, p.diagonal_rotor_distance_m));
  geaware::ident::addLeveling(
      u, geaware::ident::fitLeveling(log, {p.rotor.k_T_N_per_rpm2, p.rotor.k_TY_N_per_rpm2,
                                           p.diagonal_rotor_distance_m}));
  EXPECT_EQ(u.entries().size(), 9u);
  const auto out = dir / "fitted.yaml";
  (void)geaware::io::writeVehicleFile(base, out, u);
  const auto merged = geaware::io::loadVehicleFile(out);
  EXPECT_NEAR(merged.additional_thrust.g2_m2 / p.additional_thrust.g2_m2, 1.0, 0.05);
  EXPECT_NEAR(merged.rotor.k_TX_N_per_rpm2 / p.rotor.k_TX_N_per_rpm2, 1.0, 0.02);
  EXPECT_NEAR(merged.leveling_torque.g3_m / p.leveling_torque.g3_m, 1.0, 0.1);
}

}  // namespace
