#pragma once
// `geaware rig`: the paper's virtual test rigs on the truth simulator (platform, rotor stand)
// and the calibration of the truth against the paper's measurements. See
// docs/sim-aerodynamics.md.

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace geaware::cli {

/// Registers `rig` with its subcommands `platform`, `rotor` and `calibrate` on `app`.
Runner addRigCommand(CLI::App& app);

}  // namespace geaware::cli
