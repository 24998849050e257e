// SPDX-License-Identifier: BSD-3-Clause
// geaware command line: parse, call a library function, print. Errors end in one line per
// problem on stderr and a non-zero exit status (1: bad input or failure, 2: bad usage).

#include <exception>
#include <filesystem>
#include <iostream>
#include <utility>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/truth_file.hpp"

namespace geaware::cli {
namespace {
std::string g_command_line;
}  // namespace

const std::string& commandLine() { return g_command_line; }

io::RunInfo runInfo(std::vector<std::uint64_t> seeds, std::vector<std::string> inputs) {
  io::RunInfo run{g_command_line, std::move(seeds), {}};
  for (auto& f : inputs) {
    if (!f.empty()) run.input_files.push_back(std::move(f));
  }
  return run;
}

void writeJsonOutput(const std::string& path, io::Json doc, const io::RunInfo& run) {
  doc["provenance"] = io::provenanceJson(run);
  io::writeJson(path, doc);
  if (path != "-") std::cerr << "geaware: wrote " << path << "\n";
}

CLI::Option* addVehicleOption(CLI::App* cmd, std::string& path, const std::string& what) {
  return cmd->add_option("--vehicle", path, what)->check(CLI::ExistingFile);
}

CLI::Option* addTruthOption(CLI::App* cmd, std::string& reference, const std::string& what) {
  const CLI::Validator truth_reference(
      [](std::string& text) -> std::string {
        for (const auto& name : io::builtinTruthNames()) {
          if (text == name) return {};
        }
        std::error_code ec;
        if (std::filesystem::is_regular_file(text, ec)) return {};
        std::string names;
        for (const auto& name : io::builtinTruthNames()) names += (names.empty() ? "" : ", ") + name;
        return "--truth '" + text + "': no such truth file (expected a truth or vehicle YAML file, or a built-in world: " +
               names + ")";
      },
      "FILE");
  return cmd->add_option("--truth", reference, what)->check(truth_reference);
}

std::string truthInputFile(const std::string& reference) {
  for (const auto& name : io::builtinTruthNames()) {
    if (reference == name) return {};
  }
  return reference;
}

}  // namespace geaware::cli

int main(int argc, char** argv) {
  geaware::cli::g_command_line = geaware::io::shellQuotedCommandLine(argc, argv);
  // Ctrl-C or a kill during a run leaves no temporary file beside an output.
  geaware::io::removeTemporaryFilesOnSignals();
  CLI::App app{"geaware — ground-effect-aware modelling, identification and control for multicopters"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "geaware " + std::string(geaware::io::geawareVersion()) + " (" +
                                        std::string(geaware::io::geawareCommit()) + ")");

  namespace cli = geaware::cli;
  cli::Runner run;
  for (const auto& [name, add] : {std::pair{"model", &cli::addModelCommand},
                                  std::pair{"identify", &cli::addIdentifyCommand},
                                  std::pair{"rig", &cli::addRigCommand},
                                  std::pair{"logs", &cli::addLogsCommand},
                                  std::pair{"fly", &cli::addFlyCommand},
                                  std::pair{"bench", &cli::addBenchCommand},
                                  std::pair{"sweep", &cli::addSweepCommand},
                                  std::pair{"train-residual", &cli::addTrainCommand}}) {
    cli::Runner runner = add(app);  // registers the subcommand `name`
    app.get_subcommand(name)->callback([&run, runner] { run = runner; });
  }
#ifdef GEAWARE_HAVE_BRIDGE
  for (const auto& [name, add] : {std::pair{"sitl", &cli::addSitlCommand},
                                  std::pair{"bridge", &cli::addBridgeCommand}}) {
    cli::Runner runner = add(app);
    app.get_subcommand(name)->callback([&run, runner] { run = runner; });
  }
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return run();
  } catch (const geaware::cli::UsageError& e) {
    std::cerr << "geaware: usage error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "geaware: error: " << e.what() << "\n";
    return 1;
  }
}
