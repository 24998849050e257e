// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/rotor_telemetry.hpp"

#include <cmath>
#include <utility>

#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {

std::vector<model::FieldError> RotorTelemetryParams::validate() const {
  std::vector<model::FieldError> out;
  model::FieldChecker c(out);
  using enum model::LowerBound;
  c.range("rate_Hz", rate_Hz, 0.0, 1e5, kExclusive, "Hz");
  c.nonNegative("noise_std_rpm", noise_std_rpm, "rpm");
  c.range("resolution_rpm", resolution_rpm, 0.0, 1e4, kInclusive, "rpm");
  return out;
}

RotorTelemetrySensor::RotorTelemetrySensor(const RotorTelemetryParams& params,
                                           std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      noise_(scenario_seed, salt::kRotorTelemetry),
      clock_(params_.rate_Hz) {}

std::optional<model::RotorTelemetry> RotorTelemetrySensor::sample(const PlantState& s) noexcept {
  if (!isFinite(s)) {
    ++rejected_;
    return std::nullopt;
  }
  if (!clock_.due(s.t_s)) return std::nullopt;
  model::RotorTelemetry out;
  out.t_s = s.t_s;
  const double q = params_.resolution_rpm;
  for (int i = 0; i < 4; ++i) {
    double n = s.n_rpm[static_cast<std::size_t>(i)] + params_.noise_std_rpm * noise_.normal();
    if (q > 0.0) n = q * std::round(n / q);
    out.n_rpm[i] = n > 0.0 ? n : 0.0;
  }
  return out;
}

}  // namespace geaware::sim
