#pragma once
// "point-to-plane": the point-cloud MCL baseline. Each selected return becomes a map-frame point;
// its distance to the nearest map polygon (found through a nanoflann k-d tree over points sampled
// densely on the polygons, then refined to the true point-to-plane distance of the nearest few
// candidate polygons) is scored by a Gaussian with a uniform floor for clutter. The Gaussian's σ
// and the inlier gate are the sensor's range noise (RangeNoise): a point's distance from its plane
// is its range error along the plane's normal.

#include <memory>

#include "localizer/models/beam_selection.hpp"
#include "localizer/models/correlated_terms.hpp"
#include "localizer/models/observation_model.hpp"
#include "localizer/models/range_sensor.hpp"

namespace conicloc::localizer {

struct PointToPlaneConfig {
  BeamSelectionConfig beams{.max_beams = 500};
  double sample_spacing_m = 0.2;  ///< grid spacing of the points sampled on each polygon
  int candidates = 4;             ///< nearest samples whose polygons are tested exactly
  double hit_weight = 0.8;        ///< mixture weight of the Gaussian
  double max_distance_m = 2.0;    ///< support of the uniform (clutter) part; distances clip here
};

class PointToPlaneModel final : public ObservationModel {
 public:
  /// Keeps a reference to `map` (must outlive the model); builds the k-d tree once. `sensor`: the
  /// maximum range of the selected returns and the noise of a point's distance to its plane.
  PointToPlaneModel(const maps::PlaneMap& map, const RangeSensor& sensor,
                    const PointToPlaneConfig& config);
  ~PointToPlaneModel() override;

  std::string name() const override { return "point-to-plane"; }
  void prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) override;
  std::size_t term_count() const override {
    return static_cast<std::size_t>(points_sensor_.cols());
  }
  double effective_terms(const Pose3& T_map_sensor, Scratch* scratch) const override;
  void set_pose_blur(double blur_m) override;
  ObservationScore score(const Pose3& T_map_sensor, Scratch* scratch) const override;

  /// Distance (m) of a map-frame point to the nearest polygon, clipped at max_distance_m.
  double distance_to_map(const Eigen::Vector3d& point_map) const;

  /// Number of points sampled on the map.
  std::size_t sample_count() const;

 private:
  struct Samples;
  struct Nearest {
    double distance_m = 0.0;  ///< clipped at max_distance_m
    int polygon = -1;         ///< -1: none within max_distance_m
  };
  Nearest nearest_polygon(const Eigen::Vector3d& point_map) const;
  const maps::PlaneMap& map_;
  PointToPlaneConfig config_;
  RangeSensor sensor_;  ///< as configured
  RangeNoise noise_;    ///< sensor_.noise widened by set_pose_blur()
  std::unique_ptr<Samples> samples_;
  Surfaces surfaces_;  ///< each map polygon's plane, for effective_terms()
  Eigen::Matrix3Xd points_sensor_;
  double log_hit_scale_ = 0.0;    ///< log(hit_weight / (sqrt(2π)σ))
  double uniform_density_ = 0.0;  ///< (1 − hit_weight) / max_distance_m
};

}  // namespace conicloc::localizer
