// SPDX-License-Identifier: BSD-3-Clause
// The campaign's report page (experiments/campaign_report.hpp) in Debian's headless Chromium:
// the page is written from disk (no server, no network) and plotly must have drawn every plot.
// Labelled `browser`; skipped, with the reason, where Chromium is not installed.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "geaware/experiments/campaign.hpp"
#include "geaware/experiments/campaign_report.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/report/chromium.hpp"

namespace geaware::experiments {
namespace {

namespace fs = std::filesystem;

std::size_t count(const std::string& haystack, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = haystack.find(needle); pos != std::string::npos;
       pos = haystack.find(needle, pos + needle.size())) {
    ++n;
  }
  return n;
}

TEST(CampaignReport, EveryPlotIsDrawnInTheBrowser) {
  if (!report::findChromium()) {
    GTEST_SKIP() << "Chromium is not installed (apt-get install chromium, or set "
                    "GEAWARE_CHROMIUM); the report page cannot be checked";
  }
  // A reduced campaign with every kind of plot: two experiments of the 0.12 m group, one of
  // the 0.18 m group, a short hover descent with two torque compensations.
  CampaignOptions o;
  o.vehicle = io::builtinVehicle();
  o.seeds = 1;
  o.experiments = {1, 5, 7};
  o.hover_settings.from_height_m = 0.6;
  o.hover_settings.descent_rate_mps = 0.25;
  o.hover_settings.hold_start_s = 0.5;
  o.hover_settings.hold_end_s = 0.5;
  o.hover_settings.max_height_m = 0.7;
  o.hover_settings.torques = {control::TorqueCompensation::kNone,
                              control::TorqueCompensation::kModelIndi};
  o.collect_series = true;
  const CampaignResult r = runCampaign(o);

  const fs::path dir = fs::temp_directory_path() /
                       ("geaware-campaign-report-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const fs::path html = writeCampaignReport(r, dir, io::RunInfo{"campaign_render_test", {1}, {}});
  ASSERT_TRUE(fs::exists(html));
  const std::string dom = report::dumpDom(html, 15000);

  // Plots: F_G, torque; above/side/error for the two groups; hover E(h) and E(t); rotors,
  // torques.
  constexpr std::size_t kPlots = 2 + 3 * 2 + 2 + 2;
  for (std::size_t i = 0; i < kPlots; ++i) {
    const std::string id = "id=\"geaware-plot-" + std::to_string(i) + "\"";
    const auto at = dom.find(id);
    ASSERT_NE(at, std::string::npos) << "plot " << i << " is missing";
    const auto next = dom.find("id=\"geaware-plot-" + std::to_string(i + 1) + "\"");
    const std::string part = dom.substr(at, next == std::string::npos ? std::string::npos : next - at);
    EXPECT_GE(count(part, "main-svg"), 1u) << "plot " << i << " was not drawn";
    EXPECT_GE(count(part, "class=\"trace scatter"), 1u) << "plot " << i << " has no trace";
  }
  EXPECT_EQ(dom.find("id=\"geaware-plot-" + std::to_string(kPlots) + "\""), std::string::npos);
  EXPECT_NE(dom.find("Table I"), std::string::npos);
  EXPECT_NE(dom.find("Trajectories from above"), std::string::npos);
  EXPECT_NE(dom.find("angle error E against height"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace geaware::experiments
