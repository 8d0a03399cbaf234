#pragma once
// "conic-beam": every selected beam's measured range against the range the particle's predicted
// piecewise-conic scan line gives at the beam's azimuth, scored by the robust BeamMixture.
//
// Two ways to get the predicted ranges (PredictionShortcuts::association_grid):
// - grid (default): beams are associated with map polygons once per cell of a coarse pose grid
//   (association_grid.hpp), from the scan predicted at the cell's centre (ConicScanPredictor; the
//   rings the prepared scan has beams on):
//   per ring, runs of azimuth-sorted beams that hit one polygon (or nothing). Cached per thread
//   and scan. Per particle only the associated planes are moved into its sensor frame, and each
//   beam's range is the exact conic of its plane, r = E / (A cos θ + B sin θ + C) (ring_conic.hpp),
//   one division per beam. At a cell's centre this equals the full prediction bit for bit.
//   Elsewhere in the cell each boundary between runs moves with the particle's pose, to first
//   order, to where its ring crosses the boundary's edge (boundary_motion.hpp), and the beams it
//   passes take the surface on its other side. Kept where the centre saw them, the boundaries
//   would make the likelihood flat within a cell and step at its border, and along a corridor
//   the edges are what fixes the position.
// - full: the particle's own complete prediction (clipping the conic of every ring with beams to
//   every culled polygon, occlusion envelope), then one merge walk per ring. 2.4× slower than
//   the grid, both scoring the mixture (bench_localizer conic_beam_full_prediction against
//   conic_beam_exact_mixture); kept to measure the grid against.
// Each beam scores its max-mixture term log max(H e^(−x), F), with neither exp nor log
// (BeamLikelihoodSum::max_sum; ConicBeamConfig::max_mixture); on a scan whose short directions
// are raised to their surfaces' worth (weigh_terms(), a tracked cloud), times its weight
// (weighted_max_sum). With max_mixture false an unraised scan scores the mixture itself, its
// logs taken once per chunk of beams (BeamLikelihoodSum::sum).

#include <cstdint>
#include <memory>

#include "localizer/conic/association_grid.hpp"
#include "localizer/conic/boundary_motion.hpp"
#include "localizer/conic/cloud_cull.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/plane_culling.hpp"
#include "localizer/models/beam_likelihood_sum.hpp"
#include "localizer/models/beam_mixture.hpp"
#include "localizer/models/beam_selection.hpp"
#include "localizer/models/correlated_terms.hpp"
#include "localizer/models/observation_model.hpp"
#include "localizer/models/prediction_shortcuts.hpp"
#include "localizer/models/range_sensor.hpp"

namespace conicloc::localizer {

struct ConicBeamConfig {
  BeamSelectionConfig beams{.max_beams = 2000};
  BeamMixtureConfig mixture;  ///< its σ and inlier gate: the sensor's RangeNoise
  PredictorConfig predictor;
  CullConfig cull;
  double cull_margin_m = 0.5;  ///< the particle box is grown by this before culling (motion)
  double cull_slack_m = 1.0;   ///< ... and the region culled by this more (CloudCull)
  /// The association grid's cells (PredictionShortcuts::association_grid).
  AssociationCellSize association_cell;
  /// Every scan scored in the max-mixture form, Σ_i log max(H e^(−x_i), F_i) (what a scan with
  /// raised terms is always scored in: BeamLikelihoodSum::weighted_max_sum), below the mixture's
  /// log-density by at most log 2 per beam, at the crossover only; false: a scan without raised
  /// terms is scored with the mixture itself, Σ_i log(H e^(−x_i) + F_i) (an exp per beam).
  bool max_mixture = true;
};

class ConicBeamModel final : public ObservationModel {
 public:
  /// Keeps a reference to `map` (must outlive the model). `sensor`: the maximum range (beams,
  /// culling, prediction, the mixture's uniform part) and the range noise of a beam.
  ConicBeamModel(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
                 const RangeSensor& sensor, const ConicBeamConfig& config,
                 const PredictionShortcuts& shortcuts = {});
  ~ConicBeamModel() override;

  std::string name() const override { return "conic-beam"; }
  void prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) override;
  std::size_t term_count() const override { return measured_m_.size(); }
  double effective_terms(const Pose3& T_map_sensor, Scratch* scratch) const override;
  void weigh_terms(const Pose3& reference, Scratch* scratch) override;
  /// Only the rings the prepared scan holds are predicted.
  bool cost_follows_rings() const override { return true; }
  std::unique_ptr<Scratch> make_scratch() const override;
  void set_pose_blur(double blur_m) override;
  ObservationScore score(const Pose3& T_map_sensor, Scratch* scratch) const override;

  /// The predicted range of every selected beam (rings in ascending order, azimuths ascending
  /// within a ring; PredictedRing::kNoReturn where nothing is predicted) as score() uses them.
  /// `scratch` may be null.
  std::vector<double> predicted_ranges(const Pose3& T_map_sensor, Scratch* scratch) const;
  /// The measured ranges in the same order.
  const std::vector<double>& measured_ranges() const { return measured_m_; }

  /// Polygons kept by the last prepare()'s culling.
  const std::vector<int>& candidate_polygons() const { return cloud_cull_.candidates(); }

 private:
  struct RingBeams {
    int ring = 0;           ///< index into the predictor's rings
    std::size_t first = 0;  ///< its beams: [first, first + azimuths.size()) of the flat arrays
    AzimuthSamples azimuths;
  };
  /// A run of consecutive beams of one ring associated with one polygon (landmark −1: none).
  struct BeamRun {
    std::size_t ring_slot = 0;       ///< index into rings_
    std::size_t begin = 0, end = 0;  ///< flat beam indices
    int landmark = -1;               ///< index into BeamAssociation::polygons
  };
  /// Where consecutive runs of a ring meet, and how each boundary moves with the pose
  /// (boundary_motion.hpp): a particle off the cell's centre moves it to where its own ring
  /// crosses the edge, and the beams it passes take the other run's surface. Stored by column.
  struct BeamBoundaries {
    BoundaryRates rates;
    /// How far the boundary must move to pass the nearest beam: back to the last beam of the run
    /// before it, forward past the first beam of the run after it (radians, ≥ 0).
    std::vector<double> gap_before, gap_after;
    std::vector<std::uint32_t> run;   ///< the run before it; runs[run + 1] follows
    std::vector<double> azimuth_rad;  ///< where the cell's centre saw it
    std::size_t size() const { return run.size(); }
    void clear();
    void add(const BoundaryMotion& motion, std::uint32_t run_before);
  };
  struct BeamAssociation {
    std::vector<int> polygons;         ///< landmark → map polygon
    std::vector<BeamRun> runs;         ///< covering every beam, ring after ring
    Pose3 centre = Pose3::Identity();  ///< the pose predicted (the cell's centre)
    BeamBoundaries boundaries;         ///< ascending in run
  };
  struct BeamScratch;

  /// The beams `T_map_sensor` explains, tallied by surface; with `surface_of_beam`, each beam's
  /// surface there (−1: none).
  SurfaceTally explained_surfaces(const Pose3& T_map_sensor, BeamScratch& work,
                                  std::vector<int>* surface_of_beam) const;
  const BeamAssociation& cached_association(const Pose3& T_map_sensor, BeamScratch& work) const;
  /// The runs of `predicted`; with `centre` (the pose it was predicted at), their boundaries too.
  void associate(const PredictedScan& predicted, const Pose3* centre, BeamAssociation& out) const;
  /// Moves the boundaries of `association` to the pose `offset` from its centre: the beams a
  /// boundary passes get the range of the run on its other side (`run_inverse`: 1/r's a, b, c
  /// per run; zeros for no return).
  void move_boundaries(const BeamAssociation& association, const PoseOffset& offset,
                       BeamScratch& work) const;
  void predict_full(const Pose3& T_map_sensor, BeamScratch& work) const;
  void predict_associated(const Pose3& T_map_sensor, const BeamAssociation& association,
                          BeamScratch& work) const;
  void predict(const Pose3& T_map_sensor, BeamScratch& work) const;

  ConicBeamConfig config_;
  PredictionShortcuts shortcuts_;
  RangeSensor sensor_;  ///< as configured
  RangeNoise noise_;    ///< sensor_.noise widened by set_pose_blur()
  BeamMixture mixture_;
  BeamLikelihoodSum likelihood_sum_;
  ConicScanPredictor predictor_;
  maps::PlaneIndex index_;
  PlaneCuller culler_;
  CloudCull cloud_cull_;            ///< the candidates: what the cloud can see
  std::vector<RingBeams> rings_;    ///< only rings with selected beams
  std::vector<int> scored_rings_;   ///< their ring indices, ascending: the rings predicted
  std::vector<double> measured_m_;  ///< flat, ring after ring
  /// The beams' azimuths, flat like measured_m_ (the boundaries' beams are found by index).
  std::vector<double> azimuth_rad_, cos_azimuth_, sin_azimuth_;
  std::vector<double> short_densities_;   ///< the same order (BeamMixture::short_density)
  Surfaces surfaces_;                     ///< each map polygon's plane, for effective_terms()
  std::vector<double> term_weights_;      ///< per beam (weigh_terms()); empty: all 1
  std::vector<double> log_short_floors_;  ///< per beam: log(F_rand + short density)
  AssociationGrid grid_;                  ///< of config_.association_cell, on the map's storeys
  std::uint64_t scan_generation_ = 0;     ///< a new scan: new associations, older predictions go
};

}  // namespace conicloc::localizer
