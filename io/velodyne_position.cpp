#include "io/velodyne_position.hpp"

#include <cmath>
#include <cstdlib>
#include <vector>

#include "io/velodyne_packet.hpp"

namespace conicloc::io {
namespace {

constexpr std::size_t kPositionTimestampOffset = 198;
constexpr std::size_t kPpsStatusOffset = 202;
constexpr std::size_t kNmeaOffset = 206;

std::vector<std::string> split_fields(const std::string& text) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    fields.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

std::optional<double> to_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}

// "ddmm.mmmm" (or "dddmm.mmmm") and a hemisphere letter → signed decimal degrees.
std::optional<double> nmea_angle(const std::string& value, const std::string& hemisphere) {
  const auto raw = to_number(value);
  if (!raw || hemisphere.size() != 1) return std::nullopt;
  const double degrees = std::floor(*raw / 100.0);
  const double decimal = degrees + (*raw - degrees * 100.0) / 60.0;
  const char h = hemisphere[0];
  if (h == 'S' || h == 'W') return -decimal;
  if (h == 'N' || h == 'E') return decimal;
  return std::nullopt;
}

// Days since 1970-01-01 of a civil date (proleptic Gregorian; H. Hinnant's days_from_civil).
long days_from_civil(long y, unsigned m, unsigned d) {
  y -= m <= 2;
  const long era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<long>(doe) - 719468;
}

}  // namespace

std::optional<GprmcFix> parse_gprmc(const std::string& sentence) {
  if (sentence.size() < 7 || sentence[0] != '$' || sentence.compare(3, 3, "RMC") != 0) {
    return std::nullopt;
  }
  const std::size_t star = sentence.find('*');
  const std::string body =
      sentence.substr(1, star == std::string::npos ? std::string::npos : star - 1);
  GprmcFix fix;
  if (star != std::string::npos && star + 3 <= sentence.size()) {
    unsigned checksum = 0;
    for (const char c : body) checksum ^= static_cast<unsigned char>(c);
    const unsigned given =
        static_cast<unsigned>(std::strtoul(sentence.substr(star + 1, 2).c_str(), nullptr, 16));
    fix.checksum_ok = checksum == given;
  }
  const auto fields = split_fields(body);
  if (fields.size() < 10) return std::nullopt;
  const auto time = to_number(fields[1]);
  if (!time || fields[1].size() < 6) return std::nullopt;
  const double hh = std::floor(*time / 10000.0);
  const double mm = std::floor((*time - hh * 10000.0) / 100.0);
  const double ss = *time - hh * 10000.0 - mm * 100.0;
  fix.utc_time_of_day_s = hh * 3600.0 + mm * 60.0 + ss;
  fix.valid = fields[2] == "A";
  fix.latitude_deg = nmea_angle(fields[3], fields[4]);
  fix.longitude_deg = nmea_angle(fields[5], fields[6]);
  if (fields[9].size() == 6) {
    const int day = std::atoi(fields[9].substr(0, 2).c_str());
    const int month = std::atoi(fields[9].substr(2, 2).c_str());
    const int yy = std::atoi(fields[9].substr(4, 2).c_str());
    const int year = yy < 80 ? 2000 + yy : 1900 + yy;  // two-digit NMEA year, pivot 1980
    if (day >= 1 && day <= 31 && month >= 1 && month <= 12) {
      fix.utc_epoch_s = static_cast<double>(days_from_civil(year, static_cast<unsigned>(month),
                                                            static_cast<unsigned>(day))) *
                            86400.0 +
                        fix.utc_time_of_day_s;
    }
  }
  return fix;
}

std::optional<PositionPacket> parse_position_packet(std::span<const std::uint8_t> payload) {
  if (payload.size() != velodyne::kPositionPacketBytes) return std::nullopt;
  PositionPacket packet;
  packet.timestamp_us = velodyne::read_u32(payload.data() + kPositionTimestampOffset);
  packet.pps_status = payload[kPpsStatusOffset];
  for (std::size_t i = kNmeaOffset; i < payload.size(); ++i) {
    const char c = static_cast<char>(payload[i]);
    if (c == '\0' || c == '\r' || c == '\n') break;
    packet.nmea.push_back(c);
  }
  packet.gprmc = parse_gprmc(packet.nmea);
  return packet;
}

std::optional<double> utc_hour_start(const PositionPacket& packet) {
  if (!packet.gprmc || !packet.gprmc->utc_epoch_s) return std::nullopt;
  // The NMEA time and the device stamp describe (nearly) the same instant: the hour start is
  // their difference, snapped to a whole hour.
  const double difference = *packet.gprmc->utc_epoch_s - packet.timestamp_us * 1e-6;
  return std::round(difference / 3600.0) * 3600.0;
}

const char* pps_status_name(std::uint8_t status) {
  switch (status) {
    case 0:
      return "absent";
    case 1:
      return "synchronizing";
    case 2:
      return "locked";
    case 3:
      return "error";
    default:
      return "unknown";
  }
}

}  // namespace conicloc::io
