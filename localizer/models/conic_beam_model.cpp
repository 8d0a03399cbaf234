#include "localizer/models/conic_beam_model.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <span>

#include "localizer/conic/association_grid.hpp"
#include "localizer/conic/conic_ranges.hpp"
#include "localizer/conic/ring_conic.hpp"
#include "localizer/conic/yaw_shared_prediction.hpp"
#include "localizer/models/correlated_terms.hpp"

namespace conicloc::localizer {

struct ConicBeamModel::BeamScratch final : ObservationModel::Scratch {
  AssociationCache<BeamAssociation> associations;
  PredictedScan predicted;
  YawSharedPrediction cell_predictions;
  std::vector<SensorPlane> planes;                 ///< per landmark, in the particle's sensor frame
  std::vector<double> ranges_m;                    ///< predicted, per beam (flat)
  std::vector<std::array<double, 3>> run_inverse;  ///< per run: 1/r's a, b, c (0: no return)
  std::vector<double> shifts;  ///< per boundary of the association: δθ at the particle's pose
};

ConicBeamModel::ConicBeamModel(const maps::PlaneMap& map,
                               const sensor::LaserCalibration& calibration,
                               const RangeSensor& sensor, const ConicBeamConfig& config,
                               const PredictionShortcuts& shortcuts)
    : config_(config),
      shortcuts_(shortcuts),
      sensor_(sensor),
      noise_(sensor.noise),
      mixture_(config.mixture, sensor.noise, sensor.max_range_m),
      likelihood_sum_(config.mixture, sensor.noise, sensor.max_range_m),
      predictor_(
          map, calibration,
          cell_predictor_config(config.predictor, config.association_cell, sensor.max_range_m),
          sensor.max_range_m),
      index_(map),
      culler_(map, index_, calibration, config.cull, sensor.max_range_m),
      cloud_cull_(config.cull_margin_m, config.cull_slack_m),
      surfaces_(coplanar_surfaces(map)),
      grid_(association_grid(map, config.association_cell)) {}

ConicBeamModel::~ConicBeamModel() = default;

void ConicBeamModel::prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) {
  ++scan_generation_;
  term_weights_.clear();
  rings_.clear();
  scored_rings_.clear();
  measured_m_.clear();
  short_densities_.clear();
  azimuth_rad_.clear();
  cos_azimuth_.clear();
  sin_azimuth_.clear();
  const auto selected = select_beams(scan, config_.beams, sensor_.max_range_m);
  const int predicted_rings = static_cast<int>(predictor_.rings().size());
  std::vector<double> azimuths;
  for (std::size_t r = 0; r < selected.size(); ++r) {
    // Scan rings are indexed like the predictor's (by elevation rank); extra rings are ignored.
    if (selected[r].empty() || static_cast<int>(r) >= predicted_rings) continue;
    RingBeams ring;
    ring.ring = static_cast<int>(r);
    ring.first = measured_m_.size();
    azimuths.clear();
    for (const SelectedBeam& beam : selected[r]) {
      azimuths.push_back(beam.azimuth_rad);
      measured_m_.push_back(beam.range_m);
      short_densities_.push_back(mixture_.short_density(beam.range_m));
    }
    ring.azimuths.assign(azimuths);
    azimuth_rad_.insert(azimuth_rad_.end(), ring.azimuths.azimuth_rad.begin(),
                        ring.azimuths.azimuth_rad.end());
    cos_azimuth_.insert(cos_azimuth_.end(), ring.azimuths.cos_azimuth.begin(),
                        ring.azimuths.cos_azimuth.end());
    sin_azimuth_.insert(sin_azimuth_.end(), ring.azimuths.sin_azimuth.begin(),
                        ring.azimuths.sin_azimuth.end());
    scored_rings_.push_back(ring.ring);
    rings_.push_back(std::move(ring));
  }
  log_short_floors_.resize(short_densities_.size());
  for (std::size_t i = 0; i < short_densities_.size(); ++i)
    log_short_floors_[i] = mixture_.floor_from_short(short_densities_[i]).with_short;
  cloud_cull_.update(culler_, cloud_box);
}

SurfaceTally ConicBeamModel::explained_surfaces(const Pose3& T_map_sensor, BeamScratch& work,
                                                std::vector<int>* surface_of_beam) const {
  // The beams this pose explains (within the inlier gate) grouped by the surface (plane) they
  // meet; the others count nothing (correlated_terms.hpp). The ranges are score()'s; a beam that
  // a moved boundary gave the surface beside its run counts with its run's.
  work.ranges_m.resize(measured_m_.size());
  BeamAssociation full;
  const BeamAssociation* association = &full;
  if (shortcuts_.association_grid) {
    association = &cached_association(T_map_sensor, work);
    predict_associated(T_map_sensor, *association, work);
  } else {
    predict_full(T_map_sensor, work);
    associate(work.predicted, nullptr, full);
  }
  if (surface_of_beam) surface_of_beam->assign(measured_m_.size(), -1);
  const double gate_m = noise_.inlier_gate_m();
  SurfaceTally tally(surfaces_);
  for (const BeamRun& run : association->runs) {
    if (run.landmark < 0) continue;
    const int polygon = association->polygons[static_cast<std::size_t>(run.landmark)];
    double explained = 0.0;
    for (std::size_t i = run.begin; i < run.end; ++i) {
      if (!(std::abs(measured_m_[i] - work.ranges_m[i]) <= gate_m)) continue;
      explained += 1.0;
      if (surface_of_beam)
        (*surface_of_beam)[i] = surfaces_.of_polygon[static_cast<std::size_t>(polygon)];
    }
    tally.add(polygon, explained);
  }
  return tally;
}

double ConicBeamModel::effective_terms(const Pose3& T_map_sensor, Scratch* scratch) const {
  std::unique_ptr<BeamScratch> local;
  BeamScratch& work = own_scratch(scratch, local);
  return explained_surfaces(T_map_sensor, work, nullptr)
      .effective_terms(noise_.shared_error_correlation());
}

void ConicBeamModel::weigh_terms(const Pose3& reference, Scratch* scratch) {
  std::unique_ptr<BeamScratch> local;
  BeamScratch& work = own_scratch(scratch, local);
  std::vector<int> surface_of_beam;
  const SurfaceTally tally = explained_surfaces(reference, work, &surface_of_beam);
  term_weights_ = direction_term_weights(surface_of_beam, static_cast<double>(measured_m_.size()),
                                         tally, noise_.shared_error_correlation());
  // Nothing raised: the scan is scored as without weights.
  if (std::all_of(term_weights_.begin(), term_weights_.end(), [](double w) { return w == 1.0; }))
    term_weights_.clear();
}

std::unique_ptr<ObservationModel::Scratch> ConicBeamModel::make_scratch() const {
  return std::make_unique<BeamScratch>();
}

void ConicBeamModel::set_pose_blur(double blur_m) {
  // The short-reading densities and their log floors depend on the measured ranges, the mixture
  // weights and the maximum range only: they stay.
  noise_ = with_pose_blur(sensor_.noise, blur_m);
  mixture_ = BeamMixture(config_.mixture, noise_, sensor_.max_range_m);
  likelihood_sum_ = BeamLikelihoodSum(config_.mixture, noise_, sensor_.max_range_m);
}

void ConicBeamModel::associate(const PredictedScan& predicted, const Pose3* centre,
                               BeamAssociation& out) const {
  out.polygons.clear();
  out.runs.clear();
  out.boundaries.clear();
  if (centre) out.centre = *centre;
  const auto landmark_of = [&out](int polygon) {
    if (polygon < 0) return -1;
    for (std::size_t l = 0; l < out.polygons.size(); ++l) {
      if (out.polygons[l] == polygon) return static_cast<int>(l);
    }
    out.polygons.push_back(polygon);
    return static_cast<int>(out.polygons.size() - 1);
  };
  // Returns true when a new run was started (false: none, or the last run extended).
  const auto add_run = [&out](std::size_t slot, std::size_t begin, std::size_t end, int landmark) {
    if (begin == end) return false;
    if (!out.runs.empty() && out.runs.back().ring_slot == slot &&
        out.runs.back().landmark == landmark && out.runs.back().end == begin) {
      out.runs.back().end = end;  // a polygon split into pieces by another's occlusion gap
      return false;
    }
    out.runs.push_back({slot, begin, end, landmark});
    return true;
  };
  for (std::size_t slot = 0; slot < rings_.size(); ++slot) {
    const RingBeams& ring = rings_[slot];
    const PredictedRing& line = predicted.ring(ring.ring);
    const std::vector<double>& azimuth = ring.azimuths.azimuth_rad;
    const std::size_t n = azimuth.size();
    const std::size_t pieces = line.piece_count();
    if (pieces == 0) {
      add_run(slot, ring.first, ring.first + n, -1);
      continue;
    }
    // The same merge walk as PredictedRing::evaluate_sorted: the beams before each piece's end.
    // A boundary is kept where a new run starts right after the piece of the run before it (a
    // piece between them that holds no beam would make it two edges; one of no width, which a
    // prediction may leave where two arcs meet, is no piece).
    std::size_t i = 0;
    std::size_t last_piece = pieces;  // the piece the last run of this ring ended with
    std::size_t previous = pieces;    // the last piece of some width before p
    for (std::size_t p = 0; p < pieces && i < n; ++p) {
      const double end =
          p + 1 < pieces ? line.boundary_rad[p + 1] : std::numeric_limits<double>::max();
      std::size_t j = i;
      while (j < n && azimuth[j] < end) ++j;
      const bool adjacent = previous == last_piece && previous < pieces;
      if (end - line.boundary_rad[p] > 1e-12) previous = p;
      if (j == i) continue;
      const bool started =
          add_run(slot, ring.first + i, ring.first + j, landmark_of(line.polygon[p]));
      if (started && centre && adjacent) {
        const auto side = [&line](std::size_t q) {
          return BoundarySide{line.polygon[q], line.a[q], line.b[q], line.c[q]};
        };
        const auto motion = boundary_motion(
            predictor_.map(), predictor_.rings()[static_cast<std::size_t>(ring.ring)], *centre,
            line.boundary_rad[p], side(last_piece), side(p));
        if (motion) out.boundaries.add(*motion, static_cast<std::uint32_t>(out.runs.size() - 2));
      }
      last_piece = p;
      i = j;
    }
  }
  // The gaps to the beams around each boundary, once the runs are whole (a run may still grow by
  // a piece of its polygon past another's occlusion gap).
  BeamBoundaries& boundaries = out.boundaries;
  for (std::size_t k = 0; k < boundaries.size(); ++k) {
    const BeamRun& after = out.runs[boundaries.run[k] + 1];
    boundaries.gap_before[k] = boundaries.azimuth_rad[k] - azimuth_rad_[after.begin - 1];
    boundaries.gap_after[k] = azimuth_rad_[after.begin] - boundaries.azimuth_rad[k];
  }
}

void ConicBeamModel::BeamBoundaries::clear() {
  rates.clear();
  gap_before.clear();
  gap_after.clear();
  run.clear();
  azimuth_rad.clear();
}

void ConicBeamModel::BeamBoundaries::add(const BoundaryMotion& motion, std::uint32_t run_before) {
  rates.add(motion);
  azimuth_rad.push_back(motion.azimuth_rad);
  run.push_back(run_before);
  // Filled once the runs are whole (associate()).
  gap_before.push_back(0.0);
  gap_after.push_back(0.0);
}

void ConicBeamModel::move_boundaries(const BeamAssociation& association, const PoseOffset& offset,
                                     BeamScratch& work) const {
  // A boundary moved further than this is a near-parallel edge's first-order blow-up: kept.
  constexpr double kMaxShift_rad = 0.2;
  const BeamBoundaries& boundaries = association.boundaries;
  const std::size_t count = boundaries.size();
  boundaries.rates.shifts(offset, work.shifts);
  const double* shift = work.shifts.data();
  const double lo = 1.0 / sensor_.max_range_m;
  const double hi = 1.0 / config_.predictor.min_range_m;
  const auto range_of = [&](std::size_t run, std::size_t beam) {
    const auto& [a, b, c] = work.run_inverse[run];
    return range_from_inverse(a * cos_azimuth_[beam] + b * sin_azimuth_[beam] + c, lo, hi);
  };
  for (std::size_t k = 0; k < count; ++k) {
    // Most boundaries pass no beam: the nearest beam on the side they move to is farther.
    const bool back = -shift[k] >= boundaries.gap_before[k];
    const bool forward = shift[k] > boundaries.gap_after[k];
    if (!(back || forward) || !(std::abs(shift[k]) <= kMaxShift_rad)) continue;
    const double moved = boundaries.azimuth_rad[k] + shift[k];
    const std::size_t run = boundaries.run[k];
    const BeamRun& before = association.runs[run];
    const BeamRun& after = association.runs[run + 1];
    if (back) {
      // The run after it now begins earlier: the last beams before the boundary are its.
      for (std::size_t i = after.begin; i > before.begin && azimuth_rad_[i - 1] >= moved; --i) {
        work.ranges_m[i - 1] = range_of(run + 1, i - 1);
      }
    } else {
      for (std::size_t i = after.begin; i < after.end && azimuth_rad_[i] < moved; ++i) {
        work.ranges_m[i] = range_of(run, i);
      }
    }
  }
}

const ConicBeamModel::BeamAssociation& ConicBeamModel::cached_association(const Pose3& T_map_sensor,
                                                                          BeamScratch& work) const {
  // A new cell is predicted at its centre (a deterministic pose, whatever particle came first).
  return work.associations.get(
      T_map_sensor, scan_generation_, grid_,
      [&](const AssociationCellKey& cell, const Pose3& centre, BeamAssociation& association) {
        work.cell_predictions.predict(predictor_, cell, cloud_cull_.candidates(),
                                      cloud_cull_.version(), scored_rings_, scan_generation_, grid_,
                                      shortcuts_.share_prediction_across_yaw, work.predicted);
        associate(work.predicted, &centre, association);
      });
}

void ConicBeamModel::predict_full(const Pose3& T_map_sensor, BeamScratch& work) const {
  predictor_.predict(T_map_sensor, cloud_cull_.candidates(), scored_rings_, work.predicted);
  for (const RingBeams& ring : rings_) {
    work.predicted.ring(ring.ring).evaluate_sorted(
        ring.azimuths, std::span<double>(work.ranges_m).subspan(ring.first, ring.azimuths.size()));
  }
}

void ConicBeamModel::predict_associated(const Pose3& T_map_sensor,
                                        const BeamAssociation& association,
                                        BeamScratch& work) const {
  // Each associated plane in the particle's sensor frame, n_s = Rᵀn, D_s = D + n·t, computed as
  // the predictor does (add_sensor_polygon), so the cell's centre reproduces it exactly.
  const Eigen::Matrix3d R_t = T_map_sensor.linear().transpose();
  const Eigen::Vector3d t = T_map_sensor.translation();
  const maps::PlaneMap& map = predictor_.map();
  work.planes.resize(association.polygons.size());
  for (std::size_t l = 0; l < association.polygons.size(); ++l) {
    const auto& plane = map.polygons[static_cast<std::size_t>(association.polygons[l])].plane;
    work.planes[l].normal = R_t * plane.normal;
    work.planes[l].offset = plane.offset + plane.normal.dot(t);
  }
  const double lo = 1.0 / sensor_.max_range_m;
  const double hi = 1.0 / config_.predictor.min_range_m;
  double* out = work.ranges_m.data();
  work.run_inverse.resize(association.runs.size());
  for (std::size_t r = 0; r < association.runs.size(); ++r) {
    const BeamRun& run = association.runs[r];
    const RingBeams& ring = rings_[run.ring_slot];
    RingConic conic;
    if (run.landmark >= 0) {
      conic = ring_conic(predictor_.rings()[static_cast<std::size_t>(ring.ring)],
                         work.planes[static_cast<std::size_t>(run.landmark)]);
    }
    if (run.landmark < 0 || conic.E == 0.0) {
      // Nothing associated, or the particle's sensor lies in the plane: no return predicted
      // (the mixture scores the beam with its floor).
      work.run_inverse[r] = {0.0, 0.0, 0.0};
      std::fill(out + run.begin, out + run.end, PredictedRing::kNoReturn);
      continue;
    }
    // 1/r = a cos θ + b sin θ + c, (a, b, c) = (A, B, C)/E (ring_conic.hpp), as the predictor's
    // arcs hold it; a non-positive or out-of-limits inverse (the plane behind the beam or out of
    // range for this particle) predicts no return.
    work.run_inverse[r] = {conic.A / conic.E, conic.B / conic.E, conic.C / conic.E};
    const std::size_t first = run.begin - ring.first;
    conic_ranges(work.run_inverse[r][0], work.run_inverse[r][1], work.run_inverse[r][2],
                 ring.azimuths.cos_azimuth.data() + first, ring.azimuths.sin_azimuth.data() + first,
                 run.end - run.begin, lo, hi, out + run.begin);
  }
  move_boundaries(association, pose_offset(association.centre, T_map_sensor), work);
}

void ConicBeamModel::predict(const Pose3& T_map_sensor, BeamScratch& work) const {
  work.ranges_m.resize(measured_m_.size());
  if (shortcuts_.association_grid) {
    predict_associated(T_map_sensor, cached_association(T_map_sensor, work), work);
  } else {
    predict_full(T_map_sensor, work);
  }
}

std::vector<double> ConicBeamModel::predicted_ranges(const Pose3& T_map_sensor,
                                                     Scratch* scratch) const {
  std::unique_ptr<BeamScratch> local;
  BeamScratch& work = own_scratch(scratch, local);
  predict(T_map_sensor, work);
  return work.ranges_m;
}

ObservationScore ConicBeamModel::score(const Pose3& T_map_sensor, Scratch* scratch) const {
  ObservationScore result;
  const std::size_t n = measured_m_.size();
  if (n == 0) return result;
  std::unique_ptr<BeamScratch> local;
  BeamScratch& work = own_scratch(scratch, local);
  predict(T_map_sensor, work);
  std::size_t inliers = 0;
  if (!term_weights_.empty()) {
    result.log_likelihood = likelihood_sum_.weighted_max_sum(
        measured_m_, work.ranges_m, term_weights_, log_short_floors_, inliers);
  } else if (config_.max_mixture) {
    result.log_likelihood =
        likelihood_sum_.max_sum(measured_m_, work.ranges_m, log_short_floors_, inliers);
  } else if (shortcuts_.chunked_log) {
    result.log_likelihood =
        likelihood_sum_.sum(measured_m_, work.ranges_m, short_densities_, inliers);
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      bool inlier = false;
      result.log_likelihood += mixture_.log_likelihood(
          measured_m_[i], work.ranges_m[i], mixture_.floor_from_short(short_densities_[i]), inlier);
      inliers += inlier ? 1 : 0;
    }
  }
  result.inlier_fraction = static_cast<double>(inliers) / static_cast<double>(n);
  return result;
}

}  // namespace conicloc::localizer
