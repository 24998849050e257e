// SPDX-License-Identifier: BSD-3-Clause
// `geaware logs inspect LOG`: what a flight log holds (topics, fields, rates, time span, gaps)
// and the health of every channel (dead, constant, stuck, saturated, alternating with zero),
// as a table and as JSON. Thin: read (io/log_channels.hpp), inspect (io/log_inspect.hpp), print.

#include "commands.hpp"

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_inspect.hpp"
#include "geaware/io/output_file.hpp"

namespace geaware::cli {
namespace {

struct LogsOptions {
  std::string log;
  std::string json;                 ///< JSON output ('-': stdout)
  std::vector<std::string> topics;  ///< only these topics (empty: all)
};

int runInspect(const LogsOptions& opt) {
  io::OutputChecks files;
  files.input("LOG", opt.log);
  files.output("--json", opt.json);
  files.check();
  io::LogReadOptions read;
  read.topics = opt.topics;
  const io::LogData log = io::readLog(opt.log, read);
  if (!opt.topics.empty() && log.topics.empty()) {
    throw UsageError("--topic: none of the topics asked for is in " + opt.log);
  }
  const io::LogSummary summary = io::inspectLog(log);
  (opt.json == "-" ? std::cerr : std::cout) << io::summaryText(summary);
  if (!opt.json.empty()) writeJsonOutput(opt.json, io::summaryJson(summary), runInfo({}, {opt.log}));
  return 0;
}

}  // namespace

Runner addLogsCommand(CLI::App& app) {
  auto opts = std::make_shared<LogsOptions>();
  auto* cmd = app.add_subcommand("logs", "Look into flight logs (PX4 ULog, ArduPilot DataFlash, CSV)");
  cmd->require_subcommand(1);
  auto* inspect = cmd->add_subcommand(
      "inspect", "topics, fields, rates, time span, gaps and channel health (dead, constant, stuck, saturated, "
                 "alternating with zero) of a log");
  inspect->add_option("log", opts->log, "the log (PX4 .ulg, ArduPilot .bin, Crazyflie uSD, MATLAB .mat or CSV; format from its first bytes)")
      ->required()
      ->check(CLI::ExistingFile);
  inspect->add_option("--json", opts->json, "write the summary of every topic and channel as JSON ('-': stdout)");
  inspect->add_option("--topic", opts->topics, "inspect only this topic (message type); repeatable");
  return [opts] { return runInspect(*opts); };
}

}  // namespace geaware::cli
