#include <gtest/gtest.h>

#include <cmath>

#include "eval/svg_plot.hpp"

namespace ce = conicloc::eval;

namespace {
std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}
}  // namespace

TEST(SvgPlot, NiceTicksAreRoundAndCoverTheRange) {
  const auto ticks = ce::nice_ticks(0.0, 9.3);
  ASSERT_FALSE(ticks.empty());
  EXPECT_DOUBLE_EQ(ticks.front(), 0.0);
  EXPECT_DOUBLE_EQ(ticks[1] - ticks[0], 2.0);  // 9.3 / 6 = 1.55 -> step 2
  EXPECT_LE(ticks.back(), 9.3);
  EXPECT_TRUE(ce::nice_ticks(1.0, 1.0).empty());
  const auto small = ce::nice_ticks(0.013, 0.021, 4);
  EXPECT_NEAR(small[1] - small[0], 0.002, 1e-12);
}

TEST(SvgPlot, SeriesBecomePolylinesMarkersAndLegend) {
  ce::PlotSeries a{"conic-beam", {1, 2, 3}, {0.1, 0.05, 0.03}, true, true};
  ce::PlotSeries b{"point<to>plane", {1, 2}, {0.2, 0.1}, true, false};
  ce::PlotConfig config;
  config.title = "error vs time";
  config.log_x = true;
  const auto svg = ce::render_svg_plot({a, b}, config);
  EXPECT_EQ(count(svg, "<polyline"), 2u);
  EXPECT_EQ(count(svg, "<circle"), 3u);
  EXPECT_NE(svg.find("point&lt;to&gt;plane"), std::string::npos);  // escaped legend text
  EXPECT_EQ(svg.rfind("</svg>\n"), svg.size() - 7);
}

TEST(SvgPlot, NonFiniteAndNonPositiveOnLogAxisAreSkipped) {
  ce::PlotSeries s{"s", {0.0, 1.0, 10.0, 100.0}, {1.0, NAN, 2.0, 3.0}, false, true};
  ce::PlotConfig config;
  config.log_x = true;
  const auto svg = ce::render_svg_plot({s}, config);
  EXPECT_EQ(count(svg, "<circle"), 2u);  // x = 0 (log) and y = NaN dropped
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}
