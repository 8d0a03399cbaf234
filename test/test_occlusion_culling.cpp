// Front-to-back occlusion culling (localizer/conic/occlusion_bins.hpp): azimuth spans of polygons
// around the sensor, bins that hide only what lies behind arcs already clipped, and predictions
// that are the same with and without the culling, in buildings where it leaves most pairs out.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "io/indoorgml.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/occlusion_bins.hpp"
#include "localizer/conic/polygon_groups.hpp"
#include "test/generated_map.hpp"
#include "test/predicted_scan_compare.hpp"
#include "test/synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;
using ct::generated_map;

namespace {

constexpr double kPi = std::numbers::pi;

cl::AzimuthSpan span_of(const std::vector<Eigen::Vector2d>& xy) {
  std::vector<double> x, y;
  for (const auto& p : xy) x.push_back(p.x()), y.push_back(p.y());
  return cl::polygon_azimuth_span(x.data(), y.data(), x.size());
}

// A sensor 0.8 m above the floor at the centre of each corridor cell of `map`.
struct CorridorView {
  const conicloc::maps::Cell* cell;
  cl::Pose3 pose;
};
std::vector<CorridorView> corridor_views(const conicloc::maps::PlaneMap& map) {
  std::vector<CorridorView> views;
  for (const auto& cell : map.cells) {
    if (cell.id.find("Corridor") == std::string::npos) continue;
    const Eigen::Vector3d c = cell.bounds.center();
    views.push_back({&cell, cl::make_pose(c.x(), c.y(), cell.floor_z + 0.8, 0.4)});
  }
  return views;
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

// Arcs that meet inside a bin (a floor's arc ending where a wall's begins) cover it together, out
// to the farther of their parts; with a gap between them the bin stays open.
TEST(OcclusionBins, ArcsMeetingInsideABinCoverItTogether) {
  const double w = 2.0 * kPi / cl::OcclusionBins::kBins;
  const cl::AzimuthSpan bin_10{.whole = false, .begin_rad = 10.3 * w, .width_rad = 0.4 * w};
  // A ring of 2 m (1/r = 0.5) up to the middle of bin 10, then one of 3 m from there on.
  cl::OcclusionBins joined;
  joined.cover(2.0 * w, 10.5 * w, 0.0, 0.0, 0.5);
  EXPECT_FALSE(joined.hides(bin_10, 10.0));  // half the bin is open
  joined.cover(10.5 * w, 20.0 * w, 0.0, 0.0, 1.0 / 3.0);
  EXPECT_TRUE(joined.hides(bin_10, 3.01));
  EXPECT_FALSE(joined.hides(bin_10, 2.99));  // the 3 m part is farther
  // Three parts, the middle one last and nearest: covered once it closes the bin, at 3 m.
  cl::OcclusionBins three;
  three.cover(9.0 * w, 10.2 * w, 0.0, 0.0, 1.0 / 3.0);
  three.cover(10.8 * w, 12.0 * w, 0.0, 0.0, 0.5);
  EXPECT_FALSE(three.hides(bin_10, 10.0));
  three.cover(10.2 * w, 10.8 * w, 0.0, 0.0, 1.0);
  EXPECT_TRUE(three.hides(bin_10, 3.01));
  EXPECT_FALSE(three.hides(bin_10, 2.99));
  // A wall x = 2 (1/r = cos θ / 2) over the first half of bin 5, a 1 m circle over the rest: the
  // wall's part reaches 2 / cos(5.5 w) = 2.33 m at its own end (2.42 m at the bin's far edge).
  cl::OcclusionBins wall;
  const cl::AzimuthSpan bin_5{.whole = false, .begin_rad = 5.2 * w, .width_rad = 0.6 * w};
  wall.cover(0.0, 5.5 * w, 0.5, 0.0, 0.0);
  wall.cover(5.5 * w, 8.0 * w, 0.0, 0.0, 1.0);
  EXPECT_TRUE(wall.hides(bin_5, 2.0 / std::cos(5.5 * w) + 1e-6));
  EXPECT_FALSE(wall.hides(bin_5, 2.0 / std::cos(5.5 * w) - 1e-6));
  // The last bin closed by a part that ends at 2π.
  cl::OcclusionBins last;
  const cl::AzimuthSpan bin_63{.whole = false, .begin_rad = 63.1 * w, .width_rad = 0.8 * w};
  last.cover(60.0 * w, 63.4 * w, 0.0, 0.0, 0.5);
  EXPECT_FALSE(last.hides(bin_63, 10.0));
  last.cover(63.4 * w, 2.0 * kPi, 0.0, 0.0, 0.5);
  EXPECT_TRUE(last.hides(bin_63, 2.01));
  // A gap of 1e-4 rad (a door's edge, not rounding) leaves the bin open.
  cl::OcclusionBins gap;
  gap.cover(2.0 * w, 10.5 * w, 0.0, 0.0, 0.5);
  gap.cover(10.5 * w + 1e-4, 20.0 * w, 0.0, 0.0, 0.5);
  EXPECT_FALSE(gap.hides(bin_10, 10.0));
}

// A wall seen at a grazing angle across a bin (7.5 m to 11.6 m) and a floor 9 m away where the
// wall lies farther (the ray reaches the floor first): the two bound the bin out to 9 m together,
// in either order, though the wall alone reaches 11.6 m and the floor covers only part of it.
TEST(OcclusionBins, ANearerArcTakesOverWhereItIsNearer) {
  const double w = 2.0 * kPi / cl::OcclusionBins::kBins;
  const double wall_foot = 10.0 * w - 1.3;  // 1/r = cos(θ − θ_foot) / 2: 2 m from the apex
  const double floor_begins = wall_foot + std::acos(2.0 / 9.0);
  ASSERT_GT(floor_begins, 10.0 * w);
  ASSERT_LT(floor_begins, 11.0 * w);
  const cl::AzimuthSpan bin_10{.whole = false, .begin_rad = 10.2 * w, .width_rad = 0.6 * w};
  const auto wall = [&](cl::OcclusionBins& bins) {
    bins.cover(9.0 * w, 12.0 * w, 0.5 * std::cos(wall_foot), 0.5 * std::sin(wall_foot), 0.0);
  };
  const auto floor = [&](cl::OcclusionBins& bins) {
    bins.cover(floor_begins, 12.0 * w, 0.0, 0.0, 1.0 / 9.0);
  };
  cl::OcclusionBins wall_first, floor_first;
  wall(wall_first);
  EXPECT_FALSE(wall_first.hides(bin_10, 11.0));  // the wall alone: 11.6 m
  EXPECT_TRUE(wall_first.hides(bin_10, 11.7));
  floor(wall_first);
  floor(floor_first);
  wall(floor_first);
  for (const cl::OcclusionBins* bins : {&wall_first, &floor_first}) {
    EXPECT_TRUE(bins->hides(bin_10, 9.0 + 1e-6));
    EXPECT_FALSE(bins->hides(bin_10, 9.0 - 1e-6));
  }
}

// More arcs in a bin than it keeps segments for (door jambs down a corridor): neighbours are
// joined, and the bin is still covered out to the farthest of them, no nearer; a gap among them
// keeps it open.
TEST(OcclusionBins, ManyArcsInOneBinCoverItOutToTheFarthest) {
  const double w = 2.0 * kPi / cl::OcclusionBins::kBins;
  const cl::AzimuthSpan bin_20{.whole = false, .begin_rad = 20.05 * w, .width_rad = 0.9 * w};
  cl::OcclusionBins joined, open;
  for (int k = 0; k < 10; ++k) {
    // Circles of 1 … 10 m, the farthest in the middle of the bin.
    const double range_m = 1.0 + ((k * 7) % 10);
    joined.cover((20.0 + 0.1 * k) * w, (20.0 + 0.1 * (k + 1)) * w, 0.0, 0.0, 1.0 / range_m);
    open.cover((20.0 + 0.1 * k) * w + (k == 5 ? 1e-4 : 0.0), (20.0 + 0.1 * (k + 1)) * w, 0.0, 0.0,
               1.0 / range_m);
  }
  EXPECT_TRUE(joined.hides(bin_20, 10.0 + 1e-6));
  EXPECT_FALSE(joined.hides(bin_20, 10.0 - 1e-6));
  EXPECT_FALSE(open.hides(bin_20, 100.0));
}

// Random arcs (1/r = R cos(θ − θ₀) + c: planes seen by a ring, some circles, some with their
// nearest point inside a bin), a few to a few dozen over a handful of bins, some aligned to
// eighths of a bin: no bin is ever bounded nearer than the arcs' envelope reaches inside it, and
// none counts as covered where no arc is. The envelope is sampled away from the arcs' ends (gaps
// up to the azimuth slack count as closed).
TEST(OcclusionBins, RandomArcsNeverBoundABinNearerThanTheirEnvelope) {
  const double w = 2.0 * kPi / cl::OcclusionBins::kBins;
  struct Arc {
    double begin, end, a, b, c;
  };
  int covered = 0;
  for (unsigned seed = 1; seed <= 1500; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int kind = static_cast<int>(seed % 3);  // within bins, eighths of bins, anywhere
    const int base = static_cast<int>(rng() % 60);
    cl::OcclusionBins bins;
    std::vector<Arc> arcs;
    const int n = 1 + static_cast<int>(rng() % 30);
    for (int i = 0; i < n; ++i) {
      double begin = 0.0, end = 0.0;
      if (kind == 0) {
        begin = (base + 3.0 * unit(rng)) * w;
        end = begin + 2.0 * unit(rng) * w;
      } else if (kind == 1) {
        begin = (base + static_cast<int>(24.0 * unit(rng)) / 8.0) * w;
        end = begin + (1 + static_cast<int>(rng() % 12)) / 8.0 * w;
      } else {
        begin = 2.0 * kPi * unit(rng);
        end = begin + kPi * unit(rng);
      }
      end = std::min(end, 2.0 * kPi);
      if (!(end > begin)) continue;
      const double R = unit(rng) < 0.2 ? 0.0 : unit(rng);
      const double foot = 2.0 * kPi * unit(rng);
      const Arc arc{begin, end, R * std::cos(foot), R * std::sin(foot), 2.0 * unit(rng) - 0.45};
      arcs.push_back(arc);
      bins.cover(arc.begin, arc.end, arc.a, arc.b, arc.c);
    }
    for (int bin = 0; bin < cl::OcclusionBins::kBins; ++bin) {
      double reach = 0.0;  // the envelope's farthest range over the bin's samples
      for (int k = 0; k <= 200; ++k) {
        const double theta = (bin + k / 200.0) * w;
        double envelope = std::numeric_limits<double>::infinity();
        bool near_an_end = false;
        for (const Arc& arc : arcs) {
          near_an_end =
              near_an_end || std::abs(theta - arc.begin) < 2e-7 || std::abs(theta - arc.end) < 2e-7;
          if (theta < arc.begin || theta > arc.end) continue;
          const double inverse = arc.a * std::cos(theta) + arc.b * std::sin(theta) + arc.c;
          if (inverse > 0.0) envelope = std::min(envelope, 1.0 / inverse);
        }
        if (!near_an_end) reach = std::max(reach, envelope);
      }
      const cl::AzimuthSpan inside{
          .whole = false, .begin_rad = (bin + 0.01) * w, .width_rad = 0.98 * w};
      if (std::isinf(reach)) {
        EXPECT_FALSE(bins.hides(inside, 1e12)) << "seed " << seed << " bin " << bin;
      } else {
        covered += bins.hides(inside, 2.0 * reach) ? 1 : 0;
        EXPECT_FALSE(bins.hides(inside, reach)) << "seed " << seed << " bin " << bin;
      }
    }
  }
  EXPECT_GT(covered, 1000);  // the bins do bound most covered bins
}

// A group's box as the sensor sees it bounds every point of the box: height, azimuth,
// elevation from any apex and distance; the height range is exact for a level sensor.
TEST(SensorBox, BoundsEveryPointOfTheBox) {
  const Eigen::AlignedBox3d box(Eigen::Vector3d(3.0, -1.0, 2.5), Eigen::Vector3d(7.0, 4.0, 5.0));
  const double max_offset = 0.02;
  const auto level = cl::sensor_box(box, cl::make_pose(0.5, 0.2, 1.0, 0.3), max_offset);
  EXPECT_NEAR(level.z_low, 1.5, 1e-12);
  EXPECT_NEAR(level.z_high, 4.0, 1e-12);
  EXPECT_NEAR(level.nearest_m, std::sqrt(2.5 * 2.5 + 1.5 * 1.5) - max_offset, 1e-12);
  for (const auto& pose :
       {cl::make_pose(0.5, 0.2, 1.0, 0.3), cl::make_pose(-2.0, 6.0, 0.4, 2.0, 0.1, -0.05),
        cl::make_pose(5.0, 1.0, 0.0, -1.0), cl::make_pose(5.0, 1.0, 8.0, 1.0, 0.0, 0.08)}) {
    const auto view = cl::sensor_box(box, pose, max_offset);
    const Eigen::Isometry3d to_sensor = pose.inverse();
    for (int i = 0; i <= 4; ++i) {
      for (int j = 0; j <= 4; ++j) {
        for (int k = 0; k <= 4; ++k) {
          const Eigen::Vector3d corner =
              box.min() + Eigen::Vector3d(i, j, k).cwiseProduct(box.sizes()) / 4.0;
          const Eigen::Vector3d q = to_sensor * corner;
          EXPECT_GE(q.z(), view.z_low - 1e-12);
          EXPECT_LE(q.z(), view.z_high + 1e-12);
          EXPECT_GE(q.norm(), view.nearest_m + max_offset - 1e-12);
          for (const double o : {-max_offset, max_offset}) {
            const double elevation = std::atan2(q.z() - o, std::hypot(q.x(), q.y()));
            EXPECT_GE(elevation, view.elevation_low);
            EXPECT_LE(elevation, view.elevation_high);
          }
          if (!view.span.whole) {
            double from_begin = std::atan2(q.y(), q.x()) - view.span.begin_rad;
            while (from_begin < 0.0) from_begin += 2.0 * kPi;
            EXPECT_LE(from_begin, view.span.width_rad);
          }
        }
      }
    }
  }
  // From inside the box's footprint it spans the circle.
  EXPECT_TRUE(cl::sensor_box(box, cl::make_pose(5.0, 1.0, 0.0, 0.0), max_offset).span.whole);
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

// Cost follows what a pose sees, not the size of the building: in a 10-storey building, a
// prediction over every polygon moves into the sensor frame only the polygons of the groups
// (rooms) that some ring cannot leave out whole, and a room of another storey is hidden behind
// the floor or ceiling the ring crosses first: at most those of the storeys within two of the
// pose's (a stairwell shows the next one and a little of the one after; measured 77–117 of 424,
// against 123–216 within two; 424 when no group is left out whole).
TEST(OcclusionCulling, AStoreyHidesTheRoomsOfTheOthers) {
  const auto map = generated_map("storeys", 1, {10, 1});
  const cl::ConicScanPredictor predictor(map, ct::vlp16(), {});
  cl::PredictedScan scan;
  for (const auto& [cell, pose] : corridor_views(map)) {
    predictor.predict(pose, scan);
    std::size_t near_storeys = 0;
    for (const auto& polygon : map.polygons) {
      if (polygon.storey < 0 || std::abs(polygon.storey - cell->storey) <= 2) ++near_storeys;
    }
    SCOPED_TRACE(cell->id);
    EXPECT_EQ(scan.polygons_considered, map.polygons.size());
    EXPECT_LE(scan.polygons_prepared, near_storeys);
  }
}

// Beyond the sensor's range nothing is seen: with a 6 m range in a 4-storey building, the rooms
// and storeys whose nearest point along a ring's rays lies farther are left out, and the
// predictions agree with the predictor that leaves nothing out at the same range.
TEST(OcclusionCulling, SurfacesBeyondTheRangeAreLeftOut) {
  const auto map = generated_map("storeys", 1, {4, 2});
  constexpr double kRange_m = 6.0;
  const cl::ConicScanPredictor with(map, ct::vlp16(), {}, kRange_m);
  const cl::ConicScanPredictor without(map, ct::vlp16(), {.skip_occluded = false}, kRange_m);
  EXPECT_GT(ct::expect_same_predictions(with, without, 1e-12, 11, 30, true), 30 * 16 * 600);
  const cl::ConicScanPredictor far(map, ct::vlp16(), {});
  cl::PredictedScan near_scan, far_scan;
  for (const auto& [cell, pose] : corridor_views(map)) {
    with.predict(pose, near_scan);
    far.predict(pose, far_scan);
    SCOPED_TRACE(cell->id);
    EXPECT_GT(near_scan.ring_polygons_beyond_range, 0U);
    EXPECT_LT(near_scan.polygons_prepared, far_scan.polygons_prepared);
  }
}

// A margin keeps the surfaces out to the range plus the margin (for the poses that take up a
// prediction's surfaces, cell_predictor_config()): a 6 m range with a 2 m margin leaves out and
// clips exactly what an 8 m range does, and names the same surface at every azimuth (only what
// reads as a return differs).
TEST(OcclusionCulling, ARangeMarginKeepsTheSurfacesWithinIt) {
  const auto map = generated_map("storeys", 1, {4, 2});
  const cl::ConicScanPredictor margin(map, ct::vlp16(), {.beyond_range_margin_m = 2.0}, 6.0);
  const cl::ConicScanPredictor plain(map, ct::vlp16(), {}, 6.0);
  const cl::ConicScanPredictor longer(map, ct::vlp16(), {}, 8.0);
  cl::PredictedScan with_margin, without, eight;
  long more_named = 0;  // pieces
  for (const auto& [cell, pose] : corridor_views(map)) {
    margin.predict(pose, with_margin);
    plain.predict(pose, without);
    longer.predict(pose, eight);
    SCOPED_TRACE(cell->id);
    EXPECT_EQ(with_margin.ring_polygons_beyond_range, eight.ring_polygons_beyond_range);
    EXPECT_EQ(with_margin.ring_polygons_occluded, eight.ring_polygons_occluded);
    EXPECT_EQ(with_margin.ring_polygons_clipped, eight.ring_polygons_clipped);
    EXPECT_EQ(with_margin.polygons_prepared, eight.polygons_prepared);
    EXPECT_GT(with_margin.ring_polygons_clipped, without.ring_polygons_clipped);
    for (std::size_t k = 0; k < with_margin.rings.size(); ++k) {
      const cl::PredictedRing& a = with_margin.rings[k];
      const cl::PredictedRing& b = eight.rings[k];
      EXPECT_EQ(a.boundary_rad, b.boundary_rad);
      EXPECT_EQ(a.polygon, b.polygon);
      EXPECT_DOUBLE_EQ(a.min_inverse_range, 1.0 / 6.0);
      more_named +=
          static_cast<long>(a.piece_count()) - static_cast<long>(without.rings[k].piece_count());
    }
  }
  EXPECT_GT(more_named, 0);
}
