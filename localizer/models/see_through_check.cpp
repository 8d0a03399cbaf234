#include "localizer/models/see_through_check.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {

namespace {

// Whether a beam at `azimuth_rad`, predicted on `ring` at `predicted_m`, passes within the edge
// margins of an occluding edge (SeeThroughConfig::edge_margin_m): `margin_m` beyond it.
bool near_occluding_edge(const PredictedRing& ring, double azimuth_rad, double predicted_m,
                         double margin_m, const SeeThroughConfig& config) {
  const std::size_t piece = ring.piece_at(azimuth_rad);
  const double edge_rad = config.edge_margin_m / predicted_m + config.edge_margin_rad;
  for (const double side : {-edge_rad, edge_rad}) {
    const double neighbour_rad = azimuth_rad + side;
    if (ring.polygon[ring.piece_at(neighbour_rad)] == ring.polygon[piece]) continue;
    // The beam's plane continued to the neighbouring azimuth (1/r = a cos θ + b sin θ + c); a
    // plane that turns away from it there is taken at the beam's range.
    const double inverse = ring.a[piece] * std::cos(neighbour_rad) +
                           ring.b[piece] * std::sin(neighbour_rad) + ring.c[piece];
    const double own_m = inverse > 0.0 ? std::max(1.0 / inverse, predicted_m) : predicted_m;
    const double neighbour_m = ring.range(neighbour_rad);
    if (std::isfinite(neighbour_m) && neighbour_m > own_m + margin_m) return true;
  }
  return false;
}

}  // namespace

SeeThroughCheck::SeeThroughCheck(const maps::PlaneMap& map,
                                 const sensor::LaserCalibration& calibration,
                                 const SeeThroughConfig& config, double max_range_m)
    : map_(map),
      config_(config),
      max_range_m_(max_range_m),
      predictor_(map, calibration, config.predictor, max_range_m),
      index_(map),
      culler_(map, index_, calibration, config.cull, max_range_m) {}

SeeThroughCheck::~SeeThroughCheck() = default;

SeeThroughResult SeeThroughCheck::evaluate(const sensor::Scan& scan,
                                           const Pose3& T_map_sensor) const {
  start(T_map_sensor, 1, work_);
  part(scan, 0, work_);
  return result(work_);
}

void SeeThroughCheck::start(const Pose3& T_map_sensor, int parts, SeeThroughWork& work) const {
  work.T_map_sensor = T_map_sensor;
  work.candidates = culler_.cull(T_map_sensor).kept;
  work.predicted.resize(static_cast<std::size_t>(std::max(parts, 1)));
}

void SeeThroughCheck::part(const sensor::Scan& scan, int s, SeeThroughWork& work) const {
  if (s == 0) work.beams = select_beams(scan, config_.beams, max_range_m_);
  const int parts = static_cast<int>(work.predicted.size());
  std::vector<int> rings;
  for (int r = s; r < static_cast<int>(predictor_.rings().size()); r += parts) rings.push_back(r);
  predictor_.predict(work.T_map_sensor, work.candidates, rings,
                     work.predicted[static_cast<std::size_t>(s)]);
}

SeeThroughResult SeeThroughCheck::result(const SeeThroughWork& work) const {
  SeeThroughResult result;
  const std::size_t parts = work.predicted.size();
  const std::size_t rings = std::min(work.beams.size(), predictor_.rings().size());
  std::vector<double> azimuths_rad, predicted_m;
  for (std::size_t r = 0; r < rings; ++r) {
    const std::vector<SelectedBeam>& beams = work.beams[r];
    if (beams.empty()) continue;
    azimuths_rad.clear();
    for (const SelectedBeam& beam : beams) azimuths_rad.push_back(beam.azimuth_rad);
    predicted_m.resize(azimuths_rad.size());
    const PredictedRing& ring = work.predicted[r % parts].ring(static_cast<int>(r));
    ring.evaluate_sorted(azimuths_rad, predicted_m);
    for (std::size_t i = 0; i < predicted_m.size(); ++i) {
      // No surface predicted (a gap, or out of the sensor's range): a return there is clutter or
      // an unmapped space, not evidence against the pose.
      if (!std::isfinite(predicted_m[i])) continue;
      // Walls only: a beam past a predicted floor or ceiling also follows from a height error
      // (a stair, a sloped floor) or an opening the model lacks (a stairwell), and those are not
      // the filter being lost in the plan.
      const int polygon = ring.polygon[ring.piece_at(azimuths_rad[i])];
      if (polygon < 0 ||
          std::abs(map_.polygons[static_cast<std::size_t>(polygon)].plane.normal.z()) >
              config_.max_wall_normal_z)
        continue;
      const double margin = config_.margin_m + config_.relative_margin * predicted_m[i];
      if (near_occluding_edge(ring, azimuths_rad[i], predicted_m[i], margin, config_)) continue;
      ++result.beams;
      if (beams[i].range_m > predicted_m[i] + margin) ++result.see_through;
    }
  }
  return result;
}

}  // namespace conicloc::localizer
