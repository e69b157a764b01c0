#pragma once
/// \file plot.hpp
/// Minimal self-contained SVG plots for the reports (log-log scatter and lines).
/// No external dependency: the SVG is text, inlined as is into report.html.

#include <string>
#include <vector>

namespace qverify {

struct PlotSeries {
  std::string name, color;
  std::vector<std::pair<double, double>> points;  ///< (x, y); y == 0 is drawn on the "zero" floor
  bool line = true, markers = true, dashed = false;
  std::vector<std::string> labels;  ///< optional label per point
  bool labels_below = false;        ///< put the labels under the points (to separate two series)
};

struct Plot {
  std::string title, x_label, y_label;
  bool log_x = true, log_y = true;
  std::vector<PlotSeries> series;
  /// Optional vertical marker (e.g. where double breaks down), in data units.
  std::vector<std::pair<double, std::string>> x_marks;
  int width = 760, height = 480;
};

/// SVG text of the plot. Zero values on a log axis are drawn on a floor line
/// below the smallest non-zero value, labelled "0".
std::string render_svg(const Plot& plot);

/// Escapes &, <, > and quotes for HTML/SVG text.
std::string html_escape(const std::string& s);

}  // namespace qverify
