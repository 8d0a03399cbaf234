// Front-to-back occlusion culling (localizer/conic/occlusion_bins.hpp): azimuth spans of polygons
// around the sensor, bins that hide only what lies behind arcs already clipped, and predictions
// that are the same with and without the culling, in buildings where it leaves most pairs out.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "io/indoorgml.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/occlusion_bins.hpp"
#include "sim/building_generator.hpp"
#include "test/predicted_scan_compare.hpp"
#include "test/synthetic_room.hpp"
#include "test/temp_path.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

constexpr double kPi = std::numbers::pi;

cl::AzimuthSpan span_of(const std::vector<Eigen::Vector2d>& xy) {
  std::vector<double> x, y;
  for (const auto& p : xy) x.push_back(p.x()), y.push_back(p.y());
  return cl::polygon_azimuth_span(x.data(), y.data(), x.size());
}

conicloc::maps::PlaneMap generated_map(const std::string& kind, std::uint64_t seed,
                                       const conicloc::sim::BuildingScale& scale = {}) {
  const auto path = ct::unique_temp_path(kind + ".gml");
  std::ofstream(path) << conicloc::sim::generate_building_gml(kind, seed, scale);
  auto map = conicloc::io::load_indoorgml(path.string()).map;
  std::filesystem::remove(path);
  return map;
}

}  // namespace

TEST(AzimuthSpan, AWallInFrontSpansWhatItsEndsSubtend) {
  // A vertical wall from (2, −2) to (2, 2), seen as a segment: ±45°.
  const auto span = span_of({{2.0, -2.0}, {2.0, 2.0}, {2.0, 2.0}, {2.0, -2.0}});
  ASSERT_FALSE(span.whole);
  EXPECT_NEAR(span.begin_rad, 2.0 * kPi - kPi / 4.0, 1e-6);  // wraps past 0
  EXPECT_NEAR(span.width_rad, kPi / 2.0, 1e-6);
  // Behind the sensor: 135° to 225°, no wrap.
  const auto behind = span_of({{-2.0, 2.0}, {-2.0, -2.0}, {-3.0, -2.0}, {-3.0, 2.0}});
  ASSERT_FALSE(behind.whole);
  EXPECT_NEAR(behind.begin_rad, 3.0 * kPi / 4.0, 1e-6);
  EXPECT_NEAR(behind.width_rad, kPi / 2.0, 1e-6);
}

TEST(AzimuthSpan, APolygonAroundOrOnTheSpinAxisSpansTheCircle) {
  EXPECT_TRUE(span_of({{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}).whole);  // a ceiling
  EXPECT_TRUE(span_of({{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}}).whole);                  // touches it
  EXPECT_TRUE(span_of({{-1.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {-1.0, 1.0}}).whole);    // edge on it
  // A C-shape wound around the axis without holding it spans more than half the circle.
  const auto c_shape = span_of({{1.0, -0.5},
                                {3.0, -3.0},
                                {-3.0, -3.0},
                                {-3.0, 3.0},
                                {3.0, 3.0},
                                {1.0, 0.5},
                                {-2.0, 2.0},
                                {-2.0, -2.0}});
  ASSERT_FALSE(c_shape.whole);
  EXPECT_GT(c_shape.width_rad, 1.5 * kPi);
}

TEST(OcclusionBins, HidesOnlyWhatLiesBehindArcsCoveringItsWholeSpan) {
  cl::OcclusionBins bins;
  // ±40° ahead (bins straddle 0: the span wraps).
  const cl::AzimuthSpan front{.whole = false, .begin_rad = 2.0 * kPi - 0.7, .width_rad = 1.4};
  EXPECT_FALSE(bins.hides(front, 100.0));  // nothing covered yet
  // A wall x = 2 (1/r = cos θ / 2) seen over ±60°; within the bins of ±40° (bins of 5.6°: out to
  // ±45°) its farthest point is 2 / cos 45° = 2.83 m.
  bins.cover(0.0, kPi / 3.0, 0.5, 0.0, 0.0);
  bins.cover(2.0 * kPi - kPi / 3.0, 2.0 * kPi, 0.5, 0.0, 0.0);
  EXPECT_TRUE(bins.hides(front, 2.9));
  EXPECT_FALSE(bins.hides(front, 2.5));  // nearer than the wall at the span's ends
  const cl::AzimuthSpan wider{.whole = false, .begin_rad = 2.0 * kPi - 1.2, .width_rad = 2.4};
  EXPECT_FALSE(bins.hides(wider, 50.0));  // reaches past the wall's ends
  EXPECT_FALSE(bins.hides(cl::AzimuthSpan{}, 50.0));
  // A ceiling 1 m above the apex seen by a 10° ring: 1/r = sin 10° everywhere, 5.76 m.
  bins.cover(0.0, 2.0 * kPi, 0.0, 0.0, std::sin(10.0 * kPi / 180.0));
  EXPECT_TRUE(bins.hides(cl::AzimuthSpan{}, 5.8));
  EXPECT_FALSE(bins.hides(cl::AzimuthSpan{}, 5.7));
  bins.reset();
  EXPECT_FALSE(bins.hides(front, 2.9));
}

// Where 1/r = c + R cos(θ − θ₀) is least inside a bin rather than at its edges, that least value
// bounds the bin: here the middle of bin 32 (θ = π + π/64), c − R = 0.2, so 5 m.
TEST(OcclusionBins, ABinReachesAsFarAsItsArcDoesBetweenTheEdges) {
  const double w = 2.0 * kPi / cl::OcclusionBins::kBins;
  const double phi = w / 2.0;  // 1/r least at φ + π
  cl::OcclusionBins bins;
  bins.cover(0.0, 2.0 * kPi, 0.1 * std::cos(phi), 0.1 * std::sin(phi), 0.3);
  const cl::AzimuthSpan in_bin{.whole = false, .begin_rad = kPi + 0.3 * w, .width_rad = 0.4 * w};
  EXPECT_FALSE(bins.hides(in_bin, 4.999));  // the edges alone would say 4.997 m
  EXPECT_TRUE(bins.hides(in_bin, 5.001));
}

// The culling changes no prediction: the same surface and range at every compared azimuth, in
// the example building, a hall with pillars and stacked storeys, where it leaves pairs out.
TEST(OcclusionCulling, PredictionsAreTheSameWithAndWithoutIt) {
  const auto check = [](const conicloc::maps::PlaneMap& map, const std::string& name,
                        double least_share_occluded) {
    SCOPED_TRACE(name);
    const cl::ConicScanPredictor with(map, ct::vlp16(), {});
    const cl::ConicScanPredictor without(map, ct::vlp16(), {.skip_occluded = false});
    // Coplanar polygons (a surface split between two cells) tie in range; which of them the
    // envelope names depends on the arcs around them, and the culling leaves some out.
    EXPECT_GT(ct::expect_same_predictions(with, without, 1e-12, 7, 30, true), 30 * 16 * 600);
    // How much was left out, over poses at sensor height in the middle of the building.
    cl::PredictedScan scan;
    std::size_t occluded = 0, pairs = 0;
    const Eigen::Vector3d mid = map.bounds.center();
    for (int i = 0; i < 10; ++i) {
      const double x = map.bounds.min().x() + (i + 0.5) / 10.0 * map.bounds.sizes().x();
      with.predict(cl::make_pose(x, mid.y(), map.storeys.front().floor_z + 0.8, 0.3 * i), scan);
      occluded += scan.ring_polygons_occluded;
      pairs += scan.polygons_considered * scan.rings.size();
    }
    EXPECT_GE(static_cast<double>(occluded), least_share_occluded * static_cast<double>(pairs));
  };
  // Shares of all (ring, polygon) pairs, most of which the elevation bands already leave out:
  // measured 5–10 %; these floors catch a culling that stopped working.
  check(conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map, "example building", 0.03);
  check(generated_map("hall", 2), "hall", 0.03);
  check(generated_map("storeys", 1, {4, 2}), "4 storeys x 2 plates", 0.07);
}
