#pragma once
// Small self-contained SVG charts for evaluation reports: line and scatter series on linear or
// log10 axes, with ticks, labels and a legend. No plotting service needed.

#include <string>
#include <vector>

namespace conicloc::eval {

struct PlotSeries {
  std::string label;
  std::vector<double> x;
  std::vector<double> y;
  bool lines = true;     ///< connect the points in order
  bool markers = false;  ///< draw a circle per point
  std::string colour;    ///< any SVG colour; empty: the palette's, by series index
  bool in_legend = true;
};

/// The palette colour of series `index` (for series that should share a colour).
std::string palette_colour(std::size_t index);

struct PlotConfig {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_x = false;  ///< log10 axis; non-positive values are skipped
  bool log_y = false;
  int width_px = 720;
  int height_px = 440;
};

/// The chart as a standalone SVG document. Non-finite points are skipped; an empty chart still
/// renders its axes and title.
std::string render_svg_plot(const std::vector<PlotSeries>& series, const PlotConfig& config);

/// "Nice" tick positions covering [lo, hi]: steps of 1, 2 or 5 × 10^k, about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

}  // namespace conicloc::eval
