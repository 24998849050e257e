// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "geaware/io/vehicle_writer.hpp"
#include "geaware/model/vehicle_schema.hpp"
#include "vehicle_text.hpp"

namespace geaware::io {

using detail::CurveSection;
using detail::sectionByPath;
using detail::sectionOfKey;

const std::vector<std::string>& VehicleUpdate::fittedKeys() {
  // The schema's fitted parameters but the ground-effect tables' columns (setTable).
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (const auto& s : model::vehicleSchema().specs()) {
      if (s.fitted && s.form != model::ParamForm::kTable) k.emplace_back(s.key);
    }
    return k;
  }();
  return keys;
}

namespace {
bool isListKey(const std::string& key) {
  const auto* s = model::vehicleSchema().find(key);
  return s != nullptr && s->kind == model::ParamKind::kList && s->form == model::ParamForm::kAlways;
}
}  // namespace

void VehicleUpdate::set(const std::string& key, double value, double std_error) {
  const auto& keys = fittedKeys();
  if (std::find(keys.begin(), keys.end(), key) == keys.end() || isListKey(key)) {
    throw std::invalid_argument("VehicleUpdate: '" + key + "' is not a fitted scalar key");
  }
  if (!std::isfinite(value)) {
    throw std::invalid_argument("VehicleUpdate: " + key + " is not finite");
  }
  const CurveSection* section = sectionOfKey(key);
  std::erase_if(entries_, [&](const Entry& e) {
    return e.key == key || (section != nullptr && e.table && e.key == section->path);
  });
  Entry e;
  e.key = key;
  e.values = {value};
  e.std_error = std_error;
  entries_.push_back(std::move(e));
}

void VehicleUpdate::setList(const std::string& key, std::vector<double> values) {
  if (!isListKey(key)) throw std::invalid_argument("VehicleUpdate: '" + key + "' is not a list key");
  for (const double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument("VehicleUpdate: " + key + " is not finite");
  }
  std::erase_if(entries_, [&](const Entry& e) { return e.key == key; });
  Entry e;
  e.key = key;
  e.values = std::move(values);
  e.list = true;
  entries_.push_back(std::move(e));
}

void VehicleUpdate::setTable(const std::string& section, std::vector<double> heights_m,
                             std::vector<double> values, std::vector<double> std_errors) {
  const CurveSection* s = sectionByPath(section);
  if (s == nullptr) {
    throw std::invalid_argument("VehicleUpdate: '" + section +
                                "' is not a ground-effect curve (ground_effect.additional_thrust "
                                "or ground_effect.leveling_torque)");
  }
  if (heights_m.size() < 2) {
    throw std::invalid_argument("VehicleUpdate: the " + section +
                                " table needs at least 2 knots, got " +
                                std::to_string(heights_m.size()));
  }
  if (values.size() != heights_m.size() ||
      (!std_errors.empty() && std_errors.size() != heights_m.size())) {
    throw std::invalid_argument(
        "VehicleUpdate: the " + section + " table has " + std::to_string(heights_m.size()) +
        " heights, " + std::to_string(values.size()) + " values of " + s->values_key + " and " +
        std::to_string(std_errors.size()) +
        " std. errors (expected one value, and none or one std. error, per height)");
  }
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (!finite(heights_m) || !finite(values) || !finite(std_errors)) {
    throw std::invalid_argument("VehicleUpdate: the " + section + " table is not finite");
  }
  std::erase_if(entries_,
                [&](const Entry& e) { return e.key == section || sectionOfKey(e.key) == s; });
  Entry e;
  e.key = section;
  e.values = std::move(values);
  e.table = true;
  e.heights_m = std::move(heights_m);
  e.std_errors = std::move(std_errors);
  entries_.push_back(std::move(e));
}

}  // namespace geaware::io
