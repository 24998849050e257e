// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Debian's headless Chromium, as the report module uses it: PNG export of a page (exportPng in
// page.hpp) and, for tests, the DOM of a page after its scripts ran.

#include <filesystem>
#include <optional>
#include <string>

namespace geaware::report {

/// The Chromium executable: the environment variable GEAWARE_CHROMIUM when set and non-empty,
/// else /usr/bin/chromium, /usr/bin/chromium-browser, else chromium, chromium-browser or
/// google-chrome on PATH. std::nullopt when none is found (Debian: `apt-get install chromium`).
[[nodiscard]] std::optional<std::filesystem::path> findChromium();

/// Loads `html_file` in headless Chromium, lets its scripts run for `virtual_time_ms` of virtual
/// time, and returns the serialised DOM (`--dump-dom`). Throws std::runtime_error with the
/// reason (no Chromium, no such file, Chromium failed or timed out).
[[nodiscard]] std::string dumpDom(const std::filesystem::path& html_file,
                                  int virtual_time_ms = 5000);

}  // namespace geaware::report
