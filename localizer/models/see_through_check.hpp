#pragma once
// Is the filter lost? A physically grounded test of one pose hypothesis against a scan: count the
// returns measured *beyond* the surface the map predicts along their beam. A short return is
// normal — people, furniture and anything else the map lacks stand in front of the walls — but a
// long one means the beam passed where the pose says a mapped wall stands. A
// correct pose sees through walls only at open doors the map closes, glass and the odd grazing
// beam; a wrong pose, even one whose floor and ceiling beams fit perfectly (the inlier fraction of
// a wrong pose is often 50–75 %), sees through a large share of its predicted walls.
//
// Independent of the observation model: the check predicts the scan at one pose with the conic
// predictor over the map (culled for that pose), so it costs one full prediction per scan; its
// rings can be predicted on several threads (start, part, result).

#include <cmath>
#include <memory>
#include <vector>

#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/plane_culling.hpp"
#include "localizer/models/beam_selection.hpp"
#include "maps/plane_index.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

struct SeeThroughConfig {
  BeamSelectionConfig beams{.max_beams = 1000};
  PredictorConfig predictor;
  CullConfig cull;
  /// A return counts as seeing through when it lies beyond the predicted surface by more than
  /// margin_m + relative_margin · predicted range (noise, map error, and the range error of a
  /// slightly wrong pose on surfaces seen at grazing incidence).
  double margin_m = 0.3;
  double relative_margin = 0.1;
  /// Only beams whose predicted surface is a wall count: |n_z| at most this (about 45°).
  double max_wall_normal_z = 0.7;
  /// Nor do beams that pass within edge_margin_m (at the predicted range) plus edge_margin_rad of
  /// an occluding edge: where another surface is predicted beyond the margin above from the
  /// beam's own plane continued (a pillar's silhouette, a door jamb; not a concave corner, nor a
  /// wall whose range grows fast at grazing incidence). The map places an edge only to its
  /// accuracy (a pillar's face 5 cm off) and a tracked pose holds its heading to a fraction of a
  /// degree, so a beam that grazes a pillar in the prediction may pass beside it at a correct
  /// pose: passing 0.5 m from a pillar of a hall whose faces were 5 cm off, the true pose saw
  /// through 10 % of its walls for three scans. Only the azimuths at ± the margin are looked at
  /// (a farther surface narrower than the margin between them is not), and a gap there (no
  /// surface predicted) is no edge: from a wrong pose outside a room most walls border gaps.
  double edge_margin_m = 0.1;
  /// The heading a tracked pose may be off by (issue 14's target: 0.5°).
  double edge_margin_rad = 0.5 * M_PI / 180.0;
};

struct SeeThroughResult {
  std::size_t beams = 0;        ///< selected returns with a wall predicted along their beam
  std::size_t see_through = 0;  ///< ... measured beyond it (by more than the margin)
  /// see_through / beams; 0 without beams.
  double fraction() const {
    return beams > 0 ? static_cast<double>(see_through) / static_cast<double>(beams) : 0.0;
  }
};

/// The check's working memory for one pose, shared by its parts (SeeThroughCheck::start).
struct SeeThroughWork {
  Pose3 T_map_sensor = Pose3::Identity();
  std::vector<int> candidates;                   ///< the polygons culled for the pose
  std::vector<std::vector<SelectedBeam>> beams;  ///< per ring (select_beams), by part 0
  std::vector<PredictedScan> predicted;          ///< per part: its rings
};

class SeeThroughCheck {
 public:
  /// Keeps a reference to `map`, which must outlive the check. `max_range_m`: the sensor's
  /// maximum range (the localizer's, RangeSensor::max_range_m).
  SeeThroughCheck(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
                  const SeeThroughConfig& config, double max_range_m);
  ~SeeThroughCheck();

  /// Returns of `scan` (sensor frame, de-skewed to the pose's time) measured beyond the surfaces
  /// a sensor at T_map_sensor would see.
  SeeThroughResult evaluate(const sensor::Scan& scan, const Pose3& T_map_sensor) const;

  /// evaluate() in `parts` that may run at once on separate threads: start(), then part(s) for
  /// every s in [0, parts), then result(); the same counts for any number of parts. Part s
  /// predicts the rings r ≡ s (mod parts), part 0 also selects the scan's beams.
  void start(const Pose3& T_map_sensor, int parts, SeeThroughWork& work) const;
  void part(const sensor::Scan& scan, int s, SeeThroughWork& work) const;
  SeeThroughResult result(const SeeThroughWork& work) const;

  const SeeThroughConfig& config() const { return config_; }

 private:
  const maps::PlaneMap& map_;
  SeeThroughConfig config_;
  double max_range_m_;
  ConicScanPredictor predictor_;
  maps::PlaneIndex index_;
  PlaneCuller culler_;
  // Working memory of evaluate(), reused between scans (evaluate() is called serially).
  mutable SeeThroughWork work_;
};

}  // namespace conicloc::localizer
