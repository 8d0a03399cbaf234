#pragma once
// "point-to-plane": the point-cloud MCL baseline. Each selected return becomes a map-frame point;
// its distance to the nearest map polygon (found through a nanoflann k-d tree over points sampled
// densely on the polygons, then refined to the true point-to-plane distance of the nearest few
// candidate polygons) is scored by a Gaussian with a uniform floor for clutter.

#include <memory>

#include "localizer/models/beam_selection.hpp"
#include "localizer/models/correlated_terms.hpp"
#include "localizer/models/observation_model.hpp"

namespace conicloc::localizer {

struct PointToPlaneConfig {
  BeamSelectionConfig beams{.max_beams = 500};
  double sample_spacing_m = 0.2;  ///< grid spacing of the points sampled on each polygon
  int candidates = 4;             ///< nearest samples whose polygons are tested exactly
  double sigma_m = 0.05;          ///< std. dev. of the point's distance to its plane
  double hit_weight = 0.8;        ///< mixture weight of the Gaussian
  double max_distance_m = 2.0;    ///< support of the uniform (clutter) part; distances clip here
  double inlier_sigmas = 3.0;     ///< a point within this many σ of the map counts as an inlier
  /// The part of sigma_m shared by the points of one surface (its map error): sets how many
  /// independent terms a scan is worth (correlated_terms.hpp).
  double shared_sigma_m = 0.03;
};

class PointToPlaneModel final : public ObservationModel {
 public:
  /// Keeps a reference to `map` (must outlive the model); builds the k-d tree once.
  PointToPlaneModel(const maps::PlaneMap& map, const PointToPlaneConfig& config);
  ~PointToPlaneModel() override;

  std::string name() const override { return "point-to-plane"; }
  void prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) override;
  std::size_t term_count() const override {
    return static_cast<std::size_t>(points_sensor_.cols());
  }
  double effective_terms(const Pose3& T_map_sensor) const override;
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
  PointToPlaneConfig config_;  ///< as configured, with σ widened by set_pose_blur()
  double configured_sigma_m_;
  double configured_shared_sigma_m_;
  std::unique_ptr<Samples> samples_;
  Surfaces surfaces_;  ///< each map polygon's plane, for effective_terms()
  Eigen::Matrix3Xd points_sensor_;
  double log_hit_scale_ = 0.0;    ///< log(hit_weight / (sqrt(2π)σ))
  double uniform_density_ = 0.0;  ///< (1 − hit_weight) / max_distance_m
};

}  // namespace conicloc::localizer
