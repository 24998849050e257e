// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/provenance.hpp"

#include <stdexcept>

namespace geaware::io {
namespace {

bool needsQuoting(std::string_view arg) {
  if (arg.empty()) return true;
  for (const char c : arg) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '-' || c == '_' || c == '.' || c == '/' || c == ':' || c == '=' ||
                       c == ',' || c == '+' || c == '@' || c == '%';
    if (!plain) return true;
  }
  return false;
}

}  // namespace

std::string shellQuotedCommandLine(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    if (i > 0) line += ' ';
    const std::string_view arg = argv[i];
    if (!needsQuoting(arg)) {
      line += arg;
      continue;
    }
    line += '\'';
    for (const char c : arg) {
      if (c == '\'') {
        line += "'\\''";
      } else {
        line += c;
      }
    }
    line += '\'';
  }
  return line;
}

Json provenanceJson(const RunInfo& run) {
  Json inputs = Json::array();
  for (const auto& path : run.input_files) {
    Json entry = {{"path", path}};
    try {
      entry["sha256"] = fileSha256Hex(path);
    } catch (const std::runtime_error&) {
      entry["sha256"] = nullptr;
    }
    inputs.push_back(std::move(entry));
  }
  return Json{{"geaware_version", geawareVersion()},
              {"commit", geawareCommit()},
              {"command_line", run.command_line},
              {"seeds", run.seeds},
              {"inputs", std::move(inputs)}};
}

std::string provenanceComment(const RunInfo& run, std::string_view prefix) {
  const std::string p(prefix);
  std::string text = p + "geaware_version: " + std::string(geawareVersion()) + "\n";
  text += p + "commit: " + std::string(geawareCommit()) + "\n";
  std::string line = run.command_line;
  for (auto& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  text += p + "command_line: " + line + "\n";
  std::string seeds;
  for (std::size_t i = 0; i < run.seeds.size(); ++i) {
    seeds += (i > 0 ? " " : "") + std::to_string(run.seeds[i]);
  }
  text += p + "seeds: " + seeds + "\n";
  for (const auto& path : run.input_files) {
    std::string hash;
    try {
      hash = fileSha256Hex(path);
    } catch (const std::runtime_error&) {
      hash = "unreadable";
    }
    text += p + "input: " + path + " sha256 " + hash + "\n";
  }
  return text;
}

}  // namespace geaware::io
