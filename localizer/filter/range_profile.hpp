#pragma once
// A scan seen from above: per ring, the horizontal range in each 0.25° azimuth bin — what the
// scan-to-scan motion (scan_turn.hpp) aligns. Comparing two profiles at an azimuth shift s,
//   cost = mean over bins b seen in both  min(|r_a(b) − r_b(b + s)| / max(r, 1 m), clip),
// a robust, clipped relative range difference.

#include <Eigen/Core>
#include <vector>

#include "sensor/scan.hpp"

namespace conicloc::localizer {

/// Per ring, the horizontal sensor-frame points (x, y) of its valid returns.
using RingPoints = std::vector<std::vector<Eigen::Vector2d>>;

/// Per ring, the mean horizontal range of each bin (0: no return there).
using RangeProfile = std::vector<std::vector<float>>;

constexpr int kProfileBins = 1440;
constexpr double kProfileBinRad = 2.0 * M_PI / kProfileBins;

/// `threads` workers share the rings (parallel_for.hpp); the result is the same for any count.
RingPoints ring_points(const sensor::Scan& scan, int threads = 1);

/// The profile of `points` seen from `origin` (same frame; the points are moved by −origin).
/// Gaps of up to 2° between returns on one surface (ranges within 10 %) are filled by linear
/// interpolation, so that a ring sampled more coarsely than the bins (1200 rpm: 0.4°) does not
/// overlap another at some shifts and not at others.
/// `threads` workers share the rings, as ring_points().
RangeProfile range_profile(const RingPoints& points, const Eigen::Vector2d& origin,
                           int threads = 1);

/// The cost above of `a` against `b` shifted by `shift_bins` (every `stride`-th bin); `overlap`
/// receives the bins seen in both. +∞ when none is.
double profile_cost(const RangeProfile& a, const RangeProfile& b, int shift_bins, int stride,
                    double clip, std::size_t& overlap);

/// Bins with a return, over all rings.
std::size_t filled_bins(const RangeProfile& profile);

}  // namespace conicloc::localizer
