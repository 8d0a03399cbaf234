#pragma once
// Fuzz driver: sensor_msgs/PointCloud2 decoding (io/point_cloud2_msg) and one cloud as one scan
// (io/cloud_scan). Shared by fuzz/fuzz_point_cloud2.cpp and the corpus replay in
// test/test_fuzz_regressions.cpp.
//
// Input: byte 0 selects the serialisation (bit 0: CDR, else ROS 1) and the sensor model (bits 1-3);
// the rest is the message. A bad message may only throw MessageError; an accepted one must give
// a scan of the model's rings whose returns have finite ranges, azimuths in [0, 2π) and finite
// times, no more returns than points.

#include <cmath>
#include <cstdint>
#include <span>

#include "fuzz/contract.hpp"
#include "io/cloud_scan.hpp"
#include "io/point_cloud2_msg.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::fuzz {

inline void run_point_cloud2(std::span<const std::uint8_t> input) {
  if (input.empty()) return;
  constexpr sensor::SensorModel kModels[] = {
      sensor::SensorModel::VLP16, sensor::SensorModel::PuckLite, sensor::SensorModel::PuckHiRes,
      sensor::SensorModel::HDL32E, sensor::SensorModel::VLP32C};
  const auto encoding = (input[0] & 1) ? io::MessageEncoding::Cdr : io::MessageEncoding::Ros1;
  const auto calibration = sensor::builtin_calibration(kModels[((input[0] >> 1) & 7) % 5]);
  const auto message = input.subspan(1);
  try {
    const io::PointCloud2View cloud = io::decode_point_cloud2(message, encoding);
    const sensor::Scan scan = io::cloud_to_scan(cloud, calibration, cloud.stamp_s);
    require(scan.rings.size() == calibration.lasers.size(), "a scan without the model's rings");
    std::size_t returns = 0;
    for (const auto& ring : scan.rings) {
      for (const auto& ret : ring.returns) {
        require(std::isfinite(ret.range_m) && ret.range_m >= 0.0, "a range not finite");
        require(ret.azimuth_rad >= 0.0 && ret.azimuth_rad < 2.0 * M_PI,
                "an azimuth outside [0, 2π)");
        require(std::isfinite(ret.time_s), "a return time not finite");
        ++returns;
      }
    }
    require(returns <= cloud.point_count(), "more returns than points");
    require(scan.start_time_s <= scan.end_time_s, "a scan ends before it starts");
  } catch (const io::MessageError&) {
    // A refused message: what a bad input may do.
  }
}

}  // namespace conicloc::fuzz
