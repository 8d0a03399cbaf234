#include "localizer/models/scan_line_segmentation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace conicloc::localizer {
namespace {

struct Samples {
  std::vector<std::size_t> index;  // into RingScan::returns
  std::vector<double> theta, range;
  std::vector<double> cos_theta, sin_theta;  // once per sample: every fit and residual uses them

  void clear() {  // keeps the capacity for the next run
    index.clear();
    theta.clear();
    range.clear();
    cos_theta.clear();
    sin_theta.clear();
  }
};

// fit_inverse_range() from the samples' cosines and sines.
bool fit_samples(const Samples& s, std::size_t first, std::size_t end, double& a, double& b,
                 double& c) {
  return fit_inverse_range_trig(&s.cos_theta[first], &s.sin_theta[first], &s.range[first],
                                end - first, a, b, c);
}

double max_residual(const Samples& s, std::size_t first, std::size_t end, double a, double b,
                    double c, double& rms) {
  double worst = 0.0, sum_sq = 0.0;
  for (std::size_t i = first; i < end; ++i) {
    const double inverse = a * s.cos_theta[i] + b * s.sin_theta[i] + c;
    const double residual = inverse > 0.0 ? std::abs(1.0 / inverse - s.range[i])
                                          : std::numeric_limits<double>::infinity();
    worst = std::max(worst, residual);
    sum_sq += residual * residual;
  }
  rms = std::sqrt(sum_sq / static_cast<double>(end - first));
  return worst;
}

// Split-and-merge, split step: accept [first, end) when its fit stays within the residual bound,
// else split where the two halves' total squared residual is least, and recurse.
void split(const Samples& s, const InverseRangeSums& sums, std::size_t first, std::size_t end,
           const SegmentationConfig& config,
           std::vector<std::pair<std::size_t, std::size_t>>& out) {
  const std::size_t n = end - first;
  if (n < 3) return;
  double a = 0, b = 0, c = 0, rms = 0;
  if (fit_samples(s, first, end, a, b, c) &&
      max_residual(s, first, end, a, b, c, rms) <= config.max_residual_m) {
    out.emplace_back(first, end);
    return;
  }
  if (n < 6) return;  // too short to split into two fittable halves: noise
  std::size_t best = first + 3;
  double best_sse = std::numeric_limits<double>::infinity();
  for (std::size_t k = first + 3; k + 3 <= end; ++k) {
    const double total = sums.sse(first, k) + sums.sse(k, end);
    if (total < best_sse) {
      best_sse = total;
      best = k;
    }
  }
  split(s, sums, first, best, config, out);
  split(s, sums, best, end, config, out);
}

ConicSegment make_segment(const sensor::RingScan& ring, const Samples& s, std::size_t first,
                          std::size_t end, const SegmentationConfig& config) {
  ConicSegment segment;
  segment.first = s.index[first];
  segment.last = s.index[end - 1];
  segment.count = end - first;
  segment.begin_rad = s.theta[first];
  segment.end_rad = s.theta[end - 1];
  fit_samples(s, first, end, segment.a, segment.b, segment.c);
  max_residual(s, first, end, segment.a, segment.b, segment.c, segment.rms_residual_m);
  recover_plane(segment, ring.elevation_rad, ring.vertical_offset_m, config.min_sin_elevation);
  return segment;
}

}  // namespace

void recover_plane(ConicSegment& segment, double elevation_rad, double vertical_offset_m,
                   double min_sin_elevation) {
  const double cos_phi = std::cos(elevation_rad), sin_phi = std::sin(elevation_rad);
  const double horizontal = std::hypot(segment.a, segment.b);
  segment.tilt_observable = false;
  segment.normal_sensor.setZero();
  segment.offset_sensor = 0.0;
  if (horizontal > 0.0 && cos_phi > 0.0) {
    // The normal faces the sensor, n ∝ −(a, b, ·); the trace line's distance is cos φ/|(a, b)|.
    segment.horizontal_normal = Eigen::Vector2d(-segment.a, -segment.b) / horizontal;
    segment.trace_distance_m = cos_phi / horizontal;
  } else {
    segment.horizontal_normal.setZero();
    segment.trace_distance_m = std::numeric_limits<double>::infinity();
  }
  // n/E = (a/cos φ, b/cos φ, c/sin φ) needs sin φ: with φ → 0, c → 0 whatever the tilt.
  if (std::abs(sin_phi) < min_sin_elevation || !(cos_phi > 0.0)) return;
  const Eigen::Vector3d w(segment.a / cos_phi, segment.b / cos_phi, segment.c / sin_phi);
  const double norm = w.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) return;
  segment.tilt_observable = true;
  segment.normal_sensor = -w / norm;  // E = −1/|w| < 0: the apex is on the normal's side
  segment.offset_sensor = 1.0 / norm - segment.normal_sensor.z() * vertical_offset_m;
}

std::vector<ConicSegment> segment_scan_line(const sensor::RingScan& ring,
                                            const SegmentationConfig& config, double max_range_m) {
  std::vector<ConicSegment> segments;
  // Runs of usable returns broken at azimuth gaps and range jumps.
  Samples run;
  // Working memory reused from run to run.
  InverseRangeSums sums;
  std::vector<std::pair<std::size_t, std::size_t>> pieces, merged;
  auto close_run = [&] {
    run.cos_theta.resize(run.theta.size());
    run.sin_theta.resize(run.theta.size());
    for (std::size_t i = 0; i < run.theta.size(); ++i) {
      run.cos_theta[i] = std::cos(run.theta[i]);
      run.sin_theta[i] = std::sin(run.theta[i]);
    }
    sums.build(run.cos_theta, run.sin_theta, run.range);
    pieces.clear();
    split(run, sums, 0, run.theta.size(), config, pieces);
    // Merge step: neighbours that one conic fits within the bound become one segment (the split
    // step may cut a plane where the best two-way split of a longer run fell).
    merged.clear();
    for (const auto& piece : pieces) {
      if (!merged.empty() && merged.back().second == piece.first) {
        const std::size_t first = merged.back().first, end = piece.second;
        double a = 0, b = 0, c = 0, rms = 0;
        if (fit_samples(run, first, end, a, b, c) &&
            max_residual(run, first, end, a, b, c, rms) <= config.max_residual_m) {
          merged.back().second = end;
          continue;
        }
      }
      merged.push_back(piece);
    }
    pieces.swap(merged);
    // Boundary refinement: near a corner a return lies within the bound of both planes; give
    // each boundary return to the neighbour whose conic fits it better.
    for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
      auto& left = pieces[k];
      auto& right = pieces[k + 1];
      if (left.second != right.first) continue;
      double la = 0, lb = 0, lc = 0, ra = 0, rb = 0, rc = 0;
      if (!fit_samples(run, left.first, left.second, la, lb, lc) ||
          !fit_samples(run, right.first, right.second, ra, rb, rc)) {
        continue;
      }
      auto residual = [&](std::size_t i, double a, double b, double c) {
        const double inverse = a * run.cos_theta[i] + b * run.sin_theta[i] + c;
        return inverse > 0.0 ? std::abs(1.0 / inverse - run.range[i])
                             : std::numeric_limits<double>::infinity();
      };
      while (left.second - left.first > 3 &&
             residual(left.second - 1, ra, rb, rc) < residual(left.second - 1, la, lb, lc)) {
        --left.second;
        --right.first;
      }
      while (right.second - right.first > 3 &&
             residual(right.first, la, lb, lc) < residual(right.first, ra, rb, rc)) {
        ++left.second;
        ++right.first;
      }
    }
    for (const auto& [first, end] : pieces) {
      if (end - first >= config.min_returns) {
        segments.push_back(make_segment(ring, run, first, end, config));
      }
    }
    run.clear();
  };
  auto usable = [&](const sensor::Return& ret) {
    return ret.status == sensor::ReturnStatus::Valid && ret.range_m >= config.min_range_m &&
           ret.range_m <= max_range_m;
  };
  auto breaks = [&](double theta_prev, double range_prev, double theta, double range) {
    return theta - theta_prev > config.max_gap_rad ||
           std::abs(range - range_prev) > config.max_relative_jump * std::min(range, range_prev);
  };
  // The ring is circular: start at its largest range jump (or first gap), so a plane seen across
  // θ = 0 stays one segment. Azimuths after the wrap are unwrapped (+2π).
  std::vector<std::size_t> valid;
  for (std::size_t i = 0; i < ring.returns.size(); ++i) {
    if (usable(ring.returns[i])) valid.push_back(i);
  }
  std::size_t start = 0;
  double worst = -1.0;
  if (valid.size() > 2) {
    for (std::size_t k = 0; k < valid.size(); ++k) {
      const sensor::Return& prev = ring.returns[valid[(k + valid.size() - 1) % valid.size()]];
      const sensor::Return& cur = ring.returns[valid[k]];
      double gap = cur.azimuth_rad - prev.azimuth_rad;
      if (gap < 0.0) gap += 2.0 * std::numbers::pi;
      const double score = gap > config.max_gap_rad ? std::numeric_limits<double>::infinity()
                                                    : std::abs(cur.range_m - prev.range_m) /
                                                          std::min(cur.range_m, prev.range_m);
      if (score > worst) {
        worst = score;
        start = k;
      }
    }
  }
  auto run_from = [&](std::size_t first_valid) {
    segments.clear();
    run.clear();
    for (std::size_t step = 0; step < valid.size(); ++step) {
      const std::size_t k = (first_valid + step) % valid.size();
      const sensor::Return& ret = ring.returns[valid[k]];
      const double theta = ret.azimuth_rad + (k < first_valid ? 2.0 * std::numbers::pi : 0.0);
      if (!run.theta.empty() && breaks(run.theta.back(), run.range.back(), theta, ret.range_m)) {
        close_run();
      }
      run.index.push_back(valid[k]);
      run.theta.push_back(theta);
      run.range.push_back(ret.range_m);
    }
    close_run();
  };
  run_from(start);
  // Second pass from a boundary the first pass found between two fitted planes (a corner), so
  // the plane that was cut at the starting point is whole and its corner refined too.
  if (segments.size() >= 2 && worst < std::numeric_limits<double>::infinity()) {
    const std::size_t corner = segments[1].first;
    const auto it = std::lower_bound(valid.begin(), valid.end(), corner);
    if (it != valid.end() && *it == corner) run_from(static_cast<std::size_t>(it - valid.begin()));
  }
  return segments;
}

}  // namespace conicloc::localizer
