// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The command line's progress reporter: one line on stderr that rewrites itself, at most ten
// times a second; stage messages on lines of their own. Silent when stderr is not a terminal
// or with --quiet, so logs and pipelines see only results and errors.

#include <chrono>
#include <string>
#include <string_view>

#include "geaware/experiments/progress.hpp"

namespace geaware::cli {

class TerminalProgress final : public experiments::Progress {
 public:
  /// `prefix` starts every line, e.g. "geaware bench".
  TerminalProgress(std::string prefix, bool quiet);
  ~TerminalProgress() override;
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  void message(std::string_view text) override;
  void update(double done, double total, std::string_view what) noexcept override;
  /// Ends the rewritten line, if one is showing.
  void end() noexcept;

 private:
  std::string prefix_;
  bool enabled_;
  bool pending_ = false;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace geaware::cli
