// geaware command line: parse, call a library function, print. Errors end in one line per
// problem on stderr and a non-zero exit status (1: bad input or failure, 2: bad usage).

#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "identify_command.hpp"
#include "rig_command.hpp"

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

}  // namespace geaware::cli

int main(int argc, char** argv) {
  geaware::cli::g_command_line = geaware::io::shellQuotedCommandLine(argc, argv);
  CLI::App app{"geaware — ground-effect-aware modelling, identification and control for multicopters"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "geaware " + std::string(geaware::io::geawareVersion()) + " (" +
                                        std::string(geaware::io::geawareCommit()) + ")");

  std::function<int()> run;
  const auto model = geaware::cli::addModelCommand(app);
  app.get_subcommand("model")->callback([&] { run = model; });
  const auto identify = geaware::cli::addIdentifyCommand(app);
  app.get_subcommand("identify")->callback([&] { run = identify; });
  const auto rig = geaware::cli::addRigCommand(app);
  app.get_subcommand("rig")->callback([&] { run = rig; });
  const auto fly = geaware::cli::addFlyCommand(app);
  app.get_subcommand("fly")->callback([&] { run = fly; });
  const auto bench = geaware::cli::addBenchCommand(app);
  app.get_subcommand("bench")->callback([&] { run = bench; });

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
