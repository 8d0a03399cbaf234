// The motion of a scan line's boundaries with the pose (localizer/conic/boundary_motion.hpp),
// against the boundaries a full prediction finds at the moved pose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "localizer/conic/boundary_motion.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

// Azimuths compared on the circle: a boundary near 0 may move past 2π.
double apart(double a, double b) {
  return std::abs(std::remainder(a - b, 2.0 * M_PI));
}

struct Followed {
  double error = 0.0;  // |boundary at the moved pose − the motion's azimuth there|, radians
  double shift = 0.0;  // |boundary at the moved pose − boundary at the centre|, radians
  bool rim = false;    // the sides meet the beam at different ranges: a polygon's rim
};

// 1/r of a piece at azimuth θ (≤ 0 for a gap or a plane behind the beam).
double inverse_range(const cl::PredictedRing& line, std::size_t piece, double azimuth_rad) {
  if (line.polygon[piece] < 0) return 0.0;
  return line.a[piece] * std::cos(azimuth_rad) + line.b[piece] * std::sin(azimuth_rad) +
         line.c[piece];
}

// Every boundary of the prediction at `centre` that boundary_motion() follows, keyed by (ring,
// piece), against the boundary between the same two polygons nearest the followed azimuth in the
// prediction at `moved`.
std::map<std::pair<std::size_t, std::size_t>, Followed> follow_boundaries(
    const conicloc::maps::PlaneMap& map, const cl::Pose3& centre, const cl::Pose3& moved) {
  const cl::ConicScanPredictor predictor(map, ct::vlp16());
  cl::PredictedScan at_centre, at_moved;
  predictor.predict(centre, at_centre);
  predictor.predict(moved, at_moved);
  const cl::PoseOffset offset = cl::pose_offset(centre, moved);
  std::map<std::pair<std::size_t, std::size_t>, Followed> followed;
  for (std::size_t k = 0; k < predictor.rings().size(); ++k) {
    const cl::PredictedRing& line = at_centre.rings[k];
    const cl::PredictedRing& moved_line = at_moved.rings[k];
    for (std::size_t p = 1; p < line.piece_count(); ++p) {
      if (line.polygon[p - 1] == line.polygon[p]) continue;
      const auto side = [&line](std::size_t q) {
        return cl::BoundarySide{line.polygon[q], line.a[q], line.b[q], line.c[q]};
      };
      const auto motion = cl::boundary_motion(map, predictor.rings()[k], centre,
                                              line.boundary_rad[p], side(p - 1), side(p));
      if (!motion) continue;
      const double expected = motion->azimuth_at(offset);
      bool found = false;
      double nearest = 0.0;
      for (std::size_t q = 1; q < moved_line.piece_count(); ++q) {
        if (moved_line.polygon[q - 1] != line.polygon[p - 1] ||
            moved_line.polygon[q] != line.polygon[p]) {
          continue;
        }
        if (!found || apart(moved_line.boundary_rad[q], expected) < apart(nearest, expected)) {
          nearest = moved_line.boundary_rad[q];
          found = true;
        }
      }
      if (found) {
        const double before = inverse_range(line, p - 1, line.boundary_rad[p]);
        const double after = inverse_range(line, p, line.boundary_rad[p]);
        followed[{k, p}] = {apart(nearest, expected), apart(nearest, line.boundary_rad[p]),
                            std::abs(before - after) > 1e-3 * std::max(before, after)};
      }
    }
  }
  return followed;
}

}  // namespace

// The room's corners (two planes crossing), its floor and ceiling edges and the pillar's rims
// (occlusion), seen from poses moved by up to half an association cell in each of the six
// coordinates and by half that: the motion is right to first order when its error falls by about
// 4 as the offset halves (a wrong rate leaves a first-order error, which only halves).
TEST(BoundaryMotion, FollowsTheBoundaryAFullPredictionFindsToSecondOrder) {
  const auto map = ct::make_box_room();
  const double x = 3.0, y = 2.5, z = 1.2, yaw = 0.4;
  const cl::Pose3 centre = cl::make_pose(x, y, z, yaw);
  // (dx, dy, dz, dyaw, dpitch, droll)
  const double offsets[][6] = {{0.06, -0.04, 0.03, 0.008, 0.0, 0.0},
                               {-0.1, 0.05, -0.03, -0.01, 0.004, 0.0},
                               {0.03, 0.1, 0.0, 0.01, -0.003, 0.005}};
  for (const auto& d : offsets) {
    const auto moved_by = [&](double s) {
      return cl::make_pose(x + s * d[0], y + s * d[1], z + s * d[2], yaw + s * d[3], s * d[4],
                           s * d[5]);
    };
    const auto full = follow_boundaries(map, centre, moved_by(1.0));
    const auto half = follow_boundaries(map, centre, moved_by(0.5));
    // Sums over every boundary followed at both offsets [0] and over the rims alone [1].
    double error_full[2] = {0, 0}, error_half[2] = {0, 0}, shift_half[2] = {0, 0};
    int both[2] = {0, 0};
    for (const auto& [key, at_full] : full) {
      const auto at_half = half.find(key);
      if (at_half == half.end()) continue;
      for (int set = 0; set < (at_full.rim ? 2 : 1); ++set) {
        ++both[set];
        error_full[set] += at_full.error;
        error_half[set] += at_half->second.error;
        shift_half[set] += at_half->second.shift;
      }
    }
    // Corners, floor and ceiling edges and the pillar on most rings (95–101), 29–30 of them rims
    // (a polygon ending in front of another): neither kind of edge goes untested.
    EXPECT_GT(both[0], 80);
    EXPECT_GT(both[1], 20);
    for (int set = 0; set < 2; ++set) {
      // The motion accounts for most of the shift a quarter cell away, and its error is second
      // order.
      EXPECT_LT(error_half[set], 0.1 * shift_half[set]) << (set ? "rims" : "all");
      EXPECT_LT(error_half[set], 0.35 * error_full[set]) << (set ? "rims" : "all");
    }
  }
}
