// Classifying a polygon's azimuth intervals by crossing parity (localizer/polygon_arcs.hpp)
// gives the arcs of one midpoint test per interval: on random polygons with holes, at crossings
// exactly at θ = 0, at coincident crossings of a door hole and its wall, near a vertex, and for
// whole predictions of the example building.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "io/indoorgml.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/polygon_arcs.hpp"
#include "maps/planar_polygon.hpp"
#include "test/predicted_scan_compare.hpp"
#include "test/shared_buildings.hpp"
#include "test/synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace cm = conicloc::maps;
namespace ct = conicloc::test;

namespace {

// A polygon's arcs on one ring both ways, and whether the parity walk ran.
struct BothClassifications {
  std::vector<cl::PredictionWorkspace::Arc> parity, midpoint;
  bool walked = false;
};

BothClassifications clip_both_ways(const cl::RingGeometry& ring, const cm::PlanarPolygon& polygon,
                                   const cl::Pose3& T_map_sensor = cl::Pose3::Identity()) {
  cl::PredictionWorkspace workspace;
  cl::add_sensor_polygon(polygon, 0, T_map_sensor, workspace);
  BothClassifications out;
  out.walked = cl::append_polygon_arcs(ring, workspace.polygons[0], polygon, workspace, out.parity,
                                       cl::ArcClassification::kCrossingParity) ==
               cl::ArcClassification::kCrossingParity;
  cl::append_polygon_arcs(ring, workspace.polygons[0], polygon, workspace, out.midpoint,
                          cl::ArcClassification::kMidpointTests);
  return out;
}

}  // namespace

TEST(CrossingParity, GivesTheArcsOfOneMidpointTestPerInterval) {
  // Random polygons with up to three holes (some overlapping each other or the outer edge), on
  // random planes around the sensor, some with a vertex on purpose on a ring's cone.
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int with_arcs = 0, holes_cut = 0, walked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const cl::RingGeometry ring = cl::make_ring_geometry(
        trial % 5 == 0 ? 0.0 : 15.0 * std::numbers::pi / 180.0 * unit(rng), 0.01 * unit(rng));
    const Eigen::Vector3d centre(5.0 * unit(rng), 5.0 * unit(rng), 2.0 * unit(rng));
    Eigen::Vector3d normal(unit(rng), unit(rng), unit(rng));
    if (trial % 3 == 0) normal.z() = 0.0;  // walls
    if (!(normal.norm() > 1e-3)) continue;
    normal.normalize();
    const Eigen::Vector3d e_u = normal.unitOrthogonal(), e_v = normal.cross(e_u);
    auto ring3 = [&](const Eigen::Vector3d& middle, double size, int corners) {
      cm::Ring3 out;
      for (int k = 0; k < corners; ++k) {
        const double angle = 2.0 * std::numbers::pi * k / corners + 0.2 * unit(rng);
        out.push_back(middle + size * (1.0 + 0.3 * unit(rng)) *
                                   (std::cos(angle) * e_u + std::sin(angle) * e_v));
      }
      return out;
    };
    cm::Ring3 outer = ring3(centre, 1.0 + 3.0 * std::abs(unit(rng)), 3 + trial % 6);
    if (trial % 4 == 1) {
      // Put a vertex where the ring's beam at some azimuth meets the plane.
      const Eigen::Vector3d d = ring.direction(std::numbers::pi * unit(rng));
      const double den = normal.dot(d);
      const double r = normal.dot(centre - ring.apex()) / den;
      if (std::abs(den) > 0.1 && r > 0.5) outer[0] = ring.apex() + r * d;
    }
    std::vector<cm::Ring3> holes;
    for (int h = 0; h < trial % 4; ++h) {
      holes.push_back(ring3(centre + 1.5 * unit(rng) * e_u + 1.5 * unit(rng) * e_v,
                            0.3 + 0.8 * std::abs(unit(rng)), 3 + h));
    }
    cm::PlanarPolygon polygon;
    if (!cm::make_planar_polygon(outer, holes, polygon)) continue;
    const auto [parity, midpoint, parity_walked] = clip_both_ways(ring, polygon);
    walked += parity_walked ? 1 : 0;
    ASSERT_EQ(parity.size(), midpoint.size()) << "trial " << trial;
    for (std::size_t i = 0; i < parity.size(); ++i) {
      EXPECT_EQ(parity[i].begin_rad, midpoint[i].begin_rad) << "trial " << trial;
      EXPECT_EQ(parity[i].end_rad, midpoint[i].end_rad) << "trial " << trial;
    }
    with_arcs += parity.empty() ? 0 : 1;
    holes_cut += !polygon.holes_uv.empty() && parity.size() > 1 ? 1 : 0;
  }
  EXPECT_GT(with_arcs, 1000);  // not vacuous
  EXPECT_GT(holes_cut, 100);
  EXPECT_GT(walked, 2000);  // the parity walk ran, not only its fallback
}

TEST(CrossingParity, ACrossingAtAzimuthZeroLeavesTheOtherIntervalsRight) {
  // A floor whose edge lies on the line y = 0 under the apex: the ring crosses it at θ = 0
  // exactly (atan2(±0, 1) = ±0), so the first interval may be empty, its midpoint on the edge.
  const cl::RingGeometry ring = cl::make_ring_geometry(-15.0 * std::numbers::pi / 180.0, 0.0);
  const std::vector<cm::Ring3> outers = {
      {{1, 0, -0.5}, {3, 0, -0.5}, {3, 2, -0.5}, {1, 2, -0.5}},
      {{1, -2, -0.5}, {3, -2, -0.5}, {3, 0, -0.5}, {1, 0, -0.5}},
      {{-3, 0, -0.5}, {3, 0, -0.5}, {3, 2, -0.5}, {-3, 2, -0.5}},
      {{-3, -2, -0.5}, {3, -2, -0.5}, {3, 0, -0.5}, {-3, 0, -0.5}},
  };
  for (std::size_t o = 0; o < outers.size(); ++o) {
    cm::PlanarPolygon polygon;
    ASSERT_TRUE(cm::make_planar_polygon(outers[o], {}, polygon));
    const auto [parity, midpoint, walked] = clip_both_ways(ring, polygon);
    ASSERT_FALSE(midpoint.empty()) << o;
    ASSERT_EQ(parity.size(), midpoint.size()) << o;
    for (std::size_t i = 0; i < parity.size(); ++i) {
      EXPECT_EQ(parity[i].begin_rad, midpoint[i].begin_rad) << o;
      EXPECT_EQ(parity[i].end_rad, midpoint[i].end_rad) << o;
    }
  }
}

TEST(CrossingParity, ADoorHoleSharingTheWallsBottomEdgeKeepsTheParityWalk) {
  // A wall 6 m × 3 m at x = 3 with a door hole whose bottom edge lies on the wall's: the ring
  // crosses both bottom edges at the same azimuth. Each vertex ring flips at its own crossings,
  // so the walk is safe; inside/outside must match one midpoint test per interval everywhere but
  // within 1e-9 rad of a crossing.
  const cm::Ring3 wall = {{3, -3, 0}, {3, 3, 0}, {3, 3, 3}, {3, -3, 3}};
  const cm::Ring3 door = {{3, -0.5, 0}, {3, -0.5, 2.1}, {3, 0.5, 2.1}, {3, 0.5, 0}};
  cm::PlanarPolygon polygon;
  ASSERT_TRUE(cm::make_planar_polygon(wall, {door}, polygon));
  int compared = 0, in_door = 0, walked = 0;
  for (const double height : {0.3, 1.2, 2.5}) {
    for (const cl::RingGeometry& ring : cl::ring_geometry(ct::vlp16())) {
      const auto [parity, midpoint, parity_walked] =
          clip_both_ways(ring, polygon, cl::make_pose(0.0, 0.2, height, 0.0));
      walked += parity_walked ? 1 : 0;
      auto covered = [](const std::vector<cl::PredictionWorkspace::Arc>& arcs, double theta,
                        bool& near_end) {
        bool inside = false;
        for (const auto& arc : arcs) {
          near_end |=
              std::abs(theta - arc.begin_rad) < 1e-9 || std::abs(theta - arc.end_rad) < 1e-9;
          inside |= theta >= arc.begin_rad && theta < arc.end_rad;
        }
        return inside;
      };
      for (int i = 0; i < 7200; ++i) {
        const double theta = 2.0 * std::numbers::pi * (i + 0.5) / 7200;
        bool near_end = false;
        const bool by_parity = covered(parity, theta, near_end);
        const bool by_midpoint = covered(midpoint, theta, near_end);
        if (near_end) continue;
        EXPECT_EQ(by_parity, by_midpoint) << "height " << height << " ring " << ring.ring;
        ++compared;
        // Beams towards the door below its top, from a sensor lower than it, see through it.
        in_door += height < 2.1 && std::abs(std::tan(theta) * 3.0 - 0.2) < 0.5 &&
                           std::cos(theta) > 0 && ring.elevation_rad < 0.0 && !by_parity
                       ? 1
                       : 0;
      }
    }
  }
  EXPECT_GT(compared, 300000);
  EXPECT_GT(in_door, 100);  // the hole is cut out, not covered
  EXPECT_GT(walked, 24);    // with the coincident crossings, not by the fallback
}

TEST(CrossingParity, ACrossingNearAVertexFallsBackToMidpointTests) {
  // A floor quad whose corner V lies 2e-9 m outside the −15° ring's circle, with 30 m edges
  // meeting there at a shallow angle: both edges report a crossing just past V within the
  // wedge tolerance, far enough apart in azimuth to pass the gap test. Toggling at them would
  // invent an arc around V; such crossings must leave the classification to midpoint tests.
  const double phi = -15.0 * std::numbers::pi / 180.0, z = -0.5;
  const cl::RingGeometry ring = cl::make_ring_geometry(phi, 0.0);
  const double circle = -z / std::tan(-phi);
  for (const double outside : {2e-9, 1e-9, 5e-10}) {
    const Eigen::Vector3d V(circle + outside, 0, z);
    const double angle = 0.1, length = 30.0;
    const Eigen::Vector3d P = V + length * Eigen::Vector3d(std::sin(angle), -std::cos(angle), 0);
    const Eigen::Vector3d Q = V + length * Eigen::Vector3d(std::sin(angle), std::cos(angle), 0);
    cm::PlanarPolygon polygon;
    ASSERT_TRUE(cm::make_planar_polygon({P, V, Q, {circle + 40.0, 0, z}}, {}, polygon));
    const auto [parity, midpoint, walked] = clip_both_ways(ring, polygon);
    EXPECT_TRUE(midpoint.empty()) << outside;  // the circle passes outside the quad
    EXPECT_TRUE(parity.empty()) << outside;
  }
}

TEST(CrossingParity, PredictionsAreTheSameWithAndWithoutIt) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  const cl::ConicScanPredictor with(map, ct::vlp16(), {});
  const cl::ConicScanPredictor without(map, ct::vlp16(), {.classify_by_crossing_parity = false});
  EXPECT_GT(ct::expect_same_predictions(with, without, 0.0, 5), 100000);
}

TEST(CrossingParity, PredictionsAreTheSameOnThePublicBuildings) {
  const auto models = ct::shared_indoorgml_models();
  if (models.empty()) GTEST_SKIP() << "shared data absent: " << ct::shared_indoorgml_dir();
  for (const auto& path : models) {
    SCOPED_TRACE(path.filename().string());
    const auto map = conicloc::io::load_indoorgml(path.string()).map;
    const cl::ConicScanPredictor with(map, ct::vlp16(), {});
    const cl::ConicScanPredictor without(map, ct::vlp16(), {.classify_by_crossing_parity = false});
    EXPECT_GT(ct::expect_same_predictions(with, without, 0.0, 7, 10), 10000);
  }
  EXPECT_GE(models.size(), 4u);
}
