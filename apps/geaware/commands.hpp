#pragma once
// Subcommands of the geaware CLI. Each registers its options on the app and returns the
// function that runs it; the work itself lives in the libraries.

#include <functional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

namespace geaware::cli {

using Runner = std::function<int()>;

/// A usage error found after parsing (a combination of options CLI11 cannot express): main
/// prints it and exits with status 2.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// The command line this process was started with, shell-quoted (for the provenance of every
/// output); set once by main before any command runs.
[[nodiscard]] const std::string& commandLine();

/// `geaware model`: the controller-side ground-effect model tabulated over heights.
Runner addModelCommand(CLI::App& app);

}  // namespace geaware::cli
