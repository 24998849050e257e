// SPDX-License-Identifier: BSD-3-Clause
#include "progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <utility>

namespace geaware::cli {

TerminalProgress::TerminalProgress(std::string prefix, bool quiet)
    : prefix_(std::move(prefix)), enabled_(!quiet && ::isatty(STDERR_FILENO) == 1) {}

TerminalProgress::~TerminalProgress() { end(); }

void TerminalProgress::message(std::string_view text) {
  if (!enabled_) return;
  end();
  std::fprintf(stderr, "%s: %.*s\n", prefix_.c_str(), static_cast<int>(text.size()), text.data());
}

void TerminalProgress::update(double done, double total, std::string_view what) noexcept {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (pending_ && done < total && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  const double pct = total > 0.0 ? 100.0 * done / total : 0.0;
  std::fprintf(stderr, "\r\033[K%s: %.0f/%.0f %.*s (%.0f %%)", prefix_.c_str(), done, total,
               static_cast<int>(what.size()), what.data(), pct);
  std::fflush(stderr);
  pending_ = true;
}

void TerminalProgress::end() noexcept {
  if (!pending_) return;
  std::fputc('\n', stderr);
  pending_ = false;
}

}  // namespace geaware::cli
