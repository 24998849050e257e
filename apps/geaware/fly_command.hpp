#pragma once
// `geaware fly`: one closed-loop flight in the simulator (experiments/flight.hpp) — the
// tracking metrics of the paper's Table I, the crash status, the real-time factor, and
// optionally the CSV log (--out), one JSON object (--json) and an HTML report (--report).
// See docs/closed-loop.md.

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace geaware::cli {

/// Registers `fly` on `app`.
Runner addFlyCommand(CLI::App& app);

}  // namespace geaware::cli
