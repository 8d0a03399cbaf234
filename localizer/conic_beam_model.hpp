#pragma once
// "conic-beam": every selected beam's measured range against the range the particle's predicted
// piecewise-conic scan line gives at the beam's azimuth (ConicScanPredictor), scored by the robust
// BeamMixture. The measured azimuths (sensor frame) are sorted once per scan, so each particle's
// prediction is evaluated per ring in one merge walk; rings without beams are skipped.

#include <memory>

#include "localizer/beam_mixture.hpp"
#include "localizer/beam_selection.hpp"
#include "localizer/conic_scan_predictor.hpp"
#include "localizer/observation_model.hpp"
#include "localizer/plane_culling.hpp"

namespace conicloc::localizer {

struct ConicBeamConfig {
  BeamSelectionConfig beams{.max_beams = 2000};
  BeamMixtureConfig mixture;
  PredictorConfig predictor;
  CullConfig cull;
  double cull_margin_m = 0.5;  ///< the particle box is grown by this before culling (motion)
};

class ConicBeamModel final : public ObservationModel {
 public:
  /// Keeps a reference to `map` (must outlive the model).
  ConicBeamModel(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
                 const ConicBeamConfig& config);
  ~ConicBeamModel() override;

  std::string name() const override { return "conic-beam"; }
  void prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) override;
  std::size_t term_count() const override { return beam_count_; }
  std::unique_ptr<Scratch> make_scratch() const override;
  ObservationScore score(const Pose3& T_map_sensor, Scratch* scratch) const override;

  /// Polygons kept by the last prepare()'s culling.
  const std::vector<int>& candidate_polygons() const { return candidates_; }

 private:
  struct RingBeams {
    int ring = 0;
    AzimuthSamples azimuths;
    std::vector<double> ranges_m;
    std::vector<BeamFloor> floors;
  };

  ConicBeamConfig config_;
  BeamMixture mixture_;
  ConicScanPredictor predictor_;
  maps::PlaneIndex index_;
  PlaneCuller culler_;
  std::vector<RingBeams> rings_;  ///< only rings with selected beams
  std::vector<int> candidates_;
  std::size_t beam_count_ = 0;
};

}  // namespace conicloc::localizer
