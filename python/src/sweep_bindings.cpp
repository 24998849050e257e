// SPDX-License-Identifier: BSD-3-Clause
// Sweeps from Python (experiments/sweep.hpp, docs/sweeps.md): the keys, one key's flight (the
// GIL released, so that threads of a Dask worker fly in parallel), the results directory and
// the merge. geaware.sweep (python/geaware/sweep.py) spreads the keys over processes or a Dask
// cluster with these.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "geaware/experiments/sweep.hpp"

namespace geaware::python {
namespace {

namespace ex = experiments;

/// The sweep file at `spec`, or, with `text`, that text read as if it were the file (a Dask
/// worker on another machine gets the text; the files it names must exist there too).
ex::SweepSpec loadSpec(const std::string& spec, const std::optional<std::string>& text) {
  if (!text) return ex::loadSweepFile(spec);
  return ex::parseSweepYaml(*text, spec, std::filesystem::path(spec).parent_path());
}

}  // namespace

void bindSweep(py::module_& m) {
  m.def(
      "sweep_keys", [](const std::string& spec) { return ex::sweepKeys(ex::loadSweepFile(spec)); },
      py::arg("spec"),
      "Every flight key of the sweep file `spec`, in the sweep's order (case, controller, scenario, "
      "seed), e.g. 'case=mass+10%/ctl=recommended/scn=lem-0.12m-1mps/seed=3'.");
  m.def(
      "sweep_flight",
      [](const std::string& spec, const std::string& key, const std::optional<std::string>& text) {
        const ex::SweepSpec s = loadSpec(spec, text);
        const py::gil_scoped_release release;
        return ex::runSweepFlight(s, key);
      },
      py::arg("spec"), py::arg("key"), py::arg("text") = py::none(),
      "Flies one key of the sweep file `spec` and returns its record: one line of JSON, the same "
      "bytes whichever process or machine flies it (`text`: the file's content, for a worker that "
      "does not have the file). The belief's calibration is computed once per process and sweep. "
      "The GIL is released during the flight.");
  m.def("sweep_key_file", [](const std::string& key) { return ex::sweepKeyFileName(key); },
        py::arg("key"), "The file name of a key's record in DIR/flights.");
  m.def(
      "sweep_missing",
      [](const std::string& spec, const std::string& dir) {
        return ex::missingSweepKeys(ex::loadSweepFile(spec), dir);
      },
      py::arg("spec"), py::arg("dir"),
      "The keys of `spec` without a finished record in DIR/flights, in the sweep's order.");
  m.def(
      "sweep_prepare_dir",
      [](const std::string& spec, const std::string& dir) {
        ex::prepareSweepDirectory(ex::loadSweepFile(spec), dir);
      },
      py::arg("spec"), py::arg("dir"),
      "Creates DIR and DIR/flights and records the sweep's fingerprint (its file's and the named files' SHA-256) in DIR/sweep.sha256; "
      "RuntimeError when DIR holds another sweep's results.");
  m.def(
      "sweep_write_flight",
      [](const std::string& dir, const std::string& key, const std::string& record) {
        ex::writeSweepFlight(dir, key, record);
      },
      py::arg("dir"), py::arg("key"), py::arg("record"),
      "Writes a key's record to DIR/flights atomically (a temporary file beside it, then rename).");
  m.def(
      "sweep_merge",
      [](const std::string& spec, const std::string& dir) {
        const ex::SweepSpec s = ex::loadSweepFile(spec);
        const py::gil_scoped_release release;
        return ex::mergeSweep(s, dir).string();
      },
      py::arg("spec"), py::arg("dir"),
      "Merges every record of DIR/flights into DIR/results.json (in the sweep's order; the same "
      "bytes as `geaware sweep`) and returns its path; RuntimeError naming the missing keys.");
}

}  // namespace geaware::python
