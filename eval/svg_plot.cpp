#include "eval/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "io/xml_escape.hpp"

namespace conicloc::eval {
namespace {

constexpr std::array<const char*, 8> kPalette = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                                 "#9467bd", "#8c564b", "#e377c2", "#17becf"};

std::string format_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buffer;
}

// One axis: maps data values to pixels, in log10 space when asked.
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;  // in axis space (log10 of data when log)
  double pixel_lo = 0.0, pixel_hi = 1.0;

  bool accepts(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
  double to_axis(double v) const { return log ? std::log10(v) : v; }
  double to_pixel(double v) const {
    return pixel_lo + (to_axis(v) - lo) / (hi - lo) * (pixel_hi - pixel_lo);
  }
  // Log axes: decades; 1-2-5 within decades when fewer than three decades show; linear steps when
  // the range is under a factor of about 2.5 (they read as well there).
  std::vector<double> ticks() const {
    if (!log) return nice_ticks(lo, hi);
    for (const auto& mantissas : {std::vector<double>{1.0}, std::vector<double>{1.0, 2.0, 5.0}}) {
      std::vector<double> out;
      for (double e = std::floor(lo); e <= std::ceil(hi); e += 1.0) {
        for (const double m : mantissas) {
          const double v = m * std::pow(10.0, e);
          if (std::log10(v) >= lo - 1e-9 && std::log10(v) <= hi + 1e-9) out.push_back(v);
        }
      }
      if (out.size() >= 3) return out;
    }
    return nice_ticks(std::pow(10.0, lo), std::pow(10.0, hi), 4);
  }
};

void fit_range(Axis& axis, const std::vector<double>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values) {
    if (!axis.accepts(v)) continue;
    lo = std::min(lo, axis.to_axis(v));
    hi = std::max(hi, axis.to_axis(v));
  }
  if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-12) lo -= 0.5, hi += 0.5;
  const double pad = 0.05 * (hi - lo);
  axis.lo = lo - pad;
  axis.hi = hi + pad;
  if (!axis.log && lo >= 0.0 && axis.lo < 0.0) axis.lo = 0.0;  // errors and times start at 0
}

}  // namespace

std::string palette_colour(std::size_t index) {
  return kPalette[index % kPalette.size()];
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double raw = (hi - lo) / std::max(target, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * magnitude;
    if (step >= raw * (1.0 - 1e-9)) break;  // tolerate rounding of (hi − lo) / target
  }
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) ticks.push_back(t);
  return ticks;
}

std::string render_svg_plot(const std::vector<PlotSeries>& series, const PlotConfig& config) {
  const double left = 70, right = 170, top = 40, bottom = 55;
  Axis x_axis{config.log_x}, y_axis{config.log_y};
  std::vector<double> xs, ys;
  for (const auto& s : series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  fit_range(x_axis, xs);
  fit_range(y_axis, ys);
  x_axis.pixel_lo = left;
  x_axis.pixel_hi = config.width_px - right;
  y_axis.pixel_lo = config.height_px - bottom;  // y grows downwards in SVG
  y_axis.pixel_hi = top;

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << config.width_px << "\" height=\""
      << config.height_px << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << config.width_px / 2
      << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << io::escape_xml(config.title)
      << "</text>\n";

  for (double t : x_axis.ticks()) {
    const double px = x_axis.to_pixel(t);
    svg << "<line x1=\"" << px << "\" y1=\"" << top << "\" x2=\"" << px << "\" y2=\""
        << y_axis.pixel_lo << "\" stroke=\"#e0e0e0\"/>\n<text x=\"" << px << "\" y=\""
        << y_axis.pixel_lo + 16 << "\" text-anchor=\"middle\">" << format_number(t) << "</text>\n";
  }
  for (double t : y_axis.ticks()) {
    const double py = y_axis.to_pixel(t);
    svg << "<line x1=\"" << left << "\" y1=\"" << py << "\" x2=\"" << x_axis.pixel_hi << "\" y2=\""
        << py << "\" stroke=\"#e0e0e0\"/>\n<text x=\"" << left - 6 << "\" y=\"" << py + 4
        << "\" text-anchor=\"end\">" << format_number(t) << "</text>\n";
  }
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << x_axis.pixel_hi - left
      << "\" height=\"" << y_axis.pixel_lo - top << "\" fill=\"none\" stroke=\"black\"/>\n"
      << "<text x=\"" << (left + x_axis.pixel_hi) / 2 << "\" y=\"" << config.height_px - 12
      << "\" text-anchor=\"middle\">" << io::escape_xml(config.x_label) << "</text>\n"
      << "<text transform=\"translate(18," << (top + y_axis.pixel_lo) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << io::escape_xml(config.y_label) << "</text>\n";

  int legend_row = 0;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const auto& s = series[i];
    const std::string color =
        s.colour.empty() ? std::string(kPalette[i % kPalette.size()]) : io::escape_xml(s.colour);
    std::ostringstream points;
    std::size_t drawn = 0;
    for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k) {
      if (!x_axis.accepts(s.x[k]) || !y_axis.accepts(s.y[k])) continue;
      const double px = x_axis.to_pixel(s.x[k]), py = y_axis.to_pixel(s.y[k]);
      points << px << "," << py << " ";
      ++drawn;
      if (s.markers) {
        svg << "<circle cx=\"" << px << "\" cy=\"" << py << "\" r=\"3.5\" fill=\"" << color
            << "\"/>\n";
      }
    }
    if (s.lines && drawn > 1) {
      svg << "<polyline fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1.8\" points=\""
          << points.str() << "\"/>\n";
    }
    if (!s.in_legend) continue;
    const double ly = top + 10 + 20.0 * legend_row++;
    svg << "<rect x=\"" << x_axis.pixel_hi + 12 << "\" y=\"" << ly - 8 << "\" width=\"14\" "
        << "height=\"10\" fill=\"" << color << "\"/>\n<text x=\"" << x_axis.pixel_hi + 32
        << "\" y=\"" << ly + 1 << "\">" << io::escape_xml(s.label) << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace conicloc::eval
