// maps::check_units on the example building read at the right and at wrong unit scales: the
// metric reading is plausible; a wrong one is named with the scale that makes it plausible.
#include <gtest/gtest.h>

#include "io/indoorgml.hpp"
#include "maps/unit_plausibility.hpp"

namespace {

using conicloc::maps::check_units;

conicloc::io::LoadedMap example_at(double unit_scale) {
  conicloc::io::MapLoadOptions options;
  options.unit_scale = unit_scale;
  return conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP, options);
}

TEST(UnitPlausibility, TheMetricExampleIsPlausible) {
  const auto loaded = example_at(1.0);
  const auto check = check_units(loaded.map, 1.0, true);
  EXPECT_TRUE(check.plausible) << check.problem;
  EXPECT_NEAR(check.storey_height_m, 3.0, 0.01);
  EXPECT_NEAR(check.extent_m, 18.0, 0.01);
  EXPECT_TRUE(check.problem.empty());
  EXPECT_FALSE(check.suggested_unit_scale);
}

TEST(UnitPlausibility, AWrongScaleIsNamedWithTheScaleThatFitsTheFile) {
  for (const double wrong : {0.001, 0.01, 10.0, 1000.0}) {
    const auto loaded = example_at(wrong);
    const auto check = check_units(loaded.map, wrong, true);
    EXPECT_FALSE(check.plausible) << wrong;
    EXPECT_NE(check.problem.find("storeys are"), std::string::npos) << check.problem;
    ASSERT_TRUE(check.suggested_unit_scale) << wrong;
    EXPECT_DOUBLE_EQ(*check.suggested_unit_scale, 1.0) << wrong;
    // The loader warns with the same hint.
    ASSERT_FALSE(loaded.report.warnings.empty()) << wrong;
    EXPECT_NE(loaded.report.warnings.back().find("--unit-scale 1)"), std::string::npos)
        << loaded.report.warnings.back();
  }
}

TEST(UnitPlausibility, WithoutMeasuredHeightsTheExtentDecides) {
  // As for a 2D-only model: heights are not the file's, a 100 km building is still absurd.
  const auto loaded = example_at(10000.0);
  const auto check = check_units(loaded.map, 10000.0, false);
  EXPECT_FALSE(check.plausible);
  EXPECT_NE(check.problem.find("180000 m across"), std::string::npos) << check.problem;
  ASSERT_TRUE(check.suggested_unit_scale);
  EXPECT_LT(*check.suggested_unit_scale * 18.0, 2000.0);
  EXPECT_TRUE(check_units(example_at(1.0).map, 1.0, false).plausible);
}

}  // namespace
