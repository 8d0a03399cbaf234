// The predictor's shortcuts change nothing: the per-ring elevation rejection never rejects a
// polygon a ring's beams can hit (randomised, against a brute-force ray cast), and predictions
// with and without it agree exactly on the example building; classifying arcs by crossing parity
// gives the arcs of one midpoint test per interval; a level prediction turned in azimuth is the
// prediction at the turned pose.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "io/indoorgml.hpp"
#include "localizer/conic_scan_predictor.hpp"
#include "localizer/polygon_arcs.hpp"
#include "localizer/yaw_shared_prediction.hpp"
#include "maps/planar_polygon.hpp"
#include "sensor/builtin_calibration.hpp"

namespace cl = conicloc::localizer;
namespace cm = conicloc::maps;

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
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  const cl::ConicScanPredictor with(map, calibration, {});
  const cl::ConicScanPredictor without(map, calibration, {.reject_by_elevation = false});
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::AlignedBox3d& box = map.bounds;
  cl::PredictedScan a, b;
  int compared = 0;
  for (int pose = 0; pose < 40; ++pose) {
    const Eigen::Vector3d p =
        box.min() +
        (box.max() - box.min()).cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    const cl::Pose3 T = cl::make_pose(p.x(), p.y(), p.z(), 6.3 * unit(rng), 0.1 * unit(rng) - 0.05,
                                      0.1 * unit(rng) - 0.05);
    with.predict(T, a);
    without.predict(T, b);
    ASSERT_EQ(a.rings.size(), b.rings.size());
    for (std::size_t k = 0; k < a.rings.size(); ++k) {
      for (int i = 0; i < 720; ++i) {
        const double theta = 2.0 * std::numbers::pi * (i + 0.5) / 720;
        const double ra = a.rings[k].range(theta), rb = b.rings[k].range(theta);
        if (std::isinf(ra) || std::isinf(rb)) {
          EXPECT_EQ(ra, rb) << pose << " " << k << " " << i;
        } else {
          EXPECT_NEAR(ra, rb, 1e-12 * ra) << pose << " " << k << " " << i;
        }
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 100000);
}

namespace {

// Predicted ranges of two scans agree at 720 azimuths per ring (both no-return, or within
// `relative` of each other), skipping azimuths within 1e-9 rad of a piece boundary of either.
int expect_same_ranges(const cl::PredictedScan& a, const cl::PredictedScan& b, double relative,
                       const std::string& where) {
  int compared = 0;
  EXPECT_EQ(a.rings.size(), b.rings.size()) << where;
  for (std::size_t k = 0; k < a.rings.size() && k < b.rings.size(); ++k) {
    const auto near_boundary = [](const cl::PredictedRing& ring, double theta) {
      const std::size_t i = ring.piece_at(theta);
      return theta - ring.boundary_rad[i] < 1e-9 || ring.boundary_rad[i + 1] - theta < 1e-9;
    };
    for (int i = 0; i < 720; ++i) {
      const double theta = 2.0 * std::numbers::pi * (i + 0.37) / 720;
      if (near_boundary(a.rings[k], theta) || near_boundary(b.rings[k], theta)) continue;
      const double ra = a.rings[k].range(theta), rb = b.rings[k].range(theta);
      if (std::isinf(ra) || std::isinf(rb)) {
        EXPECT_EQ(ra, rb) << where << " ring " << k << " azimuth " << theta;
      } else {
        EXPECT_NEAR(ra, rb, relative * ra) << where << " ring " << k << " azimuth " << theta;
      }
      ++compared;
    }
  }
  return compared;
}

}  // namespace

TEST(CrossingParity, GivesTheArcsOfOneMidpointTestPerInterval) {
  // Random polygons with up to three holes (some overlapping each other or the outer edge), on
  // random planes around the sensor, some with a vertex on purpose on a ring's cone.
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int with_arcs = 0, holes_cut = 0;
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
    cl::PredictionWorkspace workspace;
    cl::add_sensor_polygon(polygon, 0, cl::Pose3::Identity(), workspace);
    std::vector<cl::PredictionWorkspace::Arc> parity, midpoint;
    cl::append_polygon_arcs(ring, workspace.polygons[0], polygon, workspace, parity,
                            cl::ArcClassification::kCrossingParity);
    cl::append_polygon_arcs(ring, workspace.polygons[0], polygon, workspace, midpoint,
                            cl::ArcClassification::kMidpointTests);
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
    cl::PredictionWorkspace workspace;
    cl::add_sensor_polygon(polygon, 0, cl::Pose3::Identity(), workspace);
    std::vector<cl::PredictionWorkspace::Arc> parity, midpoint;
    cl::append_polygon_arcs(ring, workspace.polygons[0], polygon, workspace, parity,
                            cl::ArcClassification::kCrossingParity);
    cl::append_polygon_arcs(ring, workspace.polygons[0], polygon, workspace, midpoint,
                            cl::ArcClassification::kMidpointTests);
    ASSERT_FALSE(midpoint.empty()) << o;
    ASSERT_EQ(parity.size(), midpoint.size()) << o;
    for (std::size_t i = 0; i < parity.size(); ++i) {
      EXPECT_EQ(parity[i].begin_rad, midpoint[i].begin_rad) << o;
      EXPECT_EQ(parity[i].end_rad, midpoint[i].end_rad) << o;
    }
  }
}

TEST(CrossingParity, PredictionsAreTheSameWithAndWithoutIt) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  const cl::ConicScanPredictor with(map, calibration, {});
  const cl::ConicScanPredictor without(map, calibration, {.classify_by_crossing_parity = false});
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::AlignedBox3d& box = map.bounds;
  cl::PredictedScan a, b;
  int compared = 0;
  for (int pose = 0; pose < 40; ++pose) {
    const Eigen::Vector3d p =
        box.min() +
        (box.max() - box.min()).cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    const cl::Pose3 T = cl::make_pose(p.x(), p.y(), p.z(), 6.3 * unit(rng), 0.1 * unit(rng) - 0.05,
                                      0.1 * unit(rng) - 0.05);
    with.predict(T, a);
    without.predict(T, b);
    compared += expect_same_ranges(a, b, 0.0, "pose " + std::to_string(pose));
  }
  EXPECT_GT(compared, 100000);
}

TEST(YawSharedPrediction, ALevelPredictionTurnedInAzimuthIsThePredictionAtThatYaw) {
  const auto map = conicloc::io::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  const cl::ConicScanPredictor predictor(map, calibration, {});
  std::vector<int> all(map.polygons.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double cell = 0.25, angle = 2.0 * std::numbers::pi / 180.0;
  const Eigen::AlignedBox3d& box = map.bounds;
  cl::YawSharedPrediction shared;
  cl::PredictedScan turned, direct;
  int compared = 0;
  for (int position = 0; position < 12; ++position) {
    const Eigen::Vector3d p =
        box.min() +
        (box.max() - box.min()).cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    // Cell centres at this position: level ones at several yaw bins (turned from one
    // prediction), and a tilted one (predicted directly).
    for (const int yaw_bin : {0, 1, -7, 45, 90, -179, 180}) {
      for (const int pitch_bin : {0, 0, 1}) {
        const cl::AssociationCellKey key = cl::association_cell_of(
            cl::make_pose(p.x(), p.y(), p.z(), yaw_bin * angle, pitch_bin * angle), cell, angle);
        const cl::Pose3 centre = cl::association_cell_centre(key, cell, angle);
        shared.predict(predictor, centre, all, 1, cell, angle, turned);
        predictor.predict(centre, all, direct);
        compared += expect_same_ranges(
            turned, direct, 1e-9,
            "position " + std::to_string(position) + " yaw bin " + std::to_string(yaw_bin));
      }
    }
  }
  EXPECT_GT(compared, 1000000);
}
