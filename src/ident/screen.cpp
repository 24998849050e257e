// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/screen.hpp"

#include <array>
#include <cstddef>
#include <string>

#include "fit_support.hpp"

namespace geaware::ident {

using detail::num;

void requireVarying(const std::string& source, const std::vector<NamedColumn>& columns) {
  for (const auto& c : columns) {
    const auto& v = *c.values;
    if (v.empty()) continue;
    bool varies = false;
    for (const double x : v) varies = varies || x != v.front();
    if (varies) continue;
    throw IdentError(source + ": column '" + c.name + "' " +
                     (v.front() == 0.0 ? std::string("is all zero")
                                       : "is constant (" + num(v.front()) + " in every row)") +
                     ": the fit needs it to vary (wrong column, or a sensor that was not logged?)");
  }
}

void requireNonZero(const std::string& source, const std::vector<NamedColumn>& columns) {
  for (const auto& c : columns) {
    const auto& v = *c.values;
    if (v.empty()) continue;
    bool any = false;
    for (const double x : v) any = any || x != 0.0;
    if (!any) {
      throw IdentError(source + ": column '" + c.name + "' is all zero (" + std::to_string(v.size()) +
                       " rows): a dead channel, or a column that was not logged");
    }
  }
}

std::size_t zeroSwitches(const std::vector<double>& values) noexcept {
  std::size_t switches = 0;
  for (std::size_t i = 1; i < values.size(); ++i) switches += (values[i] == 0.0) != (values[i - 1] == 0.0);
  return switches;
}

void refuseAlternatingWithZero(const std::string& source, const std::vector<NamedColumn>& rotors) {
  for (const auto& c : rotors) {
    const auto& v = *c.values;
    const std::size_t switches = zeroSwitches(v);
    if (switches <= 4 || 10 * switches <= v.size()) continue;
    std::size_t zeros = 0;
    for (const double x : v) zeros += x == 0.0;
    throw IdentError(source + ": rotor channel '" + c.name + "' alternates with 0 (" + std::to_string(zeros) +
                     " of " + std::to_string(v.size()) + " rows at 0, " + std::to_string(switches) +
                     " switches between 0 and non-zero): dead ESC telemetry? The fit would take the zeros as a "
                     "stopped rotor; fix or drop the channel");
  }
}

namespace {

/// Keeps the rows where keep(i); returns how many were dropped.
template <class Keep, class... Columns>
std::size_t keepRows(std::size_t n, const Keep& keep, Columns&... columns) {
  std::size_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep(i)) continue;
    ((columns.empty() ? void() : void(columns[out] = columns[i])), ...);
    ++out;
  }
  ((columns.empty() ? void() : columns.resize(out)), ...);
  return n - out;
}

std::string droppedNote(std::size_t dropped, std::size_t n, const std::string& why) {
  return std::to_string(dropped) + " of " + std::to_string(n) + " rows " + why + ": dropped before fitting";
}

}  // namespace

std::vector<std::string> screenRotorStand(RotorStandLog& log, const RotorStandColumns& c) {
  refuseAlternatingWithZero(log.source, {{c.rpm, &log.rpm}});
  requireVarying(log.source, {{c.rpm, &log.rpm}, {c.thrust, &log.thrust_N}, {c.torque, &log.torque_Nm},
                              {c.throttle, &log.throttle}});
  const std::size_t n = log.size();
  const std::size_t dropped = keepRows(
      n, [&](std::size_t i) { return log.rpm[i] != 0.0 && log.thrust_N[i] > 0.0; }, log.t_s, log.throttle,
      log.rpm, log.thrust_N, log.torque_Nm, log.voltage_V);
  std::vector<std::string> notes;
  if (dropped > 0) {
    notes.push_back(droppedNote(dropped, n,
                                "at rpm = 0 or thrust ≤ 0 (a stopped rotor, or an idle thrust within the "
                                "load cell's noise)"));
  }
  return notes;
}

std::vector<std::string> screenFlight(FlightLog& log, const FlightColumns& c) {
  std::vector<NamedColumn> rotors;
  for (std::size_t k = 0; k < 4; ++k) rotors.push_back({c.n[k], &log.n_rpm[k]});
  refuseAlternatingWithZero(log.source, rotors);
  requireNonZero(log.source, rotors);
  requireNonZero(log.source, {{c.a_ext[2], &log.a_ext_W[2]}});
  const std::size_t n = log.size();
  const auto running = [&](std::size_t i) {
    for (const auto& r : log.n_rpm) {
      if (r[i] == 0.0) return false;
    }
    return true;
  };
  const std::size_t dropped =
      keepRows(n, running, log.t_s, log.h_m, log.v_W[0], log.v_W[1], log.v_W[2], log.q_WB[0], log.q_WB[1],
               log.q_WB[2], log.q_WB[3], log.a_ext_W[0], log.a_ext_W[1], log.a_ext_W[2], log.n_rpm[0],
               log.n_rpm[1], log.n_rpm[2], log.n_rpm[3]);
  std::vector<std::string> notes;
  if (dropped > 0) notes.push_back(droppedNote(dropped, n, "with a rotor at 0 rpm"));
  return notes;
}

std::vector<std::string> screenPlatform(PlatformLog& log, const PlatformColumns& c) {
  std::vector<NamedColumn> rotors;
  for (std::size_t k = 0; k < 4; ++k) rotors.push_back({c.n[k], &log.n_rpm[k]});
  refuseAlternatingWithZero(log.source, rotors);
  requireNonZero(log.source, rotors);
  requireVarying(log.source, {{c.f[2], &log.f_N[2]}});
  const std::size_t n = log.size();
  const auto running = [&](std::size_t i) {
    for (const auto& r : log.n_rpm) {
      if (r[i] == 0.0) return false;
    }
    return true;
  };
  const std::size_t dropped =
      keepRows(n, running, log.t_s, log.h_m, log.tilt_deg, log.n_rpm[0], log.n_rpm[1], log.n_rpm[2],
               log.n_rpm[3], log.f_N[0], log.f_N[1], log.f_N[2], log.tau_Nm[0], log.tau_Nm[1], log.tau_Nm[2],
               log.fz_std_N, log.count);
  std::vector<std::string> notes;
  if (dropped > 0) notes.push_back(droppedNote(dropped, n, "with a rotor at 0 rpm"));
  return notes;
}

}  // namespace geaware::ident
