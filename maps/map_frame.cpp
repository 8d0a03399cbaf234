#include "maps/map_frame.hpp"

#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace conicloc::maps {
namespace {

constexpr double kLargeOffset_m = 1.0e4;
constexpr double kMaxBuildingExtent_deg = 0.05;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// The EPSG code at the end of "EPSG:4326", "EPSG::4326", "urn:ogc:def:crs:EPSG:6.6:4326",
// "http://www.opengis.net/def/crs/EPSG/0/4326".
std::string trailing_code(const std::string& name) {
  std::size_t end = name.size();
  std::size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(name[begin - 1]))) --begin;
  return name.substr(begin, end - begin);
}

std::string format_point(const Eigen::Vector3d& p, int precision) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << "(" << p.x() << ", " << p.y() << ", "
      << p.z() << ")";
  return out.str();
}

}  // namespace

CrsKind classify_srs_name(const std::string& srs_name) {
  const std::string name = lower(srs_name);
  if (name.find("crs84") != std::string::npos) return CrsKind::GeographicLonLat;
  if (name.find("epsg") != std::string::npos) {
    const std::string code = trailing_code(name);
    if (code == "4326" || code == "4979") return CrsKind::GeographicLatLon;
  }
  return CrsKind::Metric;
}

Eigen::Vector3d MapFrame::to_map(const Eigen::Vector3d& file_point) const {
  if (kind_ == CrsKind::Metric) return unit_scale_ * file_point - origin_;
  const bool lat_lon = kind_ == CrsKind::GeographicLatLon;
  const double lat = lat_lon ? file_point.x() : file_point.y();
  const double lon = lat_lon ? file_point.y() : file_point.x();
  // A fresh LocalCartesian per call would be wasteful; the projection is cheap to rebuild though,
  // and keeping the frame a plain value keeps MapFrame copyable without GeographicLib in the
  // header.
  const GeographicLib::LocalCartesian enu(geodetic_origin_.x(), geodetic_origin_.y(),
                                          geodetic_origin_.z());
  Eigen::Vector3d local;
  enu.Forward(lat, lon, file_point.z(), local.x(), local.y(), local.z());
  return local - origin_;
}

MapFrame make_map_frame(const std::string& srs_name,
                        const std::vector<Eigen::Vector3d>& file_points, double unit_scale,
                        std::vector<std::string>& warnings) {
  MapFrame frame;
  frame.unit_scale_ = unit_scale;
  Eigen::AlignedBox3d box;
  for (const auto& p : file_points) box.extend(p);
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());
  const std::string label = srs_name.empty() ? "no srsName" : "srsName \"" + srs_name + "\"";

  CrsKind kind = classify_srs_name(srs_name);
  if (kind != CrsKind::Metric) {
    const int lat_axis = kind == CrsKind::GeographicLatLon ? 0 : 1;
    const int lon_axis = 1 - lat_axis;
    const bool in_range = box.min()(lat_axis) >= -90.0 && box.max()(lat_axis) <= 90.0 &&
                          box.min()(lon_axis) >= -180.0 && box.max()(lon_axis) <= 180.0;
    const double extent_deg = std::max(box.sizes()(0), box.sizes()(1));
    if (!in_range || extent_deg > kMaxBuildingExtent_deg) {
      std::ostringstream why;
      why << label << " says geographic (degrees) but the coordinates span "
          << format_point(box.min(), 3) << " .. " << format_point(box.max(), 3)
          << (in_range ? ", far too large for a building in degrees"
                       : ", outside the latitude/longitude range")
          << ": taking them as metres";
      warnings.push_back(why.str());
      kind = CrsKind::Metric;
    }
  }
  frame.kind_ = kind;

  std::ostringstream description;
  if (kind != CrsKind::Metric) {
    const int lat_axis = kind == CrsKind::GeographicLatLon ? 0 : 1;
    const Eigen::Vector3d centre = box.center();
    frame.geodetic_origin_ = {centre(lat_axis), centre(1 - lat_axis), box.min().z()};
    description << label << ": geographic, "
                << (kind == CrsKind::GeographicLatLon ? "lat, lon" : "lon, lat")
                << " axis order; converted to local east-north-up metres (GeographicLib "
                   "LocalCartesian) at lat "
                << std::setprecision(10) << frame.geodetic_origin_.x() << ", lon "
                << frame.geodetic_origin_.y() << ", h " << frame.geodetic_origin_.z() << " m";
    frame.description_ = description.str();
    return frame;
  }

  const Eigen::Vector3d scaled_min = unit_scale * box.min();
  const Eigen::Vector3d scaled_max = unit_scale * box.max();
  for (int axis = 0; axis < 3; ++axis) {
    const double largest = std::max(std::abs(scaled_min(axis)), std::abs(scaled_max(axis)));
    if (largest > kLargeOffset_m && (axis < 2 || largest > kLargeOffset_m)) {
      frame.origin_(axis) = std::floor(scaled_min(axis));
    }
  }
  description << label << ": metric (x east, y north, z up)";
  if (unit_scale != 1.0) description << ", unit scale " << unit_scale;
  if (!frame.origin_.isZero()) {
    description << "; large offsets moved to origin " << format_point(frame.origin_, 3);
  }
  frame.description_ = description.str();
  return frame;
}

}  // namespace conicloc::maps
