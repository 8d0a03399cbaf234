#pragma once
// "conic-segment": the paper's landmark form. Once per scan each measured ring is split into
// conic segments (runs of returns on one plane, fitted as 1/r = a cos θ + b sin θ + c by
// scan_line_segmentation) and reduced to their fit and second moments (segment_landmarks.hpp).
// Segments are associated with map polygons from the scan predicted at a reference pose: the
// centre of the particle's cell in a coarse (x, y, z, roll, pitch, yaw) grid, cached per thread
// and scan, so a tracking cloud needs a handful of predictions per scan, not one per particle.
// Per particle, each associated polygon's plane is moved into the particle's sensor frame (4
// numbers) and compared in closed form with its segments: the rms range difference between the
// predicted and the fitted conics over the segments' returns, one robust term per segment (the
// BeamMixture's max-mixture form), counted once per return; the closest of the segment's
// candidate polygons is taken. The polygon's bounds count too: the segment's returns beyond the
// ends of the polygon's arc, moved with the particle's pose, are unexplained returns
// (segment_rims.hpp). A segment with no polygon, or whose polygon the particle sees
// behind it / out of range, scores as an outlier (the mixture's floor) for each of its returns.
// The terms are the returns (term_count()), and the filter tempers the scan to what its surfaces
// are worth (effective_terms(): the returns of the segments on each plane, correlated_terms.hpp),
// exactly as for conic-beam; where a direction's surfaces hold few of the returns, their
// segments' terms are raised to what those surfaces are worth (weigh_terms(), a tracked cloud).

#include <memory>

#include "localizer/conic/association_grid.hpp"
#include "localizer/conic/cloud_cull.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/plane_culling.hpp"
#include "localizer/models/beam_mixture.hpp"
#include "localizer/models/correlated_terms.hpp"
#include "localizer/models/observation_model.hpp"
#include "localizer/models/prediction_shortcuts.hpp"
#include "localizer/models/range_sensor.hpp"
#include "localizer/models/scan_line_segmentation.hpp"
#include "localizer/models/segment_landmarks.hpp"
#include "localizer/models/segment_rims.hpp"

namespace conicloc::localizer {

struct ConicSegmentConfig {
  /// A return farther than 12 cm from the fit splits a segment: ~4σ of the VLP-16's range noise
  /// (σ ≈ 3 cm). At 5 cm (the segmentation default) noise alone split each wall every ~15 returns
  /// (1481 segments instead of 101 for a scan of the box room at σ = 3 cm).
  SegmentationConfig segmentation{.max_residual_m = 0.12};
  BeamMixtureConfig mixture;
  /// The mixture's σ, shared part and inlier gate, on a segment's rms range difference between
  /// its fitted and its predicted conic, not on one return's range (RangeSensor::noise): the fit
  /// averages the returns' own noise away but not the map's error, so this is a quantity of its
  /// own, set apart from the sensor's (equal to it by default).
  RangeNoise segment_noise;
  PredictorConfig predictor;
  CullConfig cull;
  double cull_margin_m = 0.5;  ///< the particle box is grown by this before culling
  double cull_slack_m = 1.0;   ///< ... and the region culled by this more (CloudCull)
  /// Association grid: particles in one cell share the association made at its centre.
  AssociationCellSize association_cell;
  /// A segment is associated with a polygon only if their rms range difference at the cell's
  /// centre is below this (metres); else it is clutter the map lacks.
  double association_gate_m = 0.5;
  /// The returns a segment holds beyond the ends of its polygon's arc, as the particle's pose
  /// moves them, score as unexplained (segment_rims.hpp); false: each segment is compared with
  /// its polygon's plane only, and a motion within that plane goes unseen.
  bool rims = true;
};

class ConicSegmentModel final : public ObservationModel {
 public:
  /// Keeps a reference to `map` (must outlive the model). `sensor`: the maximum range
  /// (segmentation, culling, prediction, the mixture's uniform part); the noise of a segment's
  /// term is config.segment_noise.
  ConicSegmentModel(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
                    const RangeSensor& sensor, const ConicSegmentConfig& config,
                    const PredictionShortcuts& shortcuts = {});
  ~ConicSegmentModel() override;

  std::string name() const override { return "conic-segment"; }
  void prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) override;
  /// The returns the segments summarise: the likelihood sums over them (in closed form), so the
  /// filter's tempering treats the scan like a beam model's.
  std::size_t term_count() const override { return returns_; }
  void weigh_terms(const Pose3& reference, Scratch* scratch) override;
  std::size_t segment_count() const { return fits_.size(); }
  double effective_terms(const Pose3& T_map_sensor, Scratch* scratch) const override;
  /// Only the rings the prepared scan holds are predicted.
  bool cost_follows_rings() const override { return true; }
  std::unique_ptr<Scratch> make_scratch() const override;
  void set_pose_blur(double blur_m) override;
  ObservationScore score(const Pose3& T_map_sensor, Scratch* scratch) const override;

  /// The association a particle at T_map_sensor uses (that of its grid cell's centre).
  Association association_at(const Pose3& T_map_sensor) const;

 private:
  /// What a cell of the association grid holds: the association made at its centre and the
  /// ends of the associated polygons' arcs there.
  struct CellAssociation {
    Association association;
    SegmentRims rims;
    Pose3 centre = Pose3::Identity();
  };
  struct SegmentScratch;
  /// The returns of `association`'s segments tallied by surface; with `surface_of_fit`, each
  /// fit's surface (−1: its segment fits no polygon).
  SurfaceTally explained_surfaces(const Association& association,
                                  std::vector<int>* surface_of_fit) const;
  const CellAssociation& cached_association(const Pose3& T_map_sensor, SegmentScratch& work) const;
  ObservationScore score_association(const Pose3& T_map_sensor, const CellAssociation& cell,
                                     SegmentScratch& work) const;

  ConicSegmentConfig config_;
  PredictionShortcuts shortcuts_;
  double max_range_m_;  ///< the sensor's
  RangeNoise noise_;    ///< config_.segment_noise widened by set_pose_blur()
  BeamMixture mixture_;
  BeamFloor floor_;  ///< mixture_.floor_without_short(): the floor has no short term here
  ConicScanPredictor predictor_;
  maps::PlaneIndex index_;
  PlaneCuller culler_;
  CloudCull cloud_cull_;  ///< the candidates: what the cloud can see
  std::vector<SegmentFit> fits_;
  std::vector<CandidateTerm> fit_terms_;  ///< candidate_term() of each fit
  std::vector<int> scored_rings_;         ///< the rings with fits, ascending: the rings predicted
  Surfaces surfaces_;                     ///< each map polygon's plane, for effective_terms()
  AssociationGrid grid_;                  ///< of config_.association_cell, on the map's storeys
  std::size_t returns_ = 0;
  std::vector<double> fit_weights_;    ///< per fit (weigh_terms()); empty: all 1
  double weighted_returns_ = 0.0;      ///< Σ weight · returns over the fits (weigh_terms())
  std::uint64_t scan_generation_ = 0;  ///< a new scan: new associations, older predictions go
};

}  // namespace conicloc::localizer
