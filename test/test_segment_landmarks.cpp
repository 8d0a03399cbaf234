// The landmark form of the conic-segment model: the closed-form comparison of a fitted segment
// with a plane's conic against a brute-force sum over the segment's returns, the per-particle
// quadratic form and visibility against the conic route, the per-cell visibility margins against
// poses at the cell's corners, association on a noise-free scan, and exact repeatability of the
// model's scores (per-thread association caches).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "localizer/conic/ring_conic.hpp"
#include "localizer/models/conic_segment_model.hpp"
#include "localizer/models/scan_line_segmentation.hpp"
#include "localizer/models/segment_landmarks.hpp"
#include "sensor/builtin_calibration.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

using conicloc::test::vlp16;

conicloc::sensor::Scan noisy_scan(const conicloc::maps::PlaneMap& map, const cl::Pose3& pose,
                                  double sigma_m) {
  return ct::make_scan(map, pose, 0.4 * M_PI / 180.0, sigma_m, 11);
}

// The box room scanned at `pose` (range noise `sigma_m`), its segments' fits and terms, and
// their association from the scan predicted at the same pose.
struct AssociatedScan {
  std::vector<cl::RingGeometry> rings;
  std::vector<cl::SegmentFit> fits;
  std::vector<cl::CandidateTerm> fit_terms;
  cl::Association association;
};

AssociatedScan associate_scan(const conicloc::maps::PlaneMap& map, const cl::Pose3& pose,
                              double sigma_m) {
  AssociatedScan out;
  const auto scan = noisy_scan(map, pose, sigma_m);
  const cl::ConicScanPredictor predictor(map, vlp16());
  out.rings = predictor.rings();
  cl::PredictedScan predicted;
  predictor.predict(pose, predicted);
  for (std::size_t r = 0; r < scan.rings.size(); ++r) {
    for (const auto& segment :
         cl::segment_scan_line(scan.rings[r], {}, conicloc::sensor::kMaxRange_m)) {
      out.fits.push_back(
          cl::make_segment_fit(scan.rings[r], segment, static_cast<int>(r), 0.3, 100.0));
      out.fit_terms.push_back(cl::candidate_term(out.fits.back(), out.rings[r]));
    }
  }
  cl::associate_segments(out.fits, out.fit_terms, predicted, map, 0.5, out.association);
  return out;
}

}  // namespace

TEST(SegmentLandmarks, ClosedFormEqualsTheSumOverTheSegmentsReturns) {
  const auto map = ct::make_box_room();
  const auto scan = noisy_scan(map, cl::make_pose(3.0, 2.5, 1.2, 0.4), 0.01);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 0.05);
  int compared = 0;
  for (std::size_t r = 0; r < scan.rings.size(); ++r) {
    for (const auto& segment :
         cl::segment_scan_line(scan.rings[r], {}, conicloc::sensor::kMaxRange_m)) {
      const cl::SegmentFit fit =
          cl::make_segment_fit(scan.rings[r], segment, static_cast<int>(r), 0.3, 100.0);
      ASSERT_GT(fit.returns, 0.0);
      const double p[3] = {fit.p[0] + normal(rng), fit.p[1] + normal(rng), fit.p[2] + normal(rng)};
      double brute = 0.0;  // Σ (r² (p − p_fit)·x)² over the returns of the segment
      std::size_t n = scan.rings[r].returns.size();
      double returns = 0.0;
      for (std::size_t i = segment.first;; i = (i + 1) % n) {
        const auto& ret = scan.rings[r].returns[i];
        if (ret.status == conicloc::sensor::ReturnStatus::Valid && ret.range_m >= 0.3) {
          const double c = std::cos(ret.azimuth_rad), s = std::sin(ret.azimuth_rad);
          const double d = (p[0] - fit.p[0]) * c + (p[1] - fit.p[1]) * s + (p[2] - fit.p[2]);
          brute += std::pow(ret.range_m * ret.range_m * d, 2);
          returns += 1.0;
        }
        if (i == segment.last) break;
      }
      EXPECT_EQ(returns, fit.returns);
      EXPECT_EQ(returns, static_cast<double>(segment.count));
      EXPECT_NEAR(cl::squared_range_difference(fit, p), brute, 1e-9 * std::max(1.0, brute));
      const double* same = fit.p;
      EXPECT_EQ(cl::squared_range_difference(fit, same), 0.0);
      ++compared;
    }
  }
  EXPECT_GT(compared, 20);
}

TEST(SegmentLandmarks, NoiseFreeSegmentsAssociateWithTheirPlaneAndScorePerfectly) {
  // Noise-free scan at the reference pose: every segment lies on one map polygon, which the
  // association finds first, and the plane's conic matches the fit (rms difference below a
  // millimetre: a return at a segment's end may lie on the neighbouring plane; another plane
  // would be centimetres off).
  const auto map = ct::make_box_room();
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  const AssociatedScan associated = associate_scan(map, truth, 0.0);
  const auto& fits = associated.fits;
  const cl::Association& association = associated.association;
  ASSERT_GT(fits.size(), 30u);
  EXPECT_EQ(association.unassociated_segments, 0);
  ASSERT_EQ(association.segments.size(), fits.size());
  for (std::size_t s = 0; s < fits.size(); ++s) {
    const cl::LandmarkSegment& segment = association.segments[s];
    ASSERT_GE(segment.candidate_count, 1);
    const cl::Landmark& best =
        association.landmarks[static_cast<std::size_t>(segment.candidates[0])];
    const auto& polygon = map.polygons[static_cast<std::size_t>(best.polygon)];
    const cl::SensorPlane plane = cl::to_sensor_plane(polygon.plane.normal, polygon.plane.offset,
                                                      truth.linear(), truth.translation());
    const cl::RingConic conic =
        cl::ring_conic(associated.rings[static_cast<std::size_t>(fits[s].ring)], plane);
    const double p[3] = {conic.A / conic.E, conic.B / conic.E, conic.C / conic.E};
    EXPECT_LT(std::sqrt(cl::squared_range_difference(fits[s], p) / fits[s].returns), 1e-3) << s;
  }
}

TEST(SegmentLandmarks, CandidateCostsAreTheClosedFormOfThePlanesConicOrInfinityWhenUnseen) {
  // The per-particle form (a 4×4 quadratic in u = (n_s, D_s)) against the conic route: the ring's
  // conic p = (A, B, C)/E of the plane, then (p − p_fit)ᵀM(p − p_fit); and visibility against the
  // conic's ranges at the span's 5 %, 50 % and 95 % azimuths.
  const auto map = ct::make_box_room();
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  const AssociatedScan associated = associate_scan(map, truth, 0.01);
  const auto& fits = associated.fits;
  const cl::Association& association = associated.association;
  ASSERT_EQ(association.segments.size(), fits.size());
  const double min_range = 0.3, max_range = 100.0;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> offset(-8.0, 8.0);
  int seen = 0, unseen = 0;
  for (int trial = 0; trial < 50; ++trial) {
    // One random plane for every landmark: each term then has its own fit against it.
    cl::SensorPlane plane;
    plane.normal = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    plane.offset = offset(rng);
    const std::vector<cl::SensorPlaneTerms> planes(
        association.landmarks.size(),
        cl::sensor_plane_terms(plane.normal.x(), plane.normal.y(), plane.normal.z(), plane.offset));
    Eigen::ArrayXd costs;
    cl::candidate_costs(association, associated.fit_terms, planes, 1.0 / max_range, 1.0 / min_range,
                        costs);
    for (std::size_t s = 0; s < fits.size(); ++s) {
      const cl::SegmentFit& fit = fits[s];
      const cl::RingConic conic =
          cl::ring_conic(associated.rings[static_cast<std::size_t>(fit.ring)], plane);
      bool visible = conic.E != 0.0;
      for (const double fraction : {0.05, 0.5, 0.95}) {
        double range_m = 0.0;
        const double azimuth = fit.begin_rad + fraction * (fit.end_rad - fit.begin_rad);
        visible =
            visible && conic.hit(azimuth, range_m) && range_m >= min_range && range_m < max_range;
      }
      const cl::LandmarkSegment& segment = association.segments[s];
      for (int k = 0; k < segment.candidate_count; ++k) {
        const double cost = costs(segment.terms[k]);
        if (!visible) {
          EXPECT_EQ(cost, std::numeric_limits<double>::infinity()) << s << " " << trial;
          ++unseen;
          continue;
        }
        const double p[3] = {conic.A / conic.E, conic.B / conic.E, conic.C / conic.E};
        const double expected = cl::squared_range_difference(fit, p);
        // Both cancel terms of size p_fitᵀMp_fit = Σ r² (and the cost's own size): rounding only.
        const double fit_scale = cl::squared_range_difference(fit, std::array<double, 3>{}.data());
        EXPECT_NEAR(cost, expected, 1e-12 * (fit_scale + expected)) << s << " " << trial;
        ++seen;
      }
    }
  }
  EXPECT_GT(seen, 100);
  EXPECT_GT(unseen, 100);
}

TEST(SegmentLandmarks, TermsMarkedSeenThroughoutACellAreSeenFromEveryPoseInIt) {
  // The margins of mark_seen_throughout_cell against sampled poses at the cell's limits: 0.25 m on
  // each axis and 2° in roll, pitch and yaw (±half of each around the centre). A range window of
  // [0.5, 5) m puts many of the box room's checks near a limit, where the margins matter.
  const auto map = ct::make_box_room();
  const cl::Pose3 centre = cl::make_pose(3.0, 2.5, 1.25, 0.4);
  AssociatedScan associated = associate_scan(map, centre, 0.01);
  cl::Association& association = associated.association;
  const double cell = 0.25, angle = 2.0 * M_PI / 180.0, min_inverse = 1 / 5.0,
               max_inverse = 1 / 0.5;
  cl::mark_seen_throughout_cell(association, associated.fit_terms, centre,
                                0.5 * std::sqrt(3.0) * cell, 1.5 * angle, min_inverse, max_inverse);
  int marked = 0;
  for (const auto& term : association.terms) marked += term.check_visibility ? 0 : 1;
  EXPECT_GT(marked, 10);
  EXPECT_LT(marked, static_cast<int>(association.terms.size()));
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<int> corner(0, 1);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  for (int trial = 0; trial < 400; ++trial) {
    // Corners of the cell half the time (the worst case), uniform inside otherwise.
    const auto offset = [&] { return trial % 2 ? unit(rng) : corner(rng) - 0.5; };
    const cl::Pose3 pose =
        cl::make_pose(3.0 + cell * offset(), 2.5 + cell * offset(), 1.25 + cell * offset(),
                      0.4 + angle * offset(), angle * offset(), angle * offset());
    for (const auto& term : association.terms) {
      if (term.check_visibility) continue;
      const auto& landmark = association.landmarks[static_cast<std::size_t>(term.landmark)];
      const cl::SensorPlane plane = cl::to_sensor_plane(
          Eigen::Vector3d(landmark.normal_map[0], landmark.normal_map[1], landmark.normal_map[2]),
          landmark.offset_map, pose.linear(), pose.translation());
      const double u[4] = {plane.normal.x(), plane.normal.y(), plane.normal.z(), plane.offset};
      EXPECT_TRUE(cl::candidate_visible(associated.fit_terms[static_cast<std::size_t>(term.fit)], u,
                                        min_inverse, max_inverse))
          << trial;
    }
  }
}

TEST(SegmentLandmarks, ModelScoresRepeatExactlyWhateverTheCacheHolds) {
  // Association is made at the centre of the particle's grid cell, so a score does not depend on
  // which particles a thread's cache saw before: fresh and warmed scratches agree bit for bit.
  const auto map = ct::make_box_room();
  cl::ConicSegmentModel model(map, vlp16(), cl::RangeSensor{}, cl::ConicSegmentConfig{});
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  model.prepare(noisy_scan(map, truth, 0.01),
                Eigen::AlignedBox3d(Eigen::Vector3d(2, 1.5, 1), Eigen::Vector3d(4, 3.5, 1.4)));
  ASSERT_GT(model.segment_count(), 10u);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<cl::Pose3> poses;
  for (int i = 0; i < 200; ++i) {
    poses.push_back(cl::make_pose(3.0 + 0.2 * normal(rng), 2.5 + 0.2 * normal(rng), 1.2,
                                  0.4 + 0.05 * normal(rng)));
  }
  auto warm = model.make_scratch();
  for (const auto& pose : poses) model.score(pose, warm.get());
  for (std::size_t i = poses.size(); i-- > 0;) {
    auto fresh = model.make_scratch();
    const auto a = model.score(poses[i], fresh.get());
    const auto b = model.score(poses[i], warm.get());
    EXPECT_EQ(a.log_likelihood, b.log_likelihood);
    EXPECT_EQ(a.inlier_fraction, b.inlier_fraction);
  }
  // The truth explains nearly every return; a pose 30 cm off fewer (the level floor and ceiling
  // give circles around the sensor whatever its x, y and yaw) and scores much worse.
  auto scratch = model.make_scratch();
  const auto at_truth = model.score(truth, scratch.get());
  const auto off = model.score(cl::make_pose(3.3, 2.5, 1.2, 0.4), scratch.get());
  EXPECT_GT(at_truth.inlier_fraction, 0.9);
  EXPECT_LT(off.inlier_fraction, at_truth.inlier_fraction - 0.2);
  EXPECT_LT(off.log_likelihood, at_truth.log_likelihood - 100.0);
}
