#pragma once
// `geaware identify {rotor,platform,flight,correlations} LOG.csv`: identification from rig and
// flight logs (docs/identification.md). Kept in its own header so that commands.hpp, shared by
// every command, does not change when this one does.

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace geaware::cli {

/// Registers `identify` and its four subcommands on `app`; the runner runs whichever was given.
Runner addIdentifyCommand(CLI::App& app);

}  // namespace geaware::cli
