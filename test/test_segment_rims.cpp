// The ends of a segment's polygon on its scan line (localizer/models/segment_rims.hpp): the
// returns a segment holds beyond its polygon's arc, moved with the pose, against a count over the
// full prediction at that pose; and what they add to conic-segment along a corridor, where the
// planes alone say nothing of the position.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/models/conic_segment_model.hpp"
#include "localizer/models/correlated_terms.hpp"
#include "localizer/models/scan_line_segmentation.hpp"
#include "localizer/models/segment_landmarks.hpp"
#include "localizer/models/segment_rims.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;
using Eigen::Vector3d;

namespace {

// A corridor 40 m long (x), 2.4 m wide, 3 m high, open at both ends (beyond the rings' reach of
// floor and ceiling), whose wall at y = 2.4 has two door openings (x in [18, 19] and [22.5,
// 23.5]) onto a hall whose back wall stands at y = 6. Every plane runs along x: only the
// openings' edges tell where along the corridor a pose is.
conicloc::maps::PlaneMap make_corridor_with_doors() {
  conicloc::maps::PlaneMap map;
  map.storeys.push_back({"ground", 0.0, 3.0});
  conicloc::maps::Cell cell;
  cell.id = "corridor";
  cell.storey = 0;
  cell.footprint = {{0, 0}, {40, 0}, {40, 6}, {0, 6}};
  cell.bounds = Eigen::AlignedBox3d(Vector3d(0, 0, 0), Vector3d(40, 6, 3));
  cell.floor_z = 0.0;
  cell.ceiling_z = 3.0;
  cell.representative_point = {20, 1.2, 0};
  map.cells.push_back(cell);
  ct::add_quad(map, 0, {0, 0, 0}, {40, 0, 0}, {40, 6, 0}, {0, 6, 0});  // floor, +z
  ct::add_quad(map, 0, {0, 0, 3}, {0, 6, 3}, {40, 6, 3}, {40, 0, 3});  // ceiling, −z
  ct::add_quad(map, 0, {0, 0, 0}, {0, 0, 3}, {40, 0, 3}, {40, 0, 0});  // y = 0, +y
  ct::add_quad(map, 0, {0, 6, 0}, {40, 6, 0}, {40, 6, 3}, {0, 6, 3});  // back wall, −y
  for (const auto& [from, to] : {std::pair{0.0, 18.0}, {19.0, 22.5}, {23.5, 40.0}}) {
    ct::add_quad(map, 0, {from, 2.4, 0}, {to, 2.4, 0}, {to, 2.4, 3}, {from, 2.4, 3});  // −y
  }
  return map;
}

conicloc::sensor::Scan scan_at(const conicloc::maps::PlaneMap& map, const cl::Pose3& pose,
                               double sigma_m) {
  return ct::make_scan(map, pose, 0.4 * M_PI / 180.0, sigma_m, 7);
}

}  // namespace

// A particle at the truth or off it, in a cell whose centre is off both: the returns each term's
// rims count beyond its polygon's arc agree with the returns the full prediction at the
// particle's pose puts on another surface, to within the rounding of one return per rim.
TEST(SegmentRims, ReturnsBeyondTheArcAreThoseTheFullPredictionPutsElsewhere) {
  const auto map = make_corridor_with_doors();
  const cl::Pose3 truth = cl::make_pose(20.3, 1.2, 1.2, 0.3);
  const auto scan = scan_at(map, truth, 0.0);
  const cl::ConicScanPredictor predictor(map, ct::vlp16());
  std::vector<cl::ConicSegment> segments;
  std::vector<cl::SegmentFit> fits;
  std::vector<cl::CandidateTerm> fit_terms;
  for (std::size_t r = 0; r < scan.rings.size(); ++r) {
    for (const auto& segment : cl::segment_scan_line(scan.rings[r], {}, 100.0)) {
      segments.push_back(segment);
      fits.push_back(cl::make_segment_fit(scan.rings[r], segment, static_cast<int>(r), 0.3, 100.0));
      fit_terms.push_back(cl::candidate_term(fits.back(), predictor.rings()[r]));
    }
  }
  const cl::Pose3 centre = cl::make_pose(20.4, 1.15, 1.22, 0.31);
  cl::PredictedScan at_centre;
  predictor.predict(centre, at_centre);
  cl::Association association;
  cl::associate_segments(fits, fit_terms, at_centre, map, 0.5, association);
  const cl::Surfaces surfaces = cl::coplanar_surfaces(map);
  cl::SegmentRims rims;
  cl::find_segment_rims(association, fits, at_centre, map, predictor.rings(), surfaces, centre,
                        cl::AssociationCellSize{}, rims);
  // The openings' edges on most rings, on the near wall and through the doors.
  ASSERT_GT(rims.size(), 40u);
  std::vector<int> rims_of_term(association.terms.size(), 0);
  for (const int t : rims.term) ++rims_of_term[static_cast<std::size_t>(t)];

  const cl::Pose3 poses[] = {truth, cl::make_pose(20.35, 1.2, 1.2, 0.3),
                             cl::make_pose(20.23, 1.23, 1.2, 0.31),
                             cl::make_pose(20.5, 1.18, 1.21, 0.305)};
  for (const cl::Pose3& pose : poses) {
    cl::PredictedScan at_pose;
    predictor.predict(pose, at_pose);
    std::vector<double> shifts;
    Eigen::ArrayXd beyond;
    cl::returns_beyond_rims(rims, cl::pose_offset(centre, pose), association.terms.size(), shifts,
                            beyond);
    double counted = 0.0, modelled = 0.0, difference = 0.0;
    int bounded = 0;
    for (std::size_t t = 0; t < association.terms.size(); ++t) {
      // Both ends bounded: every return the full prediction puts elsewhere lies beyond one.
      if (rims_of_term[t] != 2) continue;
      const cl::AssociatedTerm& term = association.terms[t];
      const cl::ConicSegment& segment = segments[static_cast<std::size_t>(term.fit)];
      const auto& ring = scan.rings[static_cast<std::size_t>(fits[term.fit].ring)];
      const cl::PredictedRing& line = at_pose.ring(fits[term.fit].ring);
      const int surface = surfaces.of_polygon[static_cast<std::size_t>(
          association.landmarks[static_cast<std::size_t>(term.landmark)].polygon)];
      double elsewhere = 0.0;
      for (std::size_t i = segment.first;; i = (i + 1) % ring.returns.size()) {
        const auto& ret = ring.returns[i];
        if (ret.status == conicloc::sensor::ReturnStatus::Valid) {
          const int polygon = line.polygon[line.piece_at(ret.azimuth_rad)];
          if (polygon < 0 || surfaces.of_polygon[static_cast<std::size_t>(polygon)] != surface)
            elsewhere += 1.0;
        }
        if (i == segment.last) break;
      }
      counted += elsewhere;
      modelled += beyond(static_cast<Eigen::Index>(t));
      difference += std::abs(beyond(static_cast<Eigen::Index>(t)) - elsewhere);
      // Half a return of rounding per rim, and a little second-order error (measured: at most
      // 0.83 per term).
      EXPECT_LT(std::abs(beyond(static_cast<Eigen::Index>(t)) - elsewhere), 1.5) << t;
      bounded += rims_of_term[t];
    }
    // At the truth none lies past an edge; off it, dozens to hundreds do (88–442). The count is
    // the step function's continuous mean, off by at most one return per rim and by a quarter on
    // average (measured: 0.08–0.15 per rim, over the 252 rims of terms bounded at both ends).
    if (&pose == &poses[0]) {
      EXPECT_EQ(counted, 0.0);
    } else {
      EXPECT_GT(counted, 50.0);
    }
    EXPECT_LT(difference, 0.25 * bounded) << "counted " << counted << ", modelled " << modelled;
  }
}

// Along the corridor the planes alone give the same score at every x of one association cell
// (and steps where the next cell associates differently); with the rims the score peaks at the
// truth and falls off to either side, also across the cells.
TEST(SegmentRims, AlongACorridorTheEdgesPlaceTheSegmentModel) {
  const auto map = make_corridor_with_doors();
  const double x = 20.3, y = 1.2, z = 1.2, yaw = 0.3;
  const auto scan = scan_at(map, cl::make_pose(x, y, z, yaw), 0.01);
  const Eigen::AlignedBox3d box(Vector3d(x - 0.5, y - 0.5, z - 0.2),
                                Vector3d(x + 0.5, y + 0.5, z + 0.2));
  const auto profile = [&](bool rims) {
    cl::ConicSegmentConfig config;
    config.rims = rims;
    cl::ConicSegmentModel model(map, ct::vlp16(), cl::RangeSensor{}, config);
    model.prepare(scan, box);
    auto scratch = model.make_scratch();
    std::vector<double> scores;
    for (int step = -10; step <= 10; ++step) {
      scores.push_back(
          model.score(cl::make_pose(x + 0.02 * step, y, z, yaw), scratch.get()).log_likelihood);
    }
    return scores;
  };
  const std::vector<double> planes = profile(false), with_rims = profile(true);
  EXPECT_EQ(planes[9], planes[10]);
  EXPECT_EQ(planes[11], planes[10]);
  const std::size_t peak = static_cast<std::size_t>(
      std::max_element(with_rims.begin(), with_rims.end()) - with_rims.begin());
  EXPECT_NEAR(static_cast<double>(peak), 10.0, 1.0);  // within 2 cm of the truth
  // 10 cm off, the openings' edges have moved by 1–3° on every ring that sees them (measured:
  // 1,330 and 1,140 nats below the peak).
  EXPECT_LT(with_rims[5], with_rims[10] - 300.0);
  EXPECT_LT(with_rims[15], with_rims[10] - 300.0);
  for (std::size_t i = 1; i < with_rims.size(); ++i) {
    // Falls off monotonically away from the peak, within a nat of noise.
    if (i <= peak) {
      EXPECT_GT(with_rims[i], with_rims[i - 1] - 1.0) << i;
    } else {
      EXPECT_LT(with_rims[i], with_rims[i - 1] + 1.0) << i;
    }
  }
}
