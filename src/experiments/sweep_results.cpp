// SPDX-License-Identifier: BSD-3-Clause
// A sweep's results directory (experiments/sweep.hpp, docs/sweeps.md): one record file per key,
// written atomically as each flight ends; the rerun's test of a finished key; the merge; and
// the local run on threads.

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "geaware/experiments/flight_pool.hpp"
#include "geaware/experiments/sweep.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/provenance.hpp"

namespace geaware::experiments {
namespace fs = std::filesystem;
namespace {

/// A record file larger than this is not a record (a bound on what a rerun reads) [bytes].
constexpr std::uintmax_t kMaxRecordBytes = 64 * 1024;

/// The file's text when it is a regular file of at most kMaxRecordBytes; empty otherwise.
std::string readSmallFile(const fs::path& p) {
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) return {};
  const auto size = fs::file_size(p, ec);
  if (ec || size > kMaxRecordBytes) return {};
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return in ? os.str() : std::string();
}

/// The record in `text` when it is one object whose "key" is `key` and that holds every member
/// a record has (sweepRecord); null otherwise (a file cut short, another key's, not a record).
io::Json parseRecord(const std::string& text, const std::string& key) {
  io::Json j = io::Json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return nullptr;
  const auto it = j.find("key");
  if (it == j.end() || !it->is_string() || it->get<std::string>() != key) return nullptr;
  for (const char* member : {"case", "controller", "scenario", "seed", "struck", "strike_t_s", "rmse_all_cm",
                             "rmse_xy_cm", "rmse_z_cm", "max_cm", "guard_active_s", "simulated_s"}) {
    if (!j.contains(member)) return nullptr;
  }
  return j;
}

/// A record's temporary file older than this was left by a killed run (SIGKILL, a power
/// loss): a record is written in milliseconds, so an hour leaves a concurrent writer's alone [s].
constexpr int kStaleTemporaryS = 3600;

/// Whether `name` is a record's temporary file, `.<key>.json.geaware-XXXXXX` (io::AtomicFile).
bool isRecordTemporary(const std::string& name) {
  constexpr std::string_view kMark = ".json.geaware-";
  if (name.size() < 1 + kMark.size() + 6 || name.front() != '.') return false;
  const std::size_t at = name.size() - 6 - kMark.size();
  if (name.compare(at, kMark.size(), kMark) != 0) return false;
  return std::all_of(name.end() - 6, name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)); });
}

/// Removes the records' temporary files in `flights` that a killed run left (older than
/// kStaleTemporaryS). Errors leave a file where it is.
void removeStaleTemporaries(const fs::path& flights) {
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator it(flights, ec), end; !ec && it != end; it.increment(ec)) {
    if (!isRecordTemporary(it->path().filename().string())) continue;
    std::error_code e;
    if (!it->is_regular_file(e) || e) continue;
    const auto written = it->last_write_time(e);
    if (!e && now - written >= std::chrono::seconds(kStaleTemporaryS)) fs::remove(it->path(), e);
  }
}

}  // namespace

fs::path sweepFlightPath(const fs::path& dir, const std::string& key) {
  return dir / "flights" / sweepKeyFileName(key);
}

bool sweepFlightDone(const fs::path& dir, const std::string& key) {
  const std::string text = readSmallFile(sweepFlightPath(dir, key));
  return !text.empty() && !parseRecord(text, key).is_null();
}

std::vector<std::string> missingSweepKeys(const SweepSpec& spec, const fs::path& dir) {
  std::vector<std::string> out;
  for (auto& key : sweepKeys(spec)) {
    if (!sweepFlightDone(dir, key)) out.push_back(std::move(key));
  }
  return out;
}

void prepareSweepDirectory(const SweepSpec& spec, const fs::path& dir) {
  (void)io::checkOutputDirectory("--out", dir.string());
  std::error_code ec;
  const fs::path id = dir / "sweep.sha256";
  const fs::path results = dir / "results.json";
  if (fs::exists(results, ec) && !fs::is_regular_file(results, ec)) {
    throw io::OutputError(fmt::format("--out '{}': {} is not a regular file; expected the merged results there",
                                      dir.string(), results.string()));
  }
  if (!fs::exists(id, ec)) {
    // Not a sweep's directory (yet): its results.json and records would be someone else's,
    // overwritten by the merge or merged as this sweep's.
    const bool records = fs::is_directory(dir / "flights", ec) && !fs::is_empty(dir / "flights", ec);
    if (fs::exists(results, ec) || records) {
      throw io::OutputError(fmt::format("--out '{}': holds {} and no sweep.sha256: not the results directory of "
                                        "a sweep, and a sweep would overwrite or merge what it holds; expected "
                                        "a new or empty directory (nothing was changed)",
                                        dir.string(), records ? (dir / "flights").string() + "/…" : results.string()));
    }
  }
  fs::create_directories(dir / "flights", ec);
  if (ec) {
    throw io::OutputError(fmt::format("--out '{}': cannot create {}: {}", dir.string(),
                                      (dir / "flights").string(), ec.message()));
  }
  const std::string line = spec.fingerprint + "\n";
  if (fs::exists(id, ec)) {
    const std::string old = readSmallFile(id);
    const std::string old_id = old.substr(0, old.find('\n'));
    if (old != line && old_id == spec.file_sha256) {
      // Made by a build whose fingerprint was the sweep file's alone: the flights may be this
      // sweep's, if none of the files it names changed since; only the user can know.
      throw std::runtime_error(fmt::format(
          "--out '{}': {} holds the SHA-256 of {} alone, as builds before 2026-11-29 wrote it; the "
          "fingerprint now also covers the files the sweep names. If none of them changed since the "
          "directory was made, replace that line with {} to go on with its flights; otherwise give another "
          "directory",
          dir.string(), id.string(), spec.source, spec.fingerprint));
    }
    if (old != line) {
      throw std::runtime_error(fmt::format(
          "--out '{}': holds the results of another sweep ({} has '{}'; {} and the files it names have the "
          "fingerprint {}); give another directory, or remove this one to start again",
          dir.string(), id.string(), old_id, spec.source, spec.fingerprint));
    }
    removeStaleTemporaries(dir / "flights");
    return;
  }
  io::writeFileAtomically(id.string(), line, "the sweep's fingerprint");
}

void writeSweepFlight(const fs::path& dir, const std::string& key, std::string_view record) {
  std::string text(record);
  text += '\n';
  io::writeFileAtomically(sweepFlightPath(dir, key).string(), text, "the record of flight " + key);
}

std::string mergeSweepText(const SweepSpec& spec, const fs::path& dir) {
  io::Json records = io::Json::array();
  std::size_t missing = 0;
  std::string first_missing;
  for (const auto& key : sweepKeys(spec)) {
    io::Json r = parseRecord(readSmallFile(sweepFlightPath(dir, key)), key);
    if (r.is_null()) {
      if (missing++ == 0) first_missing = key;
      continue;
    }
    records.push_back(std::move(r));
  }
  if (missing > 0) {
    throw std::runtime_error(fmt::format("{}: {} of {} flights have no record in {} (the first: {}); "
                                         "run the sweep again to fly them",
                                         spec.source, missing, spec.flights(), (dir / "flights").string(),
                                         first_missing));
  }
  io::Json doc;
  doc["geaware_version"] = std::string(io::geawareVersion());
  io::Json sweep;
  io::Json cases = io::Json::array();
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    cases.push_back({{"name", spec.cases[i].name}, {"meaning", sweepCaseMeaning(spec, i)}});
  }
  sweep["cases"] = cases;
  io::Json controllers = io::Json::array();
  for (const auto& c : spec.controllers) controllers.push_back(c.name);
  sweep["controllers"] = controllers;
  io::Json scenarios = io::Json::array();
  for (const auto& s : spec.scenarios) scenarios.push_back(s.name);
  sweep["scenarios"] = scenarios;
  sweep["first_seed"] = spec.first_seed;
  sweep["seeds"] = spec.seed_count;
  sweep["calibrate"] = spec.calibrate;
  sweep["world"] = spec.world_reference;
  sweep["fingerprint_sha256"] = spec.fingerprint;
  doc["sweep"] = sweep;
  doc["flights"] = spec.flights();
  doc["records"] = std::move(records);
  return io::dumpJson(doc) + "\n";
}

fs::path mergeSweep(const SweepSpec& spec, const fs::path& dir) {
  const std::string text = mergeSweepText(spec, dir);
  const fs::path out = dir / "results.json";
  io::writeFileAtomically(out.string(), text, "the merged sweep results");
  return out;
}

std::size_t runSweepKeys(const SweepSpec& spec, const fs::path& dir, const std::vector<std::string>& keys,
                         int threads, const SweepProgress& progress) {
  const int n = std::min<int>(resolveThreads(threads), static_cast<int>(std::max<std::size_t>(keys.size(), 1)));
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;  // progress, done and the first error
  std::size_t done = 0;
  std::exception_ptr error;
  std::string error_key;
  const auto work = [&] {
    for (;;) {
      if (stop.load()) return;
      const std::size_t i = next.fetch_add(1);
      if (i >= keys.size()) return;
      try {
        writeSweepFlight(dir, keys[i], runSweepFlight(spec, keys[i]));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) {
          error = std::current_exception();
          error_key = keys[i];
        }
        stop.store(true);
        return;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) progress(done, keys.size(), keys[i]);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      throw std::runtime_error("flight " + error_key + ": " + e.what());
    }
  }
  return done;
}

}  // namespace geaware::experiments
