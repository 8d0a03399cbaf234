#pragma once
// "conic-segment": the paper's landmark form. Once per scan each measured ring is split into
// conic segments (runs of returns on one plane, fitted as 1/r = a cos θ + b sin θ + c by
// scan_line_segmentation). Per particle, each segment is compared with the particle's predicted
// scan line — the conic of the plane it falls on — at a few azimuths across its span, each
// comparison a robust BeamMixture term; a segment's score is the mean of its terms. Far fewer
// terms than beams, and the fit has already averaged the range noise away.

#include <memory>

#include "localizer/beam_mixture.hpp"
#include "localizer/conic_scan_predictor.hpp"
#include "localizer/observation_model.hpp"
#include "localizer/plane_culling.hpp"
#include "localizer/scan_line_segmentation.hpp"

namespace conicloc::localizer {

struct ConicSegmentConfig {
  SegmentationConfig segmentation;
  BeamMixtureConfig mixture{.sigma_hit_m = 0.05};
  PredictorConfig predictor;
  CullConfig cull;
  double cull_margin_m = 0.5;   ///< the particle box is grown by this before culling
  int samples_per_segment = 3;  ///< comparison azimuths, spread over the segment's span
  double span_inset = 0.1;      ///< fraction of the span left out at each end (edges are ambiguous)
  double segment_weight = 10.0;  ///< each segment counts as this many beams
};

class ConicSegmentModel final : public ObservationModel {
 public:
  /// Keeps a reference to `map` (must outlive the model).
  ConicSegmentModel(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
                    const ConicSegmentConfig& config);
  ~ConicSegmentModel() override;

  std::string name() const override { return "conic-segment"; }
  void prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) override;
  std::size_t term_count() const override { return segment_count_; }
  std::unique_ptr<Scratch> make_scratch() const override;
  ObservationScore score(const Pose3& T_map_sensor, Scratch* scratch) const override;

 private:
  /// The comparison points of one ring, all its segments' samples in ascending azimuth.
  struct RingSamples {
    int ring = 0;
    AzimuthSamples azimuths;
    std::vector<double> fitted_range_m;  ///< the segment's conic at each azimuth
    std::vector<BeamFloor> floors;
    std::vector<int> segment;  ///< local segment index of each sample
    int segments = 0;
  };

  ConicSegmentConfig config_;
  BeamMixture mixture_;
  ConicScanPredictor predictor_;
  maps::PlaneIndex index_;
  PlaneCuller culler_;
  std::vector<RingSamples> rings_;
  std::vector<int> candidates_;
  std::size_t segment_count_ = 0;
};

}  // namespace conicloc::localizer
