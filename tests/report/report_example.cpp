// SPDX-License-Identifier: BSD-3-Clause
// The example page of docs/report.md: a small report with a table and two plots, written as
// HTML and exported to PNG. Regenerates docs/figures/report-example.png:
//   build/tests/report/report_example /tmp/report-example.html docs/figures/report-example.png
// The curves are the classic Cheeseman–Bennett ground-effect law T_IGE/T_OGE =
// 1 / (1 − (R / 4z)²) (Cheeseman & Bennett 1955), computed here so that the example depends on
// the report layer only.

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "geaware/report/page.hpp"

namespace {

double cheesemanBennett(double z_over_R) {
  return 1.0 / (1.0 - std::pow(1.0 / (4.0 * z_over_R), 2));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s OUT.html [OUT.png]\n", argv[0]);
    return 2;
  }
  try {
    using namespace geaware::report;
    Page page("Report example: rotor thrust in ground effect");
    page.addText(
        "A sample page of geaware's report module: text, a table and interactive plots (zoom, "
        "pan, hover), in one HTML file that opens from disk.\nProduced by: report_example " +
        std::string(argv[1]) + (argc == 3 ? " " + std::string(argv[2]) : ""));

    Plot ratio;
    ratio.title = "Thrust ratio in ground effect (Cheeseman–Bennett)";
    ratio.x_label = "rotor height over radius z/R [-]";
    ratio.y_label = "T_IGE / T_OGE [-]";
    ratio.height_px = 380;
    Series law{"1 / (1 − (R/4z)²)", {}, {}, "lines", ""};
    Series points{"sampled every 0.5 R", {}, {}, "markers", ""};
    for (int i = 0; i <= 60; ++i) {
      const double zr = 0.5 + 0.05 * i;
      law.x.push_back(zr);
      law.y.push_back(cheesemanBennett(zr));
      if (i % 10 == 0) {
        points.x.push_back(zr);
        points.y.push_back(cheesemanBennett(zr));
      }
    }
    Series one{"out of ground effect", {0.5, 3.5}, {1.0, 1.0}, "lines", "dash"};
    ratio.series = {law, points, one};
    page.addPlot(ratio);

    Table table{"Sampled values", {"z/R [-]", "T_IGE/T_OGE [-]", "gain [%]"}, {}};
    for (std::size_t i = 0; i < points.x.size(); ++i) {
      char a[32], b[32], c[32];
      std::snprintf(a, sizeof a, "%.1f", points.x[i]);
      std::snprintf(b, sizeof b, "%.4f", points.y[i]);
      std::snprintf(c, sizeof c, "%.1f", 100.0 * (points.y[i] - 1.0));
      table.rows.push_back({a, b, c});
    }
    page.addTable(table);

    Plot excess;
    excess.title = "Excess thrust, log scale";
    excess.x_label = "z/R [-]";
    excess.y_label = "T_IGE / T_OGE − 1 [-]";
    excess.y_axis = AxisType::kLog;
    excess.height_px = 320;
    Series e{"excess", {}, {}, "lines", ""};
    for (std::size_t i = 0; i < law.x.size(); ++i) {
      e.x.push_back(law.x[i]);
      e.y.push_back(law.y[i] - 1.0);
    }
    excess.series = {e};
    page.addPlot(excess);

    page.write(argv[1]);
    std::printf("wrote %s\n", argv[1]);
    if (argc == 3) {
      exportPng(argv[1], argv[2], 1100, 1300);
      std::printf("wrote %s\n", argv[2]);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "report_example: %s\n", e.what());
    return 1;
  }
  return 0;
}
