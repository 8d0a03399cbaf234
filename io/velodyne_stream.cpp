#include "io/velodyne_stream.hpp"

#include <algorithm>
#include <cmath>

#include "io/velodyne_model_guess.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::io {
namespace {

constexpr double kHalfHourUs = 1800e6;

int first_azimuth(std::span<const std::uint8_t> payload) {
  return velodyne::read_u16(payload.data() + 2) % velodyne::kAzimuthUnitsPerTurn;
}

}  // namespace

std::size_t StreamStats::rejected_total() const {
  std::size_t total = 0;
  for (const auto count : rejected) total += count;
  return total;
}

double StreamStats::rotation_rpm() const {
  if (turned_time_s <= 0.0) return 0.0;
  return turned_cdeg / 36000.0 / turned_time_s * 60.0;
}

VelodyneStream::VelodyneStream(DatagramSource& source, const sensor::LaserCalibration& calibration,
                               StreamConfig config)
    : source_(source), decoder_(calibration, config.max_block_step_cdeg), config_(config) {}

void VelodyneStream::handle_position(const UdpDatagram& datagram) {
  const auto position = parse_position_packet(datagram.payload);
  if (!position) {
    ++stats_.bad_position_packets;
    return;
  }
  ++stats_.position_packets;
  if (!stats_.utc_hour_start_s) stats_.utc_hour_start_s = utc_hour_start(*position);
  stats_.last_position = *position;
}

void VelodyneStream::check_timing(double period_us) {
  // Only the first packets are looked at: kept for the whole capture, the periods would grow
  // memory by 6 KB per second of VLP-16 data (22 MB an hour).
  if (timing_checked_) return;
  periods_us_.push_back(period_us);
  if (periods_us_.size() < config_.timing_check_packets) return;
  timing_checked_ = true;
  std::nth_element(periods_us_.begin(), periods_us_.begin() + periods_us_.size() / 2,
                   periods_us_.end());
  const double median_us = periods_us_[periods_us_.size() / 2];
  periods_us_ = {};
  const bool dual = stats_.return_mode == static_cast<std::uint8_t>(velodyne::ReturnMode::Dual);
  const auto model = decoder_.calibration().model;
  const auto timed = model_from_packet_period(median_us, dual, stats_.product_id.value_or(0));
  const int lasers = velodyne::packet_layout(model).channels;
  if (timed && velodyne::packet_layout(*timed).channels != lasers) {
    warnings_.push_back("packets arrive every " + std::to_string(median_us) + " us, which fits a " +
                        sensor::sensor_model_name(*timed) + " rather than the " +
                        sensor::sensor_model_name(model) + " being decoded; check --model");
  }
}

void VelodyneStream::reject(const UdpDatagram& datagram, PacketCheck check) {
  ++stats_.rejected[static_cast<std::size_t>(check)];
  if (rejections_.size() < kNamedRejections) {
    rejections_.push_back(
        {datagram.record, check, datagram.payload.size(), datagram.src_address, datagram.src_port});
  }
}

bool VelodyneStream::next(std::vector<DecodedPoint>& points) {
  points.clear();
  while (auto datagram = source_.next()) {
    const bool ours = datagram->dst_port == config_.position_port ||
                      datagram->dst_port == config_.data_port;
    if (!ours) continue;  // the source was asked for more
    if (config_.source_address != 0 && datagram->src_address != config_.source_address) {
      ++stats_.other_senders;
      continue;
    }
    if (datagram->dst_port == config_.position_port) {
      ++stats_.datagrams;
      handle_position(*datagram);
      continue;
    }
    ++stats_.datagrams;
    const auto payload = datagram->payload;
    PacketCheck check = decoder_.check(payload);
    if (check != PacketCheck::Ok) {
      reject(*datagram, check);
      continue;
    }
    const std::uint32_t stamp = VelodyneDecoder::timestamp_us(payload);
    double hours_s = hours_s_;
    bool wrapped = false;
    if (have_previous_) {
      if (stamp == previous_stamp_ && first_azimuth(payload) == previous_first_azimuth_) {
        check = PacketCheck::Duplicate;
      } else if (stamp + kHalfHourUs < previous_stamp_) {
        hours_s += 3600.0;  // the device clock passed the top of the hour
        wrapped = true;
      } else if (stamp < previous_stamp_) {
        check = PacketCheck::TimeBackwards;
      }
    }
    if (check != PacketCheck::Ok) {
      reject(*datagram, check);
      continue;
    }
    const double time_s = hours_s + stamp * 1e-6;
    if (!have_previous_) {
      stats_.first_time_s = time_s;
      stats_.return_mode = VelodyneDecoder::return_mode_byte(payload);
      stats_.product_id = VelodyneDecoder::product_byte(payload);
      const auto named = velodyne::model_from_product_id(*stats_.product_id);
      const auto model = decoder_.calibration().model;
      if (named &&
          velodyne::packet_layout(*named).channels != velodyne::packet_layout(model).channels) {
        warnings_.push_back("product byte names a " + sensor::sensor_model_name(*named) +
                            ", decoding as " + sensor::sensor_model_name(model) +
                            " (old VLP-16 firmware writes the HDL-32E byte 0x21)");
      }
    } else {
      const double dt_s = time_s - stats_.last_time_s;
      const double packet_period_s =
          decoder_.layout().block_period_us() * 1e-6 *
          (stats_.return_mode == static_cast<std::uint8_t>(velodyne::ReturnMode::Dual) ? 6 : 12);
      const auto lost = static_cast<long>(std::lround(dt_s / packet_period_s)) - 1;
      if (lost > 0) {
        stats_.packets_lost += static_cast<std::size_t>(lost);
      } else {
        int step = first_azimuth(payload) - previous_first_azimuth_;
        if (step < 0) step += velodyne::kAzimuthUnitsPerTurn;
        stats_.turned_cdeg += step;
        stats_.turned_time_s += dt_s;
      }
      check_timing(dt_s * 1e6);
    }
    if (wrapped) {
      ++stats_.clock_wraps;
      hours_s_ = hours_s;
    }
    have_previous_ = true;
    previous_stamp_ = stamp;
    previous_first_azimuth_ = first_azimuth(payload);
    stats_.last_time_s = time_s;
    stats_.points += decoder_.decode(payload, time_s, points);
    ++stats_.data_packets;
    return true;
  }
  return false;
}

}  // namespace conicloc::io
