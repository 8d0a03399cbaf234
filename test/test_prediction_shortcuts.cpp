// The predictor's shortcuts change nothing: the per-ring elevation rejection never rejects a
// polygon a ring's beams can hit (randomised, against a brute-force ray cast), and predictions
// with and without it agree exactly on the example building. (Crossing parity and yaw sharing:
// test_crossing_parity.cpp, test_yaw_shared_prediction.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "io/indoorgml.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "maps/planar_polygon.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/predicted_scan_compare.hpp"
#include "test/synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace cm = conicloc::maps;
namespace ct = conicloc::test;

namespace {

// Does any beam of `ring` (azimuth grid) hit `polygon` (sensor frame) at a positive range?
bool brute_force_hits(const cl::RingGeometry& ring, const cm::PlanarPolygon& polygon, int steps) {
  for (int i = 0; i < steps; ++i) {
    const double theta = 2.0 * std::numbers::pi * i / steps;
    const Eigen::Vector3d d = ring.direction(theta);
    const double den = polygon.plane.normal.dot(d);
    if (den == 0.0) continue;
    const double r = -(polygon.plane.normal.dot(ring.apex()) + polygon.plane.offset) / den;
    if (!(r > 0.0)) continue;
    if (polygon.contains_uv(polygon.frame.project(ring.apex() + r * d))) return true;
  }
  return false;
}

}  // namespace

TEST(ElevationRejection, NeverRejectsAPolygonTheRingHits) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int rejected = 0, hit = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    // A random convex quad or pentagon (a regular polygon, stretched) on a random plane near the
    // sensor, some straddling the spin axis; a random ring of elevation in ±20° (0 included).
    const Eigen::Vector3d centre(4.0 * unit(rng), 4.0 * unit(rng), 2.0 * unit(rng));
    Eigen::Vector3d normal(unit(rng), unit(rng), unit(rng));
    if (trial % 4 == 0) normal = Eigen::Vector3d(unit(rng), unit(rng), 0.0);  // walls
    if (trial % 4 == 1) normal = Eigen::Vector3d(0.0, 0.0, 1.0);              // floors
    if (!(normal.norm() > 1e-3)) continue;
    normal.normalize();
    const Eigen::Vector3d e_u = normal.unitOrthogonal(), e_v = normal.cross(e_u);
    const int corners = 4 + trial % 2;
    const double su = 0.2 + 3.0 * std::abs(unit(rng)), sv = 0.2 + 3.0 * std::abs(unit(rng));
    cm::Ring3 outer;
    for (int k = 0; k < corners; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / corners + 0.03 * unit(rng);
      outer.push_back(centre + su * std::cos(angle) * e_u + sv * std::sin(angle) * e_v);
    }
    cm::PlanarPolygon polygon;
    if (!cm::make_planar_polygon(outer, {}, polygon)) continue;
    const double elevation = trial % 7 == 0 ? 0.0 : 20.0 * std::numbers::pi / 180.0 * unit(rng);
    const cl::RingGeometry ring = cl::make_ring_geometry(elevation, 0.01 * unit(rng));
    std::vector<double> x, y, z;
    for (const auto& p : polygon.outer) {
      x.push_back(p.x());
      y.push_back(p.y());
      z.push_back(p.z());
    }
    const bool cuts = cl::ring_cuts_polygon(ring, x.data(), y.data(), z.data(), x.size());
    const bool hits = brute_force_hits(ring, polygon, 3600);
    if (!cuts) {
      ++rejected;
      EXPECT_FALSE(hits) << "trial " << trial;
    }
    hit += hits ? 1 : 0;
  }
  EXPECT_GT(rejected, 1000);  // the test is not vacuous either way
  EXPECT_GT(hit, 500);
}

TEST(ElevationRejection, PredictionsAreIdenticalWithAndWithoutIt) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  const cl::ConicScanPredictor with(map, ct::vlp16(), {});
  const cl::ConicScanPredictor without(map, ct::vlp16(), {.reject_by_elevation = false});
  EXPECT_GT(ct::expect_same_predictions(with, without, 1e-12, 4), 100000);
}
