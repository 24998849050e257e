// SPDX-License-Identifier: BSD-3-Clause
// `geaware sweep SPEC.yaml --out DIR`: the flights of a sweep file that DIR does not hold yet,
// on local threads, each record written as it is flown, then merged into DIR/results.json
// (experiments/sweep.hpp, docs/sweeps.md).

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "geaware/experiments/flight_pool.hpp"
#include "geaware/experiments/sweep.hpp"
#include "geaware/io/output_file.hpp"
#include "numbers.hpp"
#include "progress.hpp"

namespace geaware::cli {
namespace {

struct SweepOptions {
  std::string spec;
  std::string out;
  int jobs = 0;
  bool list_keys = false;
  std::string key;
  bool quiet = false;
};

int runSweep(const SweepOptions& o) {
  // The spec is read (and every problem in it reported) before anything is written.
  const experiments::SweepSpec spec = experiments::loadSweepFile(o.spec);
  if (o.list_keys) {
    for (const auto& k : experiments::sweepKeys(spec)) std::cout << k << "\n";
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write the keys to standard output");
    return 0;
  }
  if (!o.key.empty()) (void)experiments::parseSweepKey(spec, o.key);  // a bad key before any work
  if (o.key.empty()) {
    warnOfLongSweep(spec, spec.cases.size(), spec.controllers.size(), {},
                    "each flight is kept as it ends: stop it (Ctrl-C) and run the same command again to go on");
  }
  io::OutputChecks files;
  files.input("SPEC", o.spec);
  files.directory("--out", o.out);
  files.check();
  if (!o.out.empty()) experiments::prepareSweepDirectory(spec, o.out);

  TerminalProgress progress("geaware sweep", o.quiet);
  if (!o.key.empty()) {
    experiments::prepareSweep(spec, {o.key}, &progress);
    const std::string record = experiments::runSweepFlight(spec, o.key);
    if (!o.out.empty()) experiments::writeSweepFlight(o.out, o.key, record);
    std::cout << record << "\n";
    return 0;
  }
  const auto keys = experiments::missingSweepKeys(spec, o.out);
  const int threads = std::min<int>(experiments::resolveThreads(o.jobs),
                                    static_cast<int>(std::max<std::size_t>(keys.size(), 1)));
  progress.message(fmt::format("{} flights ({} perturbations × {} controllers × {} scenarios × {} seeds), "
                               "{} already done, {} to fly on {} thread{}",
                               spec.flights(), spec.cases.size(), spec.controllers.size(),
                               spec.scenarios.size(), spec.seed_count, spec.flights() - keys.size(),
                               keys.size(), threads, threads == 1 ? "" : "s"));
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t flown = 0;
  if (!keys.empty()) {
    experiments::prepareSweep(spec, keys, &progress);
    flown = experiments::runSweepKeys(spec, o.out, keys, threads,
                                      [&](std::size_t done, std::size_t total, const std::string&) {
                                        progress.update(static_cast<double>(done),
                                                        static_cast<double>(total), "flights");
                                      });
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  progress.end();
  const auto results = experiments::mergeSweep(spec, o.out);
  fmt::print("sweep {}: {} flights, {} already done, flown {} in {:.1f} s on {} thread{}\nresults: {}\n",
             o.spec, spec.flights(), spec.flights() - keys.size(), flown, wall_s, threads,
             threads == 1 ? "" : "s", results.string());
  std::fflush(stdout);
  return 0;
}

}  // namespace

void warnOfLongSweep(const experiments::SweepSpec& spec, std::size_t cases, std::size_t controllers,
                     const std::vector<std::string>& scenarios, const std::string& advice) {
  const double simulated_s = experiments::sweepSimulatedSeconds(spec, cases, controllers, scenarios);
  if (simulated_s <= experiments::kSweepLongSimulatedS) return;
  const std::size_t flights = cases * controllers * (scenarios.empty() ? spec.scenarios.size() : scenarios.size()) *
                              static_cast<std::size_t>(spec.seed_count);
  std::cerr << fmt::format("geaware: warning: {}: {} flights, {:.0f} h of simulated flight, a long run; {}\n",
                           spec.source, flights, simulated_s / 3600.0, advice);
}

Runner addSweepCommand(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "fly the flights of a sweep file (perturbations × controllers × scenarios × seeds) that DIR "
               "does not hold yet, one record file per flight, merged into DIR/results.json (docs/sweeps.md)");
  cmd->add_option("SPEC", o->spec, "the sweep YAML file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "results directory: DIR/flights/<key>.json and DIR/results.json");
  cmd->add_option("--jobs", o->jobs, "parallel flights (0: one per core); results do not depend on it")
      ->capture_default_str()
      ->check(wholeIn(0, 256));
  cmd->add_flag("--list-keys", o->list_keys, "print every flight's key, one a line, in the sweep's order");
  cmd->add_option("--key", o->key,
                  "fly only this key and print its record (written to DIR/flights too with --out)");
  cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
  cmd->parse_complete_callback([o]() {
    if (o->list_keys && (!o->key.empty() || !o->out.empty())) {
      throw CLI::ValidationError("--list-keys", "--list-keys takes neither --key nor --out");
    }
    if (!o->list_keys && o->key.empty() && o->out.empty()) {
      throw CLI::ValidationError("--out", "--out DIR is required (except with --list-keys or --key)");
    }
  });
  return [o]() { return runSweep(*o); };
}

}  // namespace geaware::cli
