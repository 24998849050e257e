// SPDX-License-Identifier: BSD-3-Clause
// The sweep file (experiments/sweep.hpp, docs/sweeps.md): read strictly, every problem naming
// the file, the line and the key, the list sizes and the number of flights checked before any
// work.

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/scenario_file.hpp"
#include "geaware/experiments/sweep.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "geaware/io/format_version.hpp"
#include "geaware/io/input_file.hpp"
#include "geaware/io/provenance.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/io/yaml_reader.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments {
namespace {

std::filesystem::path resolve(const std::filesystem::path& base, const std::string& p) {
  const std::filesystem::path path(p);
  return path.is_absolute() ? path : base / path;
}

/// Whether `text` is UTF-8: the records are JSON, which holds UTF-8 text only (a record whose
/// key were not would never be read back as that key's, and its sweep never finish).
bool isUtf8(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
    if (n == 0 || i + n > text.size()) return false;
    std::uint32_t cp = n == 1 ? c : c & (0x7fu >> n);
    for (std::size_t k = 1; k < n; ++k) {
      const auto cc = static_cast<unsigned char>(text[i + k]);
      if ((cc >> 6) != 0x2) return false;
      cp = (cp << 6) | (cc & 0x3fu);
    }
    // Overlong forms, UTF-16 surrogates and code points past U+10FFFF are not UTF-8.
    static constexpr std::uint32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < kLeast[n] || (cp >= 0xd800 && cp <= 0xdfff) || cp > 0x10ffff) return false;
    i += n;
  }
  return true;
}

/// Names become parts of keys and file names: UTF-8, printable, no '/' (the key's separator)
/// and no ',' (the file name's), at most 64 bytes.
void checkName(io::MapReader& m, const std::string& key, const std::string& name) {
  if (name.empty()) {
    m.problem(key, "expected a non-empty name");
    return;
  }
  if (name.size() > 64) {
    m.problem(key, "got a name of " + std::to_string(name.size()) + " bytes, expected at most 64");
    return;
  }
  if (!isUtf8(name)) {
    std::string shown;  // the bytes that are not ASCII as \xNN
    for (const char c : name) {
      const auto u = static_cast<unsigned char>(c);
      shown += u >= 0x20 && u < 0x7f ? std::string(1, c) : fmt::format("\\x{:02X}", u);
    }
    m.problem(key, "got '" + shown + "', not UTF-8 text: expected a UTF-8 name (save the sweep file as UTF-8)");
    return;
  }
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '/' || c == ',' || u < 0x20 || u == 0x7f) {
      m.problem(key, "got '" + name + "', expected a name without '/', ',' or control characters");
      return;
    }
  }
}

/// `remedy`: what the message tells to do about a name listed twice.
template <typename T, typename Name>
void checkUnique(io::MapReader& root, const std::string& list, const std::vector<T>& items, Name name,
                 const char* remedy = "names must be unique: give a 'name'") {
  std::set<std::string> seen;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (!seen.insert(name(items[i])).second) {
      root.problem(list + "[" + std::to_string(i) + "]",
                   "'" + name(items[i]) + "' is listed twice (" + remedy + ")");
    }
  }
}

/// Whether list `key` has 1 to `max` items. `problems_before`: the file's problem count before
/// the list was read; a list the reader already found missing or of the wrong type reads as
/// empty and is not reported a second time.
bool checkCount(io::MapReader& root, const std::string& key, std::size_t n, std::size_t max,
                std::size_t problems_before) {
  if (n == 0) {
    if (root.problemCount() == problems_before) root.problem(key, "expected a list of at least one item");
    return false;
  }
  if (n > max) {
    root.problem(key, fmt::format("has {} items, expected at most {}", n, max));
    return false;
  }
  return true;
}

const std::vector<std::pair<std::string, PerturbationKind>>& kindNames() {
  using K = PerturbationKind;
  static const std::vector<std::pair<std::string, PerturbationKind>> names = {
      {"none", K::kNone},           {"mass", K::kMass},        {"k_T", K::kThrustCoefficient},
      {"spread", K::kMotorSpread},  {"cog", K::kCogOffset},    {"cushion", K::kInFlightCushion},
      {"latency", K::kMocapLatency}, {"gusts", K::kGusts},     {"law", K::kGroundEffectLaw}};
  return names;
}

/// A case of the fault suite by name (`fault: motor 80%`); its name in keys has no '/'.
Perturbation readFault(io::MapReader& m, FaultCase& fault) {
  Perturbation p;
  const std::string name = m.text("fault");
  std::string names;
  bool found = false;
  for (const auto& c : faultCases()) {
    if (c.name == name) {
      fault = c;
      found = true;
    }
    names += (names.empty() ? "" : ", ") + c.name;
  }
  if (!found && !name.empty()) {
    m.problem("fault", "got '" + name + "', expected a case of the fault suite (" + names + ")");
  }
  std::string default_name = name;
  for (std::size_t at = default_name.find('/'); at != std::string::npos; at = default_name.find('/')) {
    default_name.replace(at, 1, " per ");
  }
  p.name = m.has("name") ? m.text("name") : default_name;
  if (m.has("name")) {
    checkName(m, "name", p.name);
    fault.name = p.name;  // the fault suite's name for the case too
  }
  m.rejectUnknownKeys();
  return p;
}

Perturbation readCase(io::MapReader& m, FaultCase& fault) {
  if (m.has("fault")) return readFault(m, fault);
  Perturbation p;
  if (!m.has("kind")) {
    // One of the robustness suite's cases, by name.
    p.name = m.text("name");
    std::string names;
    for (const auto& c : robustnessCells()) {
      if (c.name == p.name) p = c;
      names += (names.empty() ? "" : ", ") + c.name;
    }
    if (p.kind == PerturbationKind::kNone && p.name != "none" && !p.name.empty()) {
      m.problem("name", "got '" + p.name + "', expected a case of the robustness suite (" + names +
                            ") or a map with 'kind'");
    }
    m.rejectUnknownKeys();
    return p;
  }
  std::vector<std::string> kinds;
  for (const auto& [n, k] : kindNames()) kinds.push_back(n);
  const std::string kind = m.choice("kind", kinds);
  if (kind.empty()) return p;  // reported; its other keys mean nothing then
  for (const auto& [n, k] : kindNames()) {
    if (n == kind) p.kind = k;
  }
  std::string default_name = kind;
  if (p.kind == PerturbationKind::kGroundEffectLaw) {
    const std::string law = m.choice("law", {"calibrated", "cheeseman_bennett", "sanchez_cuevas"});
    using L = sim::GroundEffectLaw;
    p.law = law == "cheeseman_bennett" ? L::kCheesemanBennett
            : law == "sanchez_cuevas"  ? L::kSanchezCuevas
                                       : L::kCalibrated;
    default_name = "law:" + law;
  } else if (p.kind != PerturbationKind::kNone) {
    p.value = m.finiteNumber("value");
    if (std::isfinite(p.value)) default_name = fmt::format("{}{:+g}", kind, p.value);
  }
  p.name = m.has("name") ? m.text("name") : default_name;
  if (m.has("name")) checkName(m, "name", p.name);
  m.rejectUnknownKeys();
  return p;
}

SweepScenario readScenario(io::MapReader& m, const std::filesystem::path& base, double max_sim_s) {
  SweepScenario s;
  const std::string type = m.choice("type", {"lemniscate", "file"});
  std::string default_name;
  if (type == "lemniscate") {
    traj::LemniscateParams p;
    p.height_m = m.finiteNumber("height_m");
    p.peak_speed_mps = m.finiteNumber("speed_mps");
    p.half_extent_x_m = m.finiteNumber("half_extent_x_m");
    p.half_extent_y_m = m.finiteNumber("half_extent_y_m");
    if (m.has("laps")) p.laps = static_cast<int>(m.integer("laps", 1, 1000));
    if (m.has("ramp_time_s")) p.ramp_time_s = m.finiteNumber("ramp_time_s");
    if (m.has("height_swing_m")) p.height_swing_m = m.finiteNumber("height_swing_m");
    default_name = p.height_swing_m > 0.0
                       ? fmt::format("lem-{:g}-{:g}m-{:g}mps", p.height_m, p.height_m + p.height_swing_m,
                                     p.peak_speed_mps)
                       : fmt::format("lem-{:g}m-{:g}mps", p.height_m, p.peak_speed_mps);
    if (m.problemCount() == 0) {
      const auto problems = p.validate();
      if (!problems.empty()) {
        std::string all;
        for (const auto& e : problems) all += (all.empty() ? "" : "; ") + e;
        m.problem("type", "not a usable lemniscate: " + all);
      } else {
        s.trajectory = std::make_shared<const traj::Lemniscate>(p);
      }
    }
  } else if (type == "file") {
    const std::string file = m.text("file");
    default_name = std::filesystem::path(file).stem().string();
    if (!file.empty()) {
      try {
        // The scenario file gives the trajectory, the terrain, the obstacles and the beam
        // rangers that see them; the rest is the sweep's.
        const FlightScenario f = loadScenarioFile(resolve(base, file), nullptr, max_sim_s);
        s.trajectory = f.trajectory;
        s.terrain = f.terrain;
        s.obstacles = f.obstacles;
        s.beam_rangers = f.beam_rangers;
      } catch (const std::exception& e) {
        m.problem("file", std::string("cannot use the scenario file: ") + e.what());
      }
    }
  }
  s.name = m.has("name") ? m.text("name") : default_name;
  if (m.has("name")) {
    checkName(m, "name", s.name);
  } else if (!isUtf8(s.name)) {
    m.problem("file", "the file's name is not UTF-8 text, and it would name the scenario: give a UTF-8 'name'");
  }
  m.rejectUnknownKeys();
  return s;
}

void readWorld(io::MapReader& root, const std::filesystem::path& base, SweepSpec& s) {
  const std::string vehicle = root.text("vehicle");
  if (vehicle == "builtin") {
    s.vehicle = io::builtinVehicle();
  } else if (!vehicle.empty()) {
    try {
      s.vehicle = io::loadVehicleFile(resolve(base, vehicle));
    } catch (const std::exception& e) {
      root.problem("vehicle", std::string("cannot use the vehicle file: ") + e.what());
    }
  }
  const std::string world = root.text("world");
  s.world_reference = world;
  if (world.empty() || root.problemCount() > 0) return;
  try {
    s.world = world == "default" ? defaultWorld(s.vehicle, vehicle == "builtin", vehicle)
                                 : io::resolveTruth(world, base);
  } catch (const std::exception& e) {
    root.problem("world", std::string("cannot use the world: ") + e.what() +
                              " (expected 'default', a built-in world or a truth file)");
  }
}

/// SHA-256 of the sweep file's bytes; when it names files, of those bytes followed, for each
/// file read in parsing it (in order), by a newline and that file's SHA-256 in hex. So an edit of
/// a scenario, vehicle, truth, controller-parameters or height-map file is another sweep.
std::string sweepFingerprint(std::string_view yaml_text, const std::vector<std::filesystem::path>& files) {
  std::string text(yaml_text);
  for (const auto& f : files) text += "\n" + io::fileSha256Hex(f.string());
  return io::sha256Hex(std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()));
}

}  // namespace

std::size_t SweepSpec::flights() const noexcept {
  return cases.size() * controllers.size() * scenarios.size() * static_cast<std::size_t>(seed_count);
}

SweepSpec parseSweepYaml(std::string_view yaml_text, const std::string& source,
                         const std::filesystem::path& base_dir, std::optional<double> max_sim_s_override) {
  io::InputFileCollector inputs;  // every file the sweep names, and the files those name
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw io::ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  if (!doc.IsMap()) throw io::ConfigError(source, {{1, "", "expected a map (a sweep) at the top level"}});
  io::YamlContext ctx;
  io::MapReader root(doc, "", ctx);
  (void)io::readFormatVersion(root, ctx, source);
  SweepSpec s;
  s.source = source;
  readWorld(root, base_dir, s);
  s.calibrate = root.boolean("calibrate");
  if (root.has("start_hover_s")) {
    s.start_hover_s = root.finiteNumber("start_hover_s");
    if (std::isfinite(s.start_hover_s) && !(s.start_hover_s >= 0.0 && s.start_hover_s <= 60.0)) {
      root.problem("start_hover_s", fmt::format("got {:g}, expected 0 … 60 s", s.start_hover_s));
    }
  }
  if (root.has("max_sim_s")) {
    s.max_sim_s = root.finiteNumber("max_sim_s");
    if (std::isfinite(s.max_sim_s) && !(s.max_sim_s > 0.0 && s.max_sim_s <= 86400.0)) {
      root.problem("max_sim_s", fmt::format("got {:g}, expected a duration in (0, 86400] s", s.max_sim_s));
    }
    // A refused value is reported once: the scenarios are read under the default.
    if (!(std::isfinite(s.max_sim_s) && s.max_sim_s > 0.0 && s.max_sim_s <= 86400.0)) s.max_sim_s = SweepSpec{}.max_sim_s;
  }
  if (max_sim_s_override) s.max_sim_s = *max_sim_s_override;

  auto seeds = root.map("seeds");
  s.first_seed = static_cast<std::uint64_t>(seeds.integer("first", 0, 1'000'000'000));
  s.seed_count = static_cast<std::uint64_t>(seeds.integer("count", 1, 1'000'000));
  seeds.rejectUnknownKeys();

  std::size_t before = root.problemCount();
  auto case_items = root.maps("perturbations");
  if (checkCount(root, "perturbations", case_items.size(), kSweepMaxCases, before)) {
    for (auto& m : case_items) {
      s.case_faults.emplace_back();
      s.cases.push_back(readCase(m, s.case_faults.back()));
    }
    checkUnique(root, "perturbations", s.cases, [](const Perturbation& p) { return p.name; });
  }

  before = root.problemCount();
  const auto names = root.texts("controllers");
  if (checkCount(root, "controllers", names.size(), kSweepMaxControllers, before)) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      control::ControllerParams p;
      const std::string item = "controllers[" + std::to_string(i) + "]";
      if (!control::parseConfiguration(names[i], p)) {
        root.problem(item, "got '" + names[i] +
                               "', expected 'recommended' or ACC:TORQUE (e.g. model:model_indi; "
                               "docs/controller.md)");
        continue;
      }
      s.controllers.push_back({control::configurationName(p), p});
    }
    checkUnique(root, "controllers", s.controllers, [](const SuiteController& c) { return c.name; },
                "expected each configuration once");
  }
  if (root.has("controller_params")) {
    const std::string file = root.text("controller_params");
    if (!file.empty()) {
      try {
        s.controller_values = io::loadControllerParamsFile(resolve(base_dir, file));
      } catch (const std::exception& e) {
        root.problem("controller_params",
                     std::string("cannot use the controller-parameters file: ") + e.what());
      }
    }
  }

  before = root.problemCount();
  auto scenario_items = root.maps("scenarios");
  if (checkCount(root, "scenarios", scenario_items.size(), kSweepMaxScenarios, before)) {
    for (auto& m : scenario_items) s.scenarios.push_back(readScenario(m, base_dir, s.max_sim_s));
    checkUnique(root, "scenarios", s.scenarios, [](const SweepScenario& c) { return c.name; });
  }
  root.rejectUnknownKeys();
  if (!ctx.problems.empty()) throw io::ConfigError(source, std::move(ctx.problems));
  s.fingerprint = sweepFingerprint(yaml_text, inputs.files());
  s.file_sha256 = sweepFingerprint(yaml_text, {});

  // The product, and the longest file name, before any work.
  const double product = static_cast<double>(s.cases.size()) * static_cast<double>(s.controllers.size()) *
                         static_cast<double>(s.scenarios.size()) * static_cast<double>(s.seed_count);
  if (product > static_cast<double>(kSweepMaxFlights)) {
    root.problem("seeds", fmt::format("{} perturbations × {} controllers × {} scenarios × {} seeds = {:.0f} "
                                      "flights, expected at most {}",
                                      s.cases.size(), s.controllers.size(), s.scenarios.size(),
                                      s.seed_count, product, kSweepMaxFlights));
  } else if (s.first_seed + s.seed_count - 1 > 1'000'000'000) {
    root.problem("seeds", "first + count − 1 is above 1000000000");
  } else {
    // The longest file name: each part's escaped length adds up, so the longest of each list.
    const auto longest = [](const auto& items) {
      std::size_t best = 0;
      for (std::size_t i = 0; i < items.size(); ++i) {
        if (sweepKeyFileName(items[i].name).size() > sweepKeyFileName(items[best].name).size()) best = i;
      }
      return best;
    };
    const SweepKey key{longest(s.cases), longest(s.controllers), longest(s.scenarios),
                       s.first_seed + s.seed_count - 1};
    const std::string file = sweepKeyFileName(sweepKeyText(s, key));
    if (file.size() > kSweepMaxFileName) {
      root.problem("perturbations", fmt::format("the flight file name '{}' has {} bytes, expected at most {}: "
                                                "give shorter names",
                                                file, file.size(), kSweepMaxFileName));
    }
  }
  if (!ctx.problems.empty()) throw io::ConfigError(source, std::move(ctx.problems));
  // Each scenario can be flown (the flight's own checks, in the unperturbed world), before any
  // calibration or flight.
  for (std::size_t i = 0; i < s.scenarios.size(); ++i) {
    for (const auto& e : sweepScenarioProblems(s, i)) {
      const std::string item = "scenarios[" + std::to_string(i) + "]";
      ctx.problem(ctx.lineOf(item), item, "cannot be flown: " + e.field + " = " + e.value + " (expected " +
                                              e.expected + ")");
    }
  }
  if (!ctx.problems.empty()) throw io::ConfigError(source, std::move(ctx.problems));
  return s;
}

SweepSpec loadSweepFile(const std::filesystem::path& file) {
  return parseSweepYaml(io::readInputFile(file, "sweep file", "sweep YAML file"), file.string(),
                        file.parent_path());
}

}  // namespace geaware::experiments
