#pragma once
// Subcommands of the geaware CLI. Each registers its options on the app and returns the
// function that runs it; the work itself lives in the libraries.

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace geaware::cli {

using Runner = std::function<int()>;

/// The command line this process was started with, shell-quoted (for the provenance of every
/// output); set once by main before any command runs.
[[nodiscard]] const std::string& commandLine();

/// `geaware model`: the controller-side ground-effect model tabulated over heights.
Runner addModelCommand(CLI::App& app);

}  // namespace geaware::cli
