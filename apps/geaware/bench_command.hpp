#pragma once
// `geaware bench`: the paper's experiments in one command (issue 6) — calibration on the
// virtual rigs, the Neural-Lander baseline (cached), Table I over seeds and the hover
// experiment, printed beside the paper's numbers with the headline ratios; optionally JSON
// (--json) and an HTML report (--report). The work is experiments/campaign.hpp; see
// docs/results.md.

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace geaware::cli {

/// Registers `bench` on `app`.
Runner addBenchCommand(CLI::App& app);

}  // namespace geaware::cli
