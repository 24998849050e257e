// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The campaign's report page (issue 6, `geaware bench --report DIR`), through the report
// module: one self-contained HTML file with Table I beside the paper's numbers, the checks, the
// calibration, and interactive plots — the identified F_G and leveling torque against the
// truth, the trajectories seen from above and from the side, the position error over time per
// controller, the hover experiment's angle error against height, rotor speeds and torques.
// Plots of single flights use each experiment's first seed (CampaignOptions::collect_series).

#include <filesystem>
#include <string>

#include "geaware/experiments/campaign.hpp"
#include "geaware/io/provenance.hpp"
#include "geaware/report/page.hpp"

namespace geaware::experiments {

/// The page, with the provenance of the run (how to reproduce it).
[[nodiscard]] report::Page campaignPage(const CampaignResult& r, const io::RunInfo& run);

/// Writes DIR/bench.html (creating DIR) and returns its path. Throws std::runtime_error when DIR
/// exists and is not a directory or the page cannot be written. With `png`, also the whole page
/// as DIR/bench.png (headless Chromium).
std::filesystem::path writeCampaignReport(const CampaignResult& r, const std::filesystem::path& dir,
                                          const io::RunInfo& run, bool png = false);

}  // namespace geaware::experiments
