#include "io/scan_assembler.hpp"

#include <algorithm>
#include <cmath>

#include "io/packet_encoder.hpp"

namespace conicloc::io {
namespace {

// A gap larger than this between consecutive firings means packets were lost (a block step is
// < 1° up to 1200 rpm).
constexpr int kGapCdeg = 200;

}  // namespace

sensor::ReturnKind return_kind(velodyne::ReturnLabel label) {
  switch (label) {
    case velodyne::ReturnLabel::Strongest:
      return sensor::ReturnKind::Strongest;
    case velodyne::ReturnLabel::DualStrongest:
      return sensor::ReturnKind::Dual;
    case velodyne::ReturnLabel::Last:
    case velodyne::ReturnLabel::DualLast:
    case velodyne::ReturnLabel::DualBoth:
      return sensor::ReturnKind::Last;
  }
  return sensor::ReturnKind::Strongest;
}

ScanAssembler::ScanAssembler(const sensor::LaserCalibration& calibration,
                             ScanAssemblerConfig config)
    : calibration_(calibration),
      config_(config),
      cut_cdeg_(velodyne_azimuth_from_rad(config.cut_azimuth_rad)) {}

void ScanAssembler::start_scan() {
  sensor::Scan scan = sensor::empty_scan(calibration_);
  scan.index = next_index_++;
  open_ = std::move(scan);
  missing_cdeg_ = 0;
}

sensor::Scan ScanAssembler::close_scan() {
  sensor::Scan scan = std::move(*open_);
  open_.reset();
  const int covered = last_rel_ - first_rel_ - missing_cdeg_;
  // The last firing of a full turn is one firing step short of 360°.
  scan.partial = covered + config_.full_turn_tolerance_cdeg < velodyne::kAzimuthUnitsPerTurn;
  sensor::sort_rings_and_time(scan);
  return scan;
}

void ScanAssembler::add(std::span<const DecodedPoint> points,
                        std::vector<sensor::Scan>& completed) {
  for (const auto& point : points) {
    int rel = static_cast<int>(point.firing_azimuth_cdeg) - cut_cdeg_;
    if (rel < 0) rel += velodyne::kAzimuthUnitsPerTurn;
    const bool crossed_cut = rel + velodyne::kAzimuthUnitsPerTurn / 2 < last_rel_;
    const bool stalled = point.time_s - last_time_s_ > config_.max_time_gap_s;
    if (open_ && (crossed_cut || stalled)) {
      if (stalled) missing_cdeg_ = velodyne::kAzimuthUnitsPerTurn;  // cut short by silence
      completed.push_back(close_scan());
    }
    if (!open_) {
      start_scan();
      first_rel_ = rel;
      last_rel_ = rel;
    } else if (rel - last_rel_ > kGapCdeg) {
      missing_cdeg_ += rel - last_rel_;  // lost packets inside the rotation
    }
    last_rel_ = std::max(last_rel_, rel);
    last_time_s_ = point.time_s;
    sensor::Return ret;
    ret.azimuth_rad = point.azimuth_rad;
    ret.range_m = point.range_m;
    ret.time_s = point.time_s;
    ret.intensity = point.intensity;
    ret.kind = return_kind(point.label);
    if (point.range_m <= 0.0f) {
      ret.status = sensor::ReturnStatus::NoReturn;
    } else if (point.range_m > config_.max_range_m || point.range_m < config_.min_range_m) {
      ret.status = sensor::ReturnStatus::OutOfRange;
    }
    const int ring = calibration_.lasers[point.channel].ring;
    open_->rings[static_cast<std::size_t>(ring)].returns.push_back(ret);
  }
}

std::optional<sensor::Scan> ScanAssembler::finish() {
  if (!open_) return std::nullopt;
  return close_scan();
}

}  // namespace conicloc::io
