// SPDX-License-Identifier: BSD-3-Clause
// Tests of the HTML writer: the page is self-contained, text is escaped, and the plot data that
// the page embeds reads back exactly (non-finite values as null). No browser needed; the
// rendering itself is checked in render_test.cpp.

#include "geaware/report/page.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "mini_json.hpp"

namespace fs = std::filesystem;
using geaware::report::AxisType;
using geaware::report::Page;
using geaware::report::Plot;
using geaware::report::Series;
using geaware::report::Table;

namespace {

// Stands in for plotly.js where the test looks at the page's own markup.
constexpr const char* kFakeLibrary = "/* plotly stand-in */ window.Plotly = {};";

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t count(const std::string& haystack, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = haystack.find(needle); pos != std::string::npos;
       pos = haystack.find(needle, pos + needle.size())) {
    ++n;
  }
  return n;
}

// The text of the JSON script element that holds the plots.
std::string embeddedJson(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"geaware-plots\">";
  const auto begin = html.find(open);
  if (begin == std::string::npos) throw std::runtime_error("no plot data element");
  const auto start = begin + open.size();
  const auto end = html.find("</script>", start);
  return html.substr(start, end - start);
}

// A unique scratch directory per test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("geaware-report-") + info->name() + "-" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Sets an environment variable for the scope of a test and restores it.
class EnvOverride {
 public:
  EnvOverride(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~EnvOverride() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  EnvOverride(const EnvOverride&) = delete;
  EnvOverride& operator=(const EnvOverride&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

Page samplePage() {
  Page page("Ground effect <calibration> & \"fit\"");
  page.addText("geaware rig platform --heights 0.07:0.5:0.01 --out sweep.csv");
  page.addTable(Table{"Fitted coefficients",
                      {"name", "value"},
                      {{"k_T", "1.5e-8"}, {"<script>alert('x')</script>", "a & b"}}});
  Plot plot;
  plot.title = "Thrust ratio";
  plot.x_label = "h [m]";
  plot.y_label = "T/T∞ [-]";
  plot.series.push_back(Series{"model", {0.1, 0.2, 0.3}, {1.2, 1.05, 1.01}, "lines", ""});
  plot.series.push_back(Series{"data", {0.1, 0.2}, {1.19, 1.07}, "markers", ""});
  page.addPlot(plot);
  return page;
}

}  // namespace

TEST(ReportPage, BundledPlotlyIsFoundWhereCMakePutIt) {
  const fs::path js = geaware::report::plotlyJsPath();
  ASSERT_TRUE(fs::is_regular_file(js)) << js;
  // plotly.js-dist-min is about 4.8 MB; a few hundred kB would mean a wrong or partial file.
  EXPECT_GT(fs::file_size(js), 1'000'000U) << js;
}

TEST(ReportPage, WrittenFileIsTheMarkupWithTheLibraryInlined) {
  const ScratchDir dir;
  const Page page = samplePage();
  const fs::path file = dir.path() / "page.html";
  page.write(file);
  const std::string written = readAll(file);
  const std::string library = readAll(geaware::report::plotlyJsPath());

  // The file is exactly html() with the real library, and the library sits in an inline
  // <script> element: the page needs nothing beside itself.
  EXPECT_EQ(written, page.html(library));
  EXPECT_NE(written.find("<script>\n" + library + "\n</script>"), std::string::npos);
  EXPECT_NE(written.find("plotly.js v"), std::string::npos);
}

TEST(ReportPage, MarkupLoadsNothingFromOutside) {
  // Checked on the page's own markup (the library replaced by a stand-in): plotly's code
  // mentions URLs in strings that a page never loads.
  const std::string html = samplePage().html(kFakeLibrary);
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("src="), std::string::npos);
  EXPECT_EQ(html.find("href="), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  // Exactly three script elements: the library, the plot data, the code that draws the plots.
  EXPECT_EQ(count(html, "<script"), 3U);
  EXPECT_EQ(count(html, "</script>"), 3U);
}

TEST(ReportPage, TitleAndTextAreEscaped) {
  const std::string html = samplePage().html(kFakeLibrary);
  const std::string escaped = "Ground effect &lt;calibration&gt; &amp; &quot;fit&quot;";
  EXPECT_NE(html.find("<title>" + escaped + "</title>"), std::string::npos);
  EXPECT_NE(html.find("<h1>" + escaped + "</h1>"), std::string::npos);
  EXPECT_NE(html.find("geaware rig platform --heights 0.07:0.5:0.01 --out sweep.csv"),
            std::string::npos);
}

TEST(ReportPage, TableCellsCannotInjectMarkup) {
  const std::string html = samplePage().html(kFakeLibrary);
  EXPECT_NE(html.find("<td>&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td>a &amp; b</td>"), std::string::npos);
  EXPECT_NE(html.find("<th>name</th><th>value</th>"), std::string::npos);
  EXPECT_EQ(html.find("alert('x')"), std::string::npos);
}

TEST(ReportPage, SeriesDataRoundTripsThroughTheEmbeddedJson) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Values chosen to need all 17 significant digits, extreme exponents, and signed zero.
  const std::vector<double> x = {0.1, std::numbers::pi, -2.5e10, 1e-300, 5e-324, -0.0, 7.0};
  const std::vector<double> y = {1.0 / 3.0, kNaN, 1.7976931348623157e308, kInf, -kInf, 42.0, -1e-7};
  Page page("round trip");
  Plot plot;
  plot.title = "p";
  plot.x_label = "x [m]";
  plot.y_label = "y [N]";
  plot.y_axis = AxisType::kLog;
  plot.height_px = 300;
  plot.series.push_back(Series{"s</script><!--", x, y, "lines+markers", "dash"});
  page.addPlot(plot);
  const std::string html = page.html(kFakeLibrary);
  const std::string text = embeddedJson(html);
  // Nothing in the data can close or comment out its script element.
  EXPECT_EQ(text.find('<'), std::string::npos);

  const auto doc = geaware_test::json::parse(text);
  ASSERT_EQ(doc.array().size(), 1U);
  const auto& trace = doc[0]["data"][0];
  EXPECT_EQ(trace["name"].string(), "s</script><!--");
  EXPECT_EQ(trace["mode"].string(), "lines+markers");
  EXPECT_EQ(trace["line"]["dash"].string(), "dash");
  ASSERT_EQ(trace["x"].array().size(), x.size());
  ASSERT_EQ(trace["y"].array().size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    // Bit-exact: the writer prints the shortest text that reads back as the same double.
    EXPECT_EQ(trace["x"][i].number(), x[i]) << "x[" << i << "]";
    EXPECT_EQ(std::signbit(trace["x"][i].number()), std::signbit(x[i])) << "x[" << i << "]";
    if (std::isfinite(y[i])) {
      EXPECT_EQ(trace["y"][i].number(), y[i]) << "y[" << i << "]";
    } else {
      EXPECT_TRUE(trace["y"][i].isNull()) << "y[" << i << "] = " << y[i] << " must be null";
    }
  }
  const auto& layout = doc[0]["layout"];
  EXPECT_EQ(layout["title"]["text"].string(), "p");
  EXPECT_EQ(layout["xaxis"]["title"]["text"].string(), "x [m]");
  EXPECT_EQ(layout["xaxis"]["type"].string(), "linear");
  EXPECT_EQ(layout["yaxis"]["type"].string(), "log");
  EXPECT_EQ(layout["height"].number(), 300.0);
}

TEST(ReportPage, OnePlotAreaPerPlotInOrder) {
  Page page("order");
  page.addHeading("First");
  Plot a;
  a.title = "A";
  page.addPlot(a);
  page.addText("between");
  Plot b;
  b.title = "B";
  page.addPlot(b);
  const std::string html = page.html(kFakeLibrary);
  const auto h = html.find("<h2>First</h2>");
  const auto p0 = html.find("id=\"geaware-plot-0\"");
  const auto t = html.find("between</p>");
  const auto p1 = html.find("id=\"geaware-plot-1\"");
  ASSERT_NE(p1, std::string::npos);
  EXPECT_LT(h, p0);
  EXPECT_LT(p0, t);
  EXPECT_LT(t, p1);
  EXPECT_EQ(html.find("geaware-plot-2"), std::string::npos);
  const auto doc = geaware_test::json::parse(embeddedJson(html));
  ASSERT_EQ(doc.array().size(), 2U);
  EXPECT_EQ(doc[1]["layout"]["title"]["text"].string(), "B");
}

TEST(ReportPage, WriteToAnUnwritablePathThrowsNamingIt) {
  const ScratchDir dir;
  // A path below a regular file cannot be created, even by root.
  const fs::path blocker = dir.path() / "not-a-dir";
  std::ofstream(blocker) << "x";
  const fs::path target = blocker / "page.html";
  try {
    samplePage().write(target);
    FAIL() << "write() to " << target << " did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
}

TEST(ReportPage, MissingLibraryThrowsNamingThePath) {
  const ScratchDir dir;
  const fs::path missing = dir.path() / "no-such-plotly.min.js";
  const EnvOverride env("GEAWARE_PLOTLY_JS", missing.string());
  EXPECT_EQ(geaware::report::plotlyJsPath(), missing);
  try {
    samplePage().write(dir.path() / "page.html");
    FAIL() << "write() without the library did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir.path() / "page.html"));
}

TEST(ReportPage, LibraryThatWouldCloseItsScriptIsRefused) {
  EXPECT_THROW((void)samplePage().html("var s = '</SCRIPT>';"), std::runtime_error);
}

TEST(ReportPage, InvalidContentIsRefusedWithTheReason) {
  EXPECT_THROW(Page(""), std::invalid_argument);
  Page page("bad");
  const auto message = [&](Plot plot) -> std::string {
    try {
      page.addPlot(std::move(plot));
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(no exception)";
  };
  Plot p;
  p.title = "thrust";
  p.series.push_back(Series{"short", {1.0, 2.0}, {1.0}, "lines", ""});
  EXPECT_NE(message(p).find("'short': x has 2 values, y has 1"), std::string::npos) << message(p);
  p.series[0] = Series{"m", {1.0}, {1.0}, "bars", ""};
  EXPECT_NE(message(p).find("mode 'bars'"), std::string::npos);
  p.series[0] = Series{"d", {1.0}, {1.0}, "lines", "dashdot"};
  EXPECT_NE(message(p).find("dash 'dashdot'"), std::string::npos);
  p.series[0] = Series{"ok", {1.0}, {1.0}, "lines", ""};
  p.height_px = 50;
  EXPECT_NE(message(p).find("height_px = 50"), std::string::npos);

  EXPECT_THROW(page.addTable(Table{"t", {"a", "b"}, {{"1", "2"}, {"3"}}}), std::invalid_argument);
  EXPECT_NO_THROW(page.addTable(Table{"headerless", {}, {{"1"}, {"2", "3"}}}));
}

TEST(ReportPage, HeatMapCellsRoundTripRowsTopToBottom) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  geaware::report::HeatMap map;
  map.title = "strikes";
  map.columns = {"none:none", "recommended"};
  map.rows = {"none", "mass+10%", "law <CB>"};
  map.z = {{0.0, 1.5}, {5.0, kNaN}, {2.0, 0.0}};
  map.text = {{"0/5", "1.5"}, {"5/5", "all struck"}, {"2/5", "0/5"}};
  map.z_label = "strikes [-]";
  map.z_max = 5.0;
  Page page("heat");
  page.addHeatMap(map);
  const auto doc = geaware_test::json::parse(embeddedJson(page.html(kFakeLibrary)));
  ASSERT_EQ(doc.array().size(), 1U);
  const auto& trace = doc[0]["data"][0];
  EXPECT_EQ(trace["type"].string(), "heatmap");
  EXPECT_EQ(trace["y"][2].string(), "law <CB>");
  EXPECT_EQ(trace["x"][1].string(), "recommended");
  EXPECT_EQ(trace["z"][1][0].number(), 5.0);
  EXPECT_TRUE(trace["z"][1][1].isNull());
  EXPECT_EQ(trace["text"][1][1].string(), "all struck");
  EXPECT_EQ(trace["zmax"].number(), 5.0);
  EXPECT_EQ(doc[0]["layout"]["yaxis"]["autorange"].string(), "reversed");
  // A row too short is refused with the heat map's name.
  map.z[2].pop_back();
  try {
    page.addHeatMap(map);
    FAIL() << "a short row was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("heat map 'strikes': z row 2"), std::string::npos)
        << e.what();
  }
}
// Links go to pages beside this one only: the names are checked, the labels escaped.
TEST(ReportPage, LinksPointBesideThePageOnly) {
  geaware::report::Page page("suite");
  page.addLinks("Pages", {{"ceiling <15 cm>", "beyond-04-ceiling-15cm.html"}});
  const std::string html = page.html(kFakeLibrary);
  EXPECT_NE(html.find("<li><a href=\"beyond-04-ceiling-15cm.html\">ceiling &lt;15 cm&gt;</a>"), std::string::npos);
  for (const std::string bad : {"", ".hidden.html", "../up.html", "dir/page.html", "javascript:alert(1)",
                                "https://example.org/x.html", "a b.html", "a\"b.html"}) {
    geaware::report::Page p("suite");
    EXPECT_THROW(p.addLinks("Pages", {{"x", bad}}), std::invalid_argument) << bad;
  }
}

