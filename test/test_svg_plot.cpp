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
  ce::PlotSeries a{"conic-beam", {1, 2, 3}, {0.1, 0.05, 0.03}, true, true, "", true};
  ce::PlotSeries b{"point<to>plane", {1, 2}, {0.2, 0.1}, true, false, "", true};
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
  ce::PlotSeries s{"s", {0.0, 1.0, 10.0, 100.0}, {1.0, NAN, 2.0, 3.0}, false, true, "", true};
  ce::PlotConfig config;
  config.log_x = true;
  const auto svg = ce::render_svg_plot({s}, config);
  EXPECT_EQ(count(svg, "<circle"), 2u);  // x = 0 (log) and y = NaN dropped
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(SvgPlot, LogAxisWithinADecadeStillHasTicks) {
  // 0.021 … 0.027 m: no decade and no 1-2-5 value inside but 0.02's neighbourhood; linear steps.
  ce::PlotSeries s{"s", {10.0, 20.0}, {0.021, 0.027}, false, true, "", true};
  ce::PlotConfig config;
  config.log_y = true;
  const auto svg = ce::render_svg_plot({s}, config);
  EXPECT_GE(count(svg, "text-anchor=\"end\""), 2u) << svg;  // y tick labels
  // 3 … 300: decades 10 and 100 plus 1-2-5 values 5, 20, 50, 200.
  ce::PlotSeries wide{"w", {1.0, 2.0}, {3.0, 300.0}, false, true, "", true};
  const auto wide_svg = ce::render_svg_plot({wide}, config);
  for (const char* label : {">5</text>", ">20</text>", ">50</text>", ">200</text>"}) {
    EXPECT_NE(wide_svg.find(label), std::string::npos) << label;
  }
}
