// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/report/page.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>

#include <nlohmann/json.hpp>

#include "escape.hpp"

#if !defined(GEAWARE_PLOTLY_JS_BUILD_PATH) || !defined(GEAWARE_PLOTLY_JS_INSTALL_PATH) || \
    !defined(GEAWARE_PLOTLY_JS_RELATIVE_PATH)
#error "GEAWARE_PLOTLY_JS_*_PATH must name where plotly.min.js is copied and installed (src/report)"
#endif

namespace geaware::report {
namespace {

using detail::escapeHtml;
using detail::scriptSafeJson;

constexpr std::array<std::string_view, 3> kModes = {"lines", "markers", "lines+markers"};
constexpr std::array<std::string_view, 3> kDashes = {"", "dash", "dot"};
constexpr int kMinHeightPx = 100;
constexpr int kMaxHeightPx = 4000;

// The page's own look: a centred column, readable type, striped tables. Kept in one place so
// every report of the project looks the same.
constexpr std::string_view kStyle = R"css(
:root { --fg: #1f2328; --muted: #59636e; --line: #d1d9e0; --stripe: #f6f8fa; --accent: #0969da; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--fg); background: #fff;
       font: 15px/1.55 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", Arial, sans-serif; }
main { max-width: 1100px; margin: 0 auto; padding: 28px 32px 48px; }
h1 { font-size: 1.7em; margin: 0 0 12px; padding-bottom: 8px; border-bottom: 2px solid var(--line); }
h2 { font-size: 1.3em; margin: 32px 0 8px; }
h3 { font-size: 1.05em; margin: 0 0 6px; color: var(--muted); }
p.text { white-space: pre-wrap; margin: 8px 0; }
section.table { margin: 18px 0; overflow-x: auto; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; font-size: 0.93em; }
th, td { border: 1px solid var(--line); padding: 5px 10px; text-align: left; vertical-align: top; }
thead th { background: var(--stripe); font-weight: 600; }
tbody tr:nth-child(even) { background: var(--stripe); }
figure.plot { margin: 18px 0; border: 1px solid var(--line); border-radius: 6px; padding: 4px; }
footer { margin-top: 36px; color: var(--muted); font-size: 0.85em; }
)css";

// Turns the embedded JSON into plotly figures once the library has loaded. The data lives in
// a JSON script element rather than in JavaScript literals so that it is inert text.
constexpr std::string_view kInitScript = R"js(
(function () {
  var specs = JSON.parse(document.getElementById('geaware-plots').textContent);
  // No plotly logo and no "Share chart" (uploads to Plotly Cloud): a report stays offline.
  var config = { responsive: true, displaylogo: false, scrollZoom: false,
                 modeBarButtonsToRemove: ['sendChartToCloud'] };
  specs.forEach(function (spec, i) {
    Plotly.newPlot('geaware-plot-' + i, spec.data, spec.layout, config);
  });
  // The whole page's height, for a PNG of the whole page (report::exportPagePng).
  document.documentElement.setAttribute('data-geaware-height',
                                        String(document.documentElement.scrollHeight));
})();
)js";

const char* axisType(AxisType t) { return t == AxisType::kLog ? "log" : "linear"; }

// One plot as plotly's {data, layout}; NaN becomes null, which plotly draws as a gap.
nlohmann::ordered_json plotJson(const Plot& plot) {
  nlohmann::ordered_json data = nlohmann::ordered_json::array();
  for (const Series& series : plot.series) {
    nlohmann::ordered_json trace = {
        {"type", "scatter"}, {"name", series.name}, {"mode", series.mode}};
    nlohmann::ordered_json style = nlohmann::ordered_json::object();
    if (!series.dash.empty()) style["dash"] = series.dash;
    if (!series.color.empty()) style["color"] = series.color;
    if (!style.empty()) trace["line"] = style;
    if (!series.color.empty()) trace["marker"] = {{"color", series.color}};
    if (!series.fill.empty()) trace["fill"] = series.fill;
    trace["x"] = series.x;
    trace["y"] = series.y;
    data.push_back(std::move(trace));
  }
  nlohmann::ordered_json y_axis = {{"title", {{"text", plot.y_label}}},
                                   {"type", axisType(plot.y_axis)},
                                   {"zeroline", false}};
  // Equal aspect: one metre is as long on the y axis as on the x axis (trajectories seen from
  // above keep their shape).
  if (plot.equal_aspect) y_axis.update({{"scaleanchor", "x"}, {"scaleratio", 1}});
  nlohmann::ordered_json layout = {
      {"title", {{"text", plot.title}}},
      {"xaxis", {{"title", {{"text", plot.x_label}}}, {"type", axisType(plot.x_axis)}, {"zeroline", false}}},
      {"yaxis", std::move(y_axis)},
      {"height", plot.height_px},
      {"margin", {{"l", 70}, {"r", 30}, {"t", 50}, {"b", 60}}},
      {"font", {{"family", "system-ui, 'DejaVu Sans', Arial, sans-serif"}}},
      {"hovermode", "closest"}};
  return {{"data", std::move(data)}, {"layout", std::move(layout)}};
}

// A heat map as plotly's {data, layout}: one heatmap trace, rows top to bottom.
nlohmann::ordered_json heatMapJson(const HeatMap& map) {
  nlohmann::ordered_json trace = {{"type", "heatmap"},
                                  {"x", map.columns},
                                  {"y", map.rows},
                                  {"z", map.z},
                                  {"colorscale", map.colorscale},
                                  {"reversescale", map.reverse_scale},
                                  {"colorbar", {{"title", {{"text", map.z_label}}}}},
                                  {"hoverongaps", false}};
  if (map.z_min < map.z_max) trace.update({{"zmin", map.z_min}, {"zmax", map.z_max}});
  if (!map.text.empty()) {
    trace["text"] = map.text;
    trace["texttemplate"] = "%{text}";
  }
  nlohmann::ordered_json layout = {
      {"title", {{"text", map.title}}},
      {"xaxis", {{"title", {{"text", map.x_label}}}, {"type", "category"}, {"automargin", true}}},
      {"yaxis",
       {{"title", {{"text", map.y_label}}},
        {"type", "category"},
        {"autorange", "reversed"},
        {"automargin", true}}},
      {"height", map.height_px},
      {"margin", {{"l", 110}, {"r", 30}, {"t", 50}, {"b", 90}}},
      {"font", {{"family", "system-ui, 'DejaVu Sans', Arial, sans-serif"}}}};
  return {{"data", nlohmann::ordered_json::array({std::move(trace)})}, {"layout", std::move(layout)}};
}

std::string tableHtml(const Table& table) {
  std::string out = "<section class=\"table\">\n";
  if (!table.title.empty()) out += "<h3>" + escapeHtml(table.title) + "</h3>\n";
  out += "<table>\n";
  if (!table.header.empty()) {
    out += "<thead><tr>";
    for (const auto& h : table.header) out += "<th>" + escapeHtml(h) + "</th>";
    out += "</tr></thead>\n";
  }
  out += "<tbody>\n";
  for (const auto& row : table.rows) {
    out += "<tr>";
    for (const auto& cell : row) out += "<td>" + escapeHtml(cell) + "</td>";
    out += "</tr>\n";
  }
  out += "</tbody>\n</table>\n</section>\n";
  return out;
}

bool containsNoCase(std::string_view haystack, std::string_view needle) {
  const auto it = std::search(haystack.begin(), haystack.end(), needle.begin(), needle.end(),
                              [](char a, char b) {
                                return std::tolower(static_cast<unsigned char>(a)) ==
                                       std::tolower(static_cast<unsigned char>(b));
                              });
  return it != haystack.end();
}

std::string readFile(const std::filesystem::path& file, const char* what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw std::runtime_error(std::string("report: cannot read ") + what + " '" + file.string() +
                             "': " + std::strerror(errno) +
                             " (set GEAWARE_PLOTLY_JS to a plotly.min.js, or rebuild so that "
                             "CMake bundles it from web/package-lock.json)");
  }
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad() || text.empty()) {
    throw std::runtime_error(std::string("report: ") + what + " '" + file.string() +
                             "' is empty or unreadable");
  }
  return text;
}

}  // namespace

Page::Page(std::string title) : title_(std::move(title)) {
  if (title_.empty()) throw std::invalid_argument("report::Page: the title is empty");
}

void Page::addText(std::string text) { blocks_.emplace_back(Text{std::move(text)}); }

void Page::addHeading(std::string text) { blocks_.emplace_back(Heading{std::move(text)}); }

void Page::addLinks(std::string title, std::vector<std::pair<std::string, std::string>> label_and_file) {
  for (const auto& [label, file] : label_and_file) {
    const bool plain = !file.empty() && file.front() != '.' &&
                       std::all_of(file.begin(), file.end(), [](char ch) {
                         return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') ||
                                ch == '.' || ch == '_' || ch == '+' || ch == '-';
                       });
    if (!plain) {
      throw std::invalid_argument("report::Page: links '" + title + "': '" + file +
                                  "' is not a file name beside the page (A-Z a-z 0-9 . _ + -, not starting with '.')");
    }
  }
  blocks_.emplace_back(Links{std::move(title), std::move(label_and_file)});
}

void Page::addTable(Table table) {
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    if (!table.header.empty() && table.rows[r].size() != table.header.size()) {
      throw std::invalid_argument("report::Page: table '" + table.title + "' row " +
                                  std::to_string(r) + " has " +
                                  std::to_string(table.rows[r].size()) + " cells, the header " +
                                  std::to_string(table.header.size()));
    }
  }
  blocks_.emplace_back(std::move(table));
}

void Page::addPlot(Plot plot) {
  const std::string where = "report::Page: plot '" + plot.title + "'";
  if (plot.height_px < kMinHeightPx || plot.height_px > kMaxHeightPx) {
    throw std::invalid_argument(where + ": height_px = " + std::to_string(plot.height_px) +
                                " is outside [" + std::to_string(kMinHeightPx) + ", " +
                                std::to_string(kMaxHeightPx) + "]");
  }
  for (const Series& s : plot.series) {
    const std::string series = where + " series '" + s.name + "'";
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument(series + ": x has " + std::to_string(s.x.size()) +
                                  " values, y has " + std::to_string(s.y.size()));
    }
    if (std::find(kModes.begin(), kModes.end(), s.mode) == kModes.end()) {
      throw std::invalid_argument(series + ": mode '" + s.mode +
                                  "' is not one of lines, markers, lines+markers");
    }
    if (std::find(kDashes.begin(), kDashes.end(), s.dash) == kDashes.end()) {
      throw std::invalid_argument(series + ": dash '" + s.dash +
                                  "' is not one of \"\" (solid), dash, dot");
    }
    if (!s.fill.empty() && s.fill != "tozeroy") {
      throw std::invalid_argument(series + ": fill '" + s.fill + "' is not one of \"\", tozeroy");
    }
  }
  blocks_.emplace_back(std::move(plot));
}

void Page::addHeatMap(HeatMap map) {
  const std::string where = "report::Page: heat map '" + map.title + "'";
  if (map.height_px < kMinHeightPx || map.height_px > kMaxHeightPx) {
    throw std::invalid_argument(where + ": height_px = " + std::to_string(map.height_px) +
                                " is outside [" + std::to_string(kMinHeightPx) + ", " +
                                std::to_string(kMaxHeightPx) + "]");
  }
  const auto check = [&](const auto& grid, const char* what) {
    if (grid.size() != map.rows.size()) {
      throw std::invalid_argument(where + ": " + what + " has " + std::to_string(grid.size()) +
                                  " rows, the labels " + std::to_string(map.rows.size()));
    }
    for (std::size_t r = 0; r < grid.size(); ++r) {
      if (grid[r].size() != map.columns.size()) {
        throw std::invalid_argument(where + ": " + what + " row " + std::to_string(r) + " has " +
                                    std::to_string(grid[r].size()) + " values, the columns " +
                                    std::to_string(map.columns.size()));
      }
    }
  };
  check(map.z, "z");
  if (!map.text.empty()) check(map.text, "text");
  blocks_.emplace_back(std::move(map));
}

std::string Page::html(const std::string& plotly_js) const {
  // The library is inlined verbatim, so it must not contain anything that ends or nests the
  // <script> element (HTML spec 4.12.1.3). plotly.min.js has neither; check rather than assume.
  if (containsNoCase(plotly_js, "</script") || containsNoCase(plotly_js, "<script")) {
    throw std::runtime_error(
        "report: the plotting library contains \"<script\" or \"</script\" and cannot be inlined");
  }

  std::string body;
  nlohmann::ordered_json plots = nlohmann::ordered_json::array();
  int plot_count = 0;
  for (const Block& block : blocks_) {
    std::visit(
        [&](const auto& b) {
          using B = std::decay_t<decltype(b)>;
          if constexpr (std::is_same_v<B, Text>) {
            body += "<p class=\"text\">" + escapeHtml(b.text) + "</p>\n";
          } else if constexpr (std::is_same_v<B, Heading>) {
            body += "<h2>" + escapeHtml(b.text) + "</h2>\n";
          } else if constexpr (std::is_same_v<B, Table>) {
            body += tableHtml(b);
          } else if constexpr (std::is_same_v<B, Links>) {
            // The file names were checked by addLinks: plain names beside this page.
            body += "<section class=\"links\">\n<h3>" + escapeHtml(b.title) + "</h3>\n<ul>\n";
            for (const auto& [label, file] : b.items) {
              body += "<li><a href=\"" + escapeHtml(file) + "\">" + escapeHtml(label) + "</a> (" +
                      escapeHtml(file) + ")</li>\n";
            }
            body += "</ul>\n</section>\n";
          } else {
            const std::string id = "geaware-plot-" + std::to_string(plot_count);
            body += "<figure class=\"plot\"><div class=\"plot-area\" id=\"" + id +
                    "\" style=\"height:" + std::to_string(b.height_px) + "px\"></div></figure>\n";
            if constexpr (std::is_same_v<B, HeatMap>) {
              plots.push_back(heatMapJson(b));
            } else {
              plots.push_back(plotJson(b));
            }
            ++plot_count;
          }
        },
        block);
  }
  const std::string plots_json = scriptSafeJson(
      plots.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace));

  std::string out;
  out.reserve(plotly_js.size() + body.size() + plots_json.size() + 4096);
  out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += "<meta name=\"generator\" content=\"geaware report\">\n";
  out += "<title>" + escapeHtml(title_) + "</title>\n";
  out += "<style>";
  out += kStyle;
  out += "</style>\n<script>\n";
  out += plotly_js;
  out += "\n</script>\n</head>\n<body>\n<main>\n";
  out += "<h1>" + escapeHtml(title_) + "</h1>\n";
  out += body;
  out +=
      "<footer>Written by geaware. Self-contained: opens from disk, needs no network. "
      "Plots by plotly.js (MIT licence).</footer>\n";
  out += "</main>\n<script type=\"application/json\" id=\"geaware-plots\">\n";
  out += plots_json;
  out += "\n</script>\n<script>";
  out += kInitScript;
  out += "</script>\n</body>\n</html>\n";
  return out;
}

void Page::write(const std::filesystem::path& html_file) const {
  const std::string page = html(readFile(plotlyJsPath(), "the plotly.js bundle"));
  // Whole or not at all: a temporary file beside the page, renamed over it once written (a
  // symlinked page is written through to its target). The report layer sees no other layer,
  // so this is io::AtomicFile's rule in a few lines.
  std::error_code ec;
  const std::filesystem::path target =
      std::filesystem::is_symlink(html_file, ec) ? std::filesystem::canonical(html_file, ec) : html_file;
  if (std::filesystem::exists(target, ec) && !std::filesystem::is_regular_file(target, ec)) {
    throw std::runtime_error("report: '" + html_file.string() + "' exists and is not a regular file");
  }
  std::filesystem::path temp = target;
  temp += ".geaware-tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw std::runtime_error("report: cannot write '" + html_file.string() + "': " + std::strerror(errno));
    }
    out.write(page.data(), static_cast<std::streamsize>(page.size()));
    out.close();
    if (!out) {
      const int e = errno;
      std::filesystem::remove(temp, ec);
      throw std::runtime_error("report: writing '" + html_file.string() + "' failed: " + std::strerror(e));
    }
  }
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw std::runtime_error("report: cannot replace '" + html_file.string() + "': " + ec.message());
  }
}

std::filesystem::path plotlyJsPath() {
  if (const char* env = std::getenv("GEAWARE_PLOTLY_JS"); env != nullptr && *env != '\0') {
    return env;
  }
  namespace fs = std::filesystem;
  std::error_code ec;
  auto exists = [&](const fs::path& p) { return fs::is_regular_file(p, ec); };
  // An installed program finds the bundle beside it (<prefix>/bin/../share/geaware/web), wherever
  // the prefix was moved to (a Debian package installs under /usr).
  if (const fs::path exe = fs::read_symlink("/proc/self/exe", ec); !ec && !exe.empty()) {
    if (const fs::path p = exe.parent_path() / GEAWARE_PLOTLY_JS_RELATIVE_PATH; exists(p)) {
      return p.lexically_normal();
    }
  }
  // A program of this build tree (tests, the CLI before install), then a program of another
  // project linking the installed library.
  if (const fs::path p = GEAWARE_PLOTLY_JS_BUILD_PATH; exists(p)) return p;
  if (const fs::path p = GEAWARE_PLOTLY_JS_INSTALL_PATH; exists(p)) return p;
  return GEAWARE_PLOTLY_JS_BUILD_PATH;  // named in the error when nothing is found
}

}  // namespace geaware::report
