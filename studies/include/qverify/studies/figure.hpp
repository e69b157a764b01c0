#pragma once
/// \file figure.hpp
/// A study's figure as data: series of (x, y) points with their names, colours
/// and labels. The studies fill them; report/plot.hpp draws them as SVG.

#include <string>
#include <utility>
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

}  // namespace qverify
