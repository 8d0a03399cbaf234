#include "localizer/conic_segment_model.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace conicloc::localizer {

namespace {

struct SegmentScratch final : ObservationModel::Scratch {
  PredictedScan predicted;
  std::vector<double> ranges_m;
  std::vector<double> segment_sum;
  std::vector<int> segment_inliers;
  std::vector<int> segment_counts;
};

double wrap_two_pi(double angle) {
  angle = std::fmod(angle, 2.0 * M_PI);
  return angle < 0.0 ? angle + 2.0 * M_PI : angle;
}

}  // namespace

ConicSegmentModel::ConicSegmentModel(const maps::PlaneMap& map,
                                     const sensor::LaserCalibration& calibration,
                                     const ConicSegmentConfig& config)
    : config_(config),
      mixture_(config.mixture),
      predictor_(map, calibration, config.predictor),
      index_(map),
      culler_(map, index_, calibration, config.cull) {}

ConicSegmentModel::~ConicSegmentModel() = default;

void ConicSegmentModel::prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) {
  rings_.clear();
  segment_count_ = 0;
  const int predicted_rings = static_cast<int>(predictor_.rings().size());
  const int samples = std::max(1, config_.samples_per_segment);
  for (std::size_t r = 0; r < scan.rings.size() && static_cast<int>(r) < predicted_rings; ++r) {
    const auto segments = segment_scan_line(scan.rings[r], config_.segmentation);
    if (segments.empty()) continue;
    RingSamples ring;
    ring.ring = static_cast<int>(r);
    struct Sample {
      double azimuth, range;
      int segment;
    };
    std::vector<Sample> points;
    for (const ConicSegment& segment : segments) {
      const double span = segment.end_rad - segment.begin_rad;
      for (int s = 0; s < samples; ++s) {
        const double t = samples == 1 ? 0.5
                                      : config_.span_inset +
                                            (1.0 - 2.0 * config_.span_inset) * s / (samples - 1);
        const double azimuth = segment.begin_rad + t * span;
        const double inverse =
            segment.a * std::cos(azimuth) + segment.b * std::sin(azimuth) + segment.c;
        if (!(inverse > 0.0)) continue;
        points.push_back({wrap_two_pi(azimuth), 1.0 / inverse, ring.segments});
      }
      ++ring.segments;
    }
    std::sort(points.begin(), points.end(),
              [](const Sample& a, const Sample& b) { return a.azimuth < b.azimuth; });
    std::vector<double> azimuths;
    for (const Sample& p : points) {
      azimuths.push_back(p.azimuth);
      ring.fitted_range_m.push_back(p.range);
      ring.floors.push_back(mixture_.floor(p.range));
      ring.segment.push_back(p.segment);
    }
    ring.azimuths.assign(azimuths);
    segment_count_ += static_cast<std::size_t>(ring.segments);
    rings_.push_back(std::move(ring));
  }
  Eigen::AlignedBox3d region = cloud_box;
  candidates_.clear();
  if (!region.isEmpty()) {
    region.min().array() -= config_.cull_margin_m;
    region.max().array() += config_.cull_margin_m;
    candidates_ = culler_.cull(region).kept;
  }
}

std::unique_ptr<ObservationModel::Scratch> ConicSegmentModel::make_scratch() const {
  return std::make_unique<SegmentScratch>();
}

ObservationScore ConicSegmentModel::score(const Pose3& T_map_sensor, Scratch* scratch) const {
  ObservationScore result;
  if (segment_count_ == 0) return result;
  SegmentScratch local;
  SegmentScratch& work = scratch ? static_cast<SegmentScratch&>(*scratch) : local;
  predictor_.predict(T_map_sensor, candidates_, work.predicted);
  std::size_t inlier_segments = 0;
  for (const RingSamples& ring : rings_) {
    const std::size_t n = ring.fitted_range_m.size();
    work.ranges_m.resize(n);
    work.predicted.ring(ring.ring).evaluate_sorted(ring.azimuths, work.ranges_m);
    work.segment_sum.assign(static_cast<std::size_t>(ring.segments), 0.0);
    work.segment_inliers.assign(static_cast<std::size_t>(ring.segments), 0);
    std::vector<int>& counts = work.segment_counts;
    counts.assign(static_cast<std::size_t>(ring.segments), 0);
    for (std::size_t i = 0; i < n; ++i) {
      bool inlier = false;
      const auto s = static_cast<std::size_t>(ring.segment[i]);
      work.segment_sum[s] +=
          mixture_.log_likelihood(ring.fitted_range_m[i], work.ranges_m[i], ring.floors[i], inlier);
      work.segment_inliers[s] += inlier ? 1 : 0;
      ++counts[s];
    }
    for (std::size_t s = 0; s < counts.size(); ++s) {
      if (counts[s] == 0) continue;
      // A segment is one landmark: the mean of its comparisons, weighted as a few beams.
      result.log_likelihood += config_.segment_weight * work.segment_sum[s] / counts[s];
      inlier_segments += 2 * work.segment_inliers[s] > counts[s] ? 1 : 0;
    }
  }
  result.inlier_fraction =
      static_cast<double>(inlier_segments) / static_cast<double>(segment_count_);
  return result;
}

}  // namespace conicloc::localizer
