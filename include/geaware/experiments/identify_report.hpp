// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The HTML page of an identification (`geaware identify --report DIR`): the command, the
// result's tables (parameters, residuals and the kind's own), its plots and warnings.

#include <filesystem>
#include <string>

#include "geaware/ident/identify.hpp"
#include "geaware/report/page.hpp"

namespace geaware::experiments {

/// The page: `title`, then "Command: <command>", the tables, the plots, the warnings.
[[nodiscard]] report::Page identifyPage(const ident::IdentifyResult& result, const std::string& title,
                                        const std::string& command);

/// Writes identifyPage into `dir`/index.html (the directory is created); returns the file.
std::filesystem::path writeIdentifyReport(const ident::IdentifyResult& result, const std::filesystem::path& dir,
                                          const std::string& title, const std::string& command);

}  // namespace geaware::experiments
