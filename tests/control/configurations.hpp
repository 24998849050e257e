// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers shared by the controller's feed-forward tests (per-rotor ground effect, ceilings and
// walls): a configuration by name, and the model's reference thrust in a level hover.
#include <string>

#include <gtest/gtest.h>

#include "geaware/control/controller_params.hpp"
#include "geaware/model/units.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware_test {

/// The configuration `name` ("model:model_indi+rotors", "recommended", …); a test failure when
/// the name does not parse.
inline geaware::control::ControllerParams named(const std::string& name) {
  geaware::control::ControllerParams p;
  EXPECT_TRUE(geaware::control::parseConfiguration(name, p)) << name;
  return p;
}

/// The model's reference thrust in a level hover at h: m·g/(1 + F_G(h)) [N].
inline double hoverThrust(double h) {
  return paperVehicle().params().mass_kg * geaware::model::kGravity /
         (1.0 + paperVehicle().groundEffect().thrustRatio(h));
}

}  // namespace geaware_test
