// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The robustness suite and the fault campaign from sweep files (issue 15 item 3; docs/sweeps.md,
// "The suites' sweep files"). config/sweeps/robustness.yaml and config/sweeps/faults.yaml are
// the grids that `geaware bench --suite robustness` and `--suite faults` fly; another sweep file
// flies another grid through the same machinery (the calibration, the Neural-Lander cache, the
// checks, the JSON and the report). A file whose items a suite cannot fly is refused before any
// work, each such item named with what the suite expects.

#include "geaware/experiments/fault_suite.hpp"
#include "geaware/experiments/robustness.hpp"
#include "geaware/experiments/sweep.hpp"

namespace geaware::experiments {

/// The robustness suite of a sweep file: its vehicle, world, start hover and controller
/// parameters, its perturbations (changes of the truth: no `fault:` item), controllers,
/// scenarios (lemniscates over flat ground, at distinct heights) and seeds. Throws
/// io::ConfigError naming the file, every item the suite cannot fly and what it expects
/// (`calibrate: false` among them: the suite calibrates the belief).
[[nodiscard]] RobustnessOptions robustnessOptionsOf(const SweepSpec& spec);

/// The fault campaign of a sweep file: as robustnessOptionsOf, with `fault:` items for
/// perturbations, `fault: none` first (the baseline every case is compared with), and no neural
/// configuration (the campaign trains no network).
[[nodiscard]] FaultSuiteOptions faultSuiteOptionsOf(const SweepSpec& spec);

}  // namespace geaware::experiments
