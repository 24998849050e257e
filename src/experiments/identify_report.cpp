// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/identify_report.hpp"

namespace geaware::experiments {

report::Page identifyPage(const ident::IdentifyResult& r, const std::string& title, const std::string& command) {
  report::Page page(title);
  page.addText("Command: " + command);
  for (const auto& t : r.report_tables) page.addTable({t.title, t.header, t.rows});
  for (const auto& p : r.plots) {
    report::Plot plot{p.title, p.x_label, p.y_label, {}};
    for (const auto& c : p.curves) plot.series.push_back({c.name, c.x, c.y, c.mode, c.dash});
    page.addPlot(std::move(plot));
  }
  for (const auto& w : r.warnings) page.addText("Warning: " + w);
  return page;
}

std::filesystem::path writeIdentifyReport(const ident::IdentifyResult& r, const std::filesystem::path& dir,
                                          const std::string& title, const std::string& command) {
  const report::Page page = identifyPage(r, title, command);
  std::filesystem::create_directories(dir);
  const auto file = dir / "index.html";
  page.write(file);
  return file;
}

}  // namespace geaware::experiments
