// SPDX-License-Identifier: BSD-3-Clause
// Browser tests of the report pages: Debian's headless Chromium loads a written page from disk
// (no server, no network) and plotly must have drawn every plot; PNG export gives a real PNG.
// Labelled `browser` in CTest; skipped, with the reason, where Chromium is not installed.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "geaware/report/chromium.hpp"
#include "geaware/report/page.hpp"

namespace fs = std::filesystem;
using geaware::report::Page;
using geaware::report::Plot;
using geaware::report::Series;

namespace {

class RenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!geaware::report::findChromium()) {
      GTEST_SKIP() << "Chromium is not installed (apt-get install chromium, or set "
                      "GEAWARE_CHROMIUM); the page rendering cannot be checked";
    }
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("geaware-render-") + info->name() + "-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

// Two plots of three and two series; the second has a gap (NaN) and a log axis.
Page twoPlotPage() {
  Page page("Render test");
  page.addText("Two plots, five series.");
  Plot a;
  a.title = "Thrust ratio in ground effect";
  a.x_label = "z/R [-]";
  a.y_label = "T_IGE/T_OGE [-]";
  for (const double k : {1.0, 0.9, 0.8}) {
    Series s{"k = " + std::to_string(k), {}, {}, "lines", k < 0.85 ? "dash" : ""};
    for (double zr = 0.6; zr <= 4.0; zr += 0.1) {
      s.x.push_back(zr);
      s.y.push_back(1.0 / (1.0 - k * std::pow(1.0 / (4.0 * zr), 2)));
    }
    a.series.push_back(std::move(s));
  }
  a.series[2].name = "</script><b>not bold</b>";  // escaping must hold in the browser too
  page.addPlot(a);
  Plot b;
  b.title = "Residuals";
  b.x_label = "sample [-]";
  b.y_label = "|r| [N]";
  b.y_axis = geaware::report::AxisType::kLog;
  b.series.push_back(
      Series{"fit", {1, 2, 3, 4, 5}, {0.1, 0.05, NAN, 0.02, 0.01}, "lines+markers", ""});
  b.series.push_back(Series{"data", {1, 2, 3}, {0.2, 0.1, 0.04}, "markers", ""});
  page.addPlot(b);
  return page;
}

std::size_t count(const std::string& haystack, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = haystack.find(needle); pos != std::string::npos;
       pos = haystack.find(needle, pos + needle.size())) {
    ++n;
  }
  return n;
}

std::uint32_t bigEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8U) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

}  // namespace

TEST_F(RenderTest, PlotlyDrawsEveryPlotFromAPageOnDisk) {
  const fs::path html = dir_ / "two plots.html";  // a space, to exercise the file URL
  twoPlotPage().write(html);
  const std::string dom = geaware::report::dumpDom(html);

  // Each plot area becomes a plotly graph with its own SVG: the DOM after the scripts ran,
  // cut at the plot areas, shows a "main-svg" in each and one trace group per series.
  const auto p0 = dom.find("id=\"geaware-plot-0\"");
  const auto p1 = dom.find("id=\"geaware-plot-1\"");
  ASSERT_NE(p0, std::string::npos) << dom.substr(0, 2000);
  ASSERT_NE(p1, std::string::npos);
  const std::string first = dom.substr(p0, p1 - p0);
  const std::string second = dom.substr(p1);
  EXPECT_GE(count(first, "main-svg"), 1U);
  EXPECT_GE(count(second, "main-svg"), 1U);
  EXPECT_EQ(count(first, "class=\"trace scatter"), 3U);
  EXPECT_EQ(count(second, "class=\"trace scatter"), 2U);
  EXPECT_NE(first.find("Thrust ratio in ground effect"), std::string::npos);
  EXPECT_NE(second.find("Residuals"), std::string::npos);
  // Zoom and the PNG download are there; nothing that would go to the network is.
  EXPECT_NE(dom.find("data-title=\"Zoom\""), std::string::npos);
  EXPECT_EQ(dom.find("data-title=\"Share chart"), std::string::npos);
  EXPECT_EQ(dom.find("data-title=\"Produced with Plotly"), std::string::npos);
  // The legend shows the hostile series name as text; it did not become markup.
  EXPECT_EQ(dom.find("<b>not bold</b>"), std::string::npos);
}

TEST_F(RenderTest, ExportPngWritesARealPngOfTheWindowSize) {
  const fs::path html = dir_ / "page.html";
  const fs::path png = dir_ / "page.png";
  twoPlotPage().write(html);
  geaware::report::exportPng(html, png, 1000, 1400);

  std::ifstream in(png, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GE(bytes.size(), 24U);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(bigEndian32(bytes, 16), 1000U);
  EXPECT_EQ(bigEndian32(bytes, 20), 1400U);
  // A blank 1000×1400 page compresses to a few kB; two drawn plots with text are far larger.
  EXPECT_GT(bytes.size(), 30'000U);
  EXPECT_LT(bytes.size(), 10'000'000U);
}

// The whole page, not its first screen: six plots of 600 px are ≈ 3,800 px tall, and the PNG is
// as tall as the page measured itself (within the margins of the page's layout).
TEST_F(RenderTest, ExportPagePngHoldsTheWholePage) {
  const fs::path html = dir_ / "tall.html";
  const fs::path png = dir_ / "tall.png";
  geaware::report::Page page("A tall page");
  for (int i = 0; i < 6; ++i) {
    geaware::report::Plot plot{"plot " + std::to_string(i), "x [m]", "y [m]", {}};
    plot.height_px = 600;
    plot.equal_aspect = i == 0;
    plot.series.push_back({"s", {0.0, 1.0, 2.0}, {0.0, 1.0, 0.5}, "lines", "", "#d62728"});
    page.addPlot(std::move(plot));
  }
  page.write(html);
  geaware::report::exportPagePng(html, png, 1000);
  std::ifstream in(png, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GE(bytes.size(), 24U);
  EXPECT_EQ(bigEndian32(bytes, 16), 1000U);
  EXPECT_GT(bigEndian32(bytes, 20), 6U * 600U);
  EXPECT_LT(bigEndian32(bytes, 20), 6U * 600U + 1000U);
}

TEST_F(RenderTest, ExportOfAMissingPageThrowsNamingIt) {
  const fs::path missing = dir_ / "missing.html";
  try {
    geaware::report::exportPng(missing, dir_ / "x.png");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}
