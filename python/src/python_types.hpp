// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The C++ objects behind geaware.Vehicle and geaware.FlatMap (held by shared pointers, so that
// a Python object keeps what it needs alive and copies are cheap).

#include <memory>

#include "bindings.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::flatness {
class FlatMap;
}

namespace geaware::python {

/// A validated vehicle and its controller-side model.
class Vehicle {
 public:
  /// Validates (model::InvalidParameters, a ValueError in Python).
  explicit Vehicle(model::VehicleParams params);
  [[nodiscard]] const model::VehicleParams& params() const noexcept { return model_->params(); }
  [[nodiscard]] const model::VehicleModel& model() const noexcept { return *model_; }

 private:
  std::shared_ptr<const model::VehicleModel> model_;
};

/// flatness::FlatMap evaluated on arrays (flat_map_bindings.cpp).
class FlatMapHandle {
 public:
  FlatMapHandle(const Vehicle& v, bool additional_thrust, bool height_drag, bool leveling_inertia);
  [[nodiscard]] py::dict evaluate(const DoubleArray& p, const DoubleArray& v, const DoubleArray& a,
                                  const DoubleArray& j, const DoubleArray& s, const DoubleArray& yaw,
                                  const DoubleArray& yaw_rate, const DoubleArray& yaw_acc,
                                  const DoubleArray& height) const;

 private:
  std::shared_ptr<const flatness::FlatMap> map_;
};

}  // namespace geaware::python
