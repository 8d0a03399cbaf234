// PlaneMap frames: geographic models to local metres, large offsets to the origin, the binary's
// map-info --json output.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "io/indoorgml.hpp"
#include "maps/map_frame.hpp"

namespace {

std::string test_file(const std::string& name) {
  return std::string(CONICLOC_TEST_DATA) + "/indoorgml/" + name;
}

// WGS84 radii of curvature at latitude phi: meridian M and prime vertical N.
void wgs84_radii(double phi, double& meridian_m, double& prime_m) {
  const double a = 6378137.0;
  const double f = 1.0 / 298.257223563;
  const double e2 = f * (2.0 - f);
  const double w = 1.0 - e2 * std::sin(phi) * std::sin(phi);
  meridian_m = a * (1.0 - e2) / std::pow(w, 1.5);
  prime_m = a / std::sqrt(w);
}

void expect_geographic_box(const std::string& name) {
  const auto loaded = conicloc::io::load_indoorgml(test_file(name));
  double meridian = 0.0;
  double prime = 0.0;
  const double phi = 48.00005 * M_PI / 180.0;
  wgs84_radii(phi, meridian, prime);
  const double step = 0.0001 * M_PI / 180.0;
  const double east_m = prime * std::cos(phi) * step;  // ≈ 7.46 m
  const double north_m = meridian * step;              // ≈ 11.12 m
  const Eigen::Vector3d size = loaded.map.bounds.sizes();
  EXPECT_NEAR(size.x(), east_m, 0.01) << name;
  EXPECT_NEAR(size.y(), north_m, 0.01) << name;
  EXPECT_NEAR(size.z(), 3.0, 0.01) << name;
  // Local frame at the box centre: geometry symmetric about zero in x and y.
  EXPECT_NEAR(loaded.map.bounds.center().x(), 0.0, 0.01);
  EXPECT_NEAR(loaded.map.bounds.center().y(), 0.0, 0.01);
  EXPECT_TRUE(loaded.report.warnings.empty());
  EXPECT_EQ(loaded.report.planes_after_merge, 6);
}

TEST(PlaneMapFrames, GeographicLatLonUrnForm) {
  expect_geographic_box("geographic_latlon.gml");
}

TEST(PlaneMapFrames, GeographicCrs84LonLat) {
  expect_geographic_box("geographic_crs84.gml");
}

TEST(PlaneMapFrames, ClassifiesSrsNames) {
  using conicloc::maps::classify_srs_name;
  using conicloc::maps::CrsKind;
  EXPECT_EQ(classify_srs_name("EPSG:4326"), CrsKind::GeographicLatLon);
  EXPECT_EQ(classify_srs_name("urn:ogc:def:crs:EPSG::4979"), CrsKind::GeographicLatLon);
  EXPECT_EQ(classify_srs_name("http://www.opengis.net/def/crs/EPSG/0/4326"),
            CrsKind::GeographicLatLon);
  EXPECT_EQ(classify_srs_name("urn:ogc:def:crs:OGC:1.3:CRS84"), CrsKind::GeographicLonLat);
  EXPECT_EQ(classify_srs_name("EPSG:25832"), CrsKind::Metric);
  EXPECT_EQ(classify_srs_name("EPSG:43260"), CrsKind::Metric);
  EXPECT_EQ(classify_srs_name(""), CrsKind::Metric);
}

TEST(PlaneMapFrames, LargeOffsetsMovedToOrigin) {
  const auto loaded = conicloc::io::load_indoorgml(test_file("large_offset.gml"));
  EXPECT_TRUE(loaded.map.origin.isApprox(Eigen::Vector3d(500123.0, 5400456.0, 0.0)));
  EXPECT_TRUE(loaded.map.bounds.min().isApprox(Eigen::Vector3d(0.25, 0.5, 250.0)));
  EXPECT_TRUE(loaded.map.bounds.max().isApprox(Eigen::Vector3d(4.25, 3.5, 252.75)));
  for (const auto& polygon : loaded.map.polygons) EXPECT_LT(polygon.flatness_m, 1e-9);
}

TEST(PlaneMapFrames, UnitScaleWarnsOnImplausibleHeights) {
  conicloc::io::MapLoadOptions options;
  options.unit_scale = 0.001;  // as if the 2.5 m room were written in millimetres
  const auto loaded = conicloc::io::load_indoorgml(test_file("v101_room.gml"), options);
  EXPECT_NEAR(loaded.map.bounds.max().z(), 0.0025, 1e-12);
  ASSERT_FALSE(loaded.report.warnings.empty());
  EXPECT_NE(loaded.report.warnings.back().find("implausible"), std::string::npos);
}

TEST(PlaneMapFrames, MapInfoJsonFromTheBinary) {
  const std::string path = std::string(CONICLOC_SHARED_DATA) +
                           "/indoorgml/FJK-Haus_IndoorGML_withEXR-corrected_1_0_3.gml";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
  const std::string command = std::string(CONICLOC_BINARY) + " map-info --json '" + path + "'";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  ASSERT_TRUE(pipe);
  std::string output;
  std::array<char, 4096> buffer{};
  while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe.get()))
    output.append(buffer.data(), n);
  ASSERT_FALSE(output.empty());
  EXPECT_EQ(output.front(), '{');
  for (const char* key : {"version", "cells", "polygons", "planes", "storeys", "origin", "bbox_min",
                          "bbox_max", "nav_nodes", "nav_edges", "warnings"}) {
    EXPECT_NE(output.find(std::string("\"") + key + "\":"), std::string::npos) << key;
  }
  EXPECT_NE(output.find("\"read\":358"), std::string::npos);
  EXPECT_NE(output.find("\"nav_edges\":30"), std::string::npos);
}

TEST(PlaneMapFrames, MapInfoBadFileExitsNonZero) {
  const std::string command =
      std::string(CONICLOC_BINARY) + " map-info '" + test_file("bad_nan_coordinate.gml") + "' 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string output;
  std::array<char, 4096> buffer{};
  while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe.get()))
    output.append(buffer.data(), n);
  const int status = pclose(pipe.release());
  EXPECT_NE(status, 0);
  EXPECT_NE(output.find("line 10"), std::string::npos) << output;
}

}  // namespace
