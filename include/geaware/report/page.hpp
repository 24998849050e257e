// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The project's one report module: self-contained HTML pages (open from disk, no server, no
// network) with interactive plots, and PNG export of a page through headless Chromium.
// Every command that makes figures (rig calibration, identification, the benchmark campaign)
// builds a Page and writes it. Usage and the build-time bundling of plotly.js: docs/report.md.

#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace geaware::report {

/// One curve or scatter of a plot. Non-finite values are written as gaps (JSON null).
struct Series {
  std::string name;
  std::vector<double> x;
  std::vector<double> y;
  std::string mode = "lines";  ///< "lines", "markers" or "lines+markers"
  std::string dash;            ///< "" (solid), "dash", "dot"
  std::string color{};         ///< CSS colour, e.g. "#1f77b4"; "": plotly's next colour
  std::string fill{};          ///< "" (none) or "tozeroy" (shade down to y = 0, e.g. terrain)
};

enum class AxisType { kLinear, kLog };

struct Plot {
  std::string title;
  std::string x_label;  ///< with unit, e.g. "h [m]"
  std::string y_label;
  std::vector<Series> series;
  AxisType x_axis = AxisType::kLinear;
  AxisType y_axis = AxisType::kLinear;
  int height_px = 420;  ///< height of the plot on the page [px], 100…4000
  bool equal_aspect = false;  ///< one unit as long on y as on x (x–y views of a trajectory)
};

/// A grid of coloured cells (plotly's heatmap trace), e.g. a result per case and controller.
/// Rows are drawn top to bottom in the order given. Non-finite values are empty cells.
struct HeatMap {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<std::string> columns;           ///< x labels, left to right
  std::vector<std::string> rows;              ///< y labels, top to bottom
  std::vector<std::vector<double>> z;         ///< [row][column]
  std::vector<std::vector<std::string>> text; ///< [row][column] shown in each cell; empty: none
  std::string z_label;                        ///< colour-bar title, with unit
  std::string colorscale = "Viridis";         ///< a plotly colour-scale name
  bool reverse_scale = false;                 ///< high values in the scale's first colour
  double z_min = 0.0;  ///< colour range; z_min = z_max: the data's own range
  double z_max = 0.0;
  int height_px = 420;  ///< 100…4000
};

struct Table {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

class Page {
 public:
  /// Throws std::invalid_argument if the title is empty.
  explicit Page(std::string title);

  /// A paragraph of plain text (escaped), e.g. the command that produced the page.
  void addText(std::string text);
  /// A section heading (escaped); blocks appear in the order they were added.
  void addHeading(std::string text);
  /// Throws std::invalid_argument naming the table when a row's width differs from the header's.
  void addTable(Table table);
  /// Throws std::invalid_argument naming the plot and series when x and y differ in length, or
  /// when mode, dash or height_px is not one of the documented values.
  void addPlot(Plot plot);
  /// Throws std::invalid_argument naming the heat map when z or text does not have one row per
  /// label and one value per column, or height_px is out of range.
  void addHeatMap(HeatMap map);
  /// A list of links to pages written beside this one (a suite's page per scenario): each a
  /// label (escaped) and a file name in the same directory. Throws std::invalid_argument naming
  /// the file when it is not a plain file name (empty, starting with '.', or holding anything but
  /// A–Z a–z 0–9 . _ + -): a page links to nothing elsewhere.
  void addLinks(std::string title, std::vector<std::pair<std::string, std::string>> label_and_file);

  /// Writes one self-contained HTML file (plotting library inlined). Throws std::runtime_error
  /// naming the file when it cannot be written, and naming the plotly.js path when the library
  /// cannot be read (see plotlyJsPath()).
  void write(const std::filesystem::path& html_file) const;

  /// The page as HTML text, with `plotly_js` inlined as the plotting library (write() passes
  /// the bundled plotly.min.js). Throws std::runtime_error if `plotly_js` contains "<script" or
  /// "</script", which would break out of the inline script element.
  [[nodiscard]] std::string html(const std::string& plotly_js) const;

  [[nodiscard]] const std::string& title() const { return title_; }

 private:
  struct Text {
    std::string text;
  };
  struct Heading {
    std::string text;
  };
  struct Links {
    std::string title;
    std::vector<std::pair<std::string, std::string>> items;  ///< label, file beside the page
  };
  using Block = std::variant<Text, Heading, Table, Plot, HeatMap, Links>;

  std::string title_;
  std::vector<Block> blocks_;
};

/// Where write() reads the minified plotly.js from, the first that applies: the environment
/// variable GEAWARE_PLOTLY_JS when set and non-empty; the installed copy beside the running
/// program (<prefix>/bin/../share/geaware/web/plotly.min.js); the copy CMake placed in the
/// build tree; the copy installed under the configured prefix.
[[nodiscard]] std::filesystem::path plotlyJsPath();

/// Renders `html_file` to `png_file` with headless Chromium at the given window size.
/// Throws std::runtime_error with the reason (no Chromium found, render failed).
void exportPng(const std::filesystem::path& html_file, const std::filesystem::path& png_file,
               int width_px = 1200, int height_px = 900);

/// Renders the whole of a page written by Page::write (every block, however tall, up to
/// 10000 px) to `png_file`, `width_px` wide. Throws std::runtime_error with the reason.
void exportPagePng(const std::filesystem::path& html_file, const std::filesystem::path& png_file,
                   int width_px = 1200);

}  // namespace geaware::report
