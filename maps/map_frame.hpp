#pragma once
// From file coordinates to the metric map frame: CRS axis order and geographic conversion
// (GeographicLib LocalCartesian), unit scale, and the origin shift for large projected offsets.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace conicloc::maps {

enum class CrsKind {
  Metric,            ///< projected or local: x east, y north, z up, in file units
  GeographicLatLon,  ///< EPSG:4326 / 4979 and their urn / http forms: lat, lon [, h]
  GeographicLonLat,  ///< OGC CRS84 / CRS84h: lon, lat [, h]
};

/// Axis order and kind a srsName announces (no look at the coordinates).
CrsKind classify_srs_name(const std::string& srs_name);

/// Converts file points to the map frame. Build with make_map_frame() from all file points.
class MapFrame {
 public:
  /// Map-frame point of a file point.
  Eigen::Vector3d to_map(const Eigen::Vector3d& file_point) const;

  CrsKind kind() const { return kind_; }
  /// Map frame zero in local metric coordinates (after geographic conversion and unit scale).
  const Eigen::Vector3d& origin() const { return origin_; }
  /// One line for reports: what was done with the CRS, axis order, origin.
  const std::string& description() const { return description_; }

 private:
  friend MapFrame make_map_frame(const std::string&, const std::vector<Eigen::Vector3d>&, double,
                                 std::vector<std::string>&);
  CrsKind kind_ = CrsKind::Metric;
  double unit_scale_ = 1.0;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d geodetic_origin_ = Eigen::Vector3d::Zero();  // lat°, lon°, h m
  std::string description_;
};

/// Decides the frame for a model whose points are `file_points`:
/// - a geographic label is checked against the values: latitudes within ±90°, longitudes within
///   ±180° and a building extent below 0.05° (~5 km); a label the values contradict gets a warning
///   and the values are taken as metres;
/// - geographic models become a local east-north-up frame at the centre of their bounding box
///   (height: its lowest point), origin zero;
/// - metric models are scaled by `unit_scale`; when any coordinate exceeds 10 km the origin is
///   the bounding-box minimum rounded down to whole metres (x, y; z too when it is large), so
///   map coordinates stay small and the shift itself is a readable number.
MapFrame make_map_frame(const std::string& srs_name,
                        const std::vector<Eigen::Vector3d>& file_points, double unit_scale,
                        std::vector<std::string>& warnings);

}  // namespace conicloc::maps
