#pragma once
// Velodyne position packets (UDP port 8308, 512-byte payload; VLP-16 manual 9.4, HDL-32E manual):
// byte 198 timestamp (uint32 LE, µs past the hour), 202 PPS status, 206.. the NMEA $GPRMC
// sentence (NUL- or CR/LF-terminated). The GPRMC time and date put the device clock on UTC.
//
// Example:
//   auto position = io::parse_position_packet(payload);          // nullopt: not 512 bytes
//   if (position && position->gprmc && position->gprmc->utc_epoch_s)
//     hour_start = io::utc_hour_start(*position);

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace conicloc::io {

enum class PpsStatus : std::uint8_t { Absent = 0, Synchronizing = 1, Locked = 2, Error = 3 };

struct GprmcFix {
  double utc_time_of_day_s = 0.0;       ///< hhmmss.sss
  std::optional<double> utc_epoch_s;    ///< seconds since 1970 when the date field is present
  bool valid = false;                   ///< status 'A' (active) vs 'V' (void)
  std::optional<double> latitude_deg;   ///< north positive
  std::optional<double> longitude_deg;  ///< east positive
  bool checksum_ok = false;
};

struct PositionPacket {
  std::uint32_t timestamp_us = 0;
  std::uint8_t pps_status = 0;
  std::string nmea;               ///< the sentence as sent, without line end
  std::optional<GprmcFix> gprmc;  ///< when the sentence is a well-formed $GPRMC / $GNRMC
};

/// Parses a 512-byte position payload; nullopt for any other size.
std::optional<PositionPacket> parse_position_packet(std::span<const std::uint8_t> payload);

/// Parses an NMEA RMC sentence
/// ("$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A").
std::optional<GprmcFix> parse_gprmc(const std::string& sentence);

/// UTC (seconds since 1970) of the top of the hour the packet's device stamp counts from: the
/// device clock in UTC is utc_hour_start + timestamp_us·1e-6. nullopt without a dated GPRMC.
std::optional<double> utc_hour_start(const PositionPacket& packet);

/// "absent", "synchronizing", "locked", "error".
const char* pps_status_name(std::uint8_t status);

}  // namespace conicloc::io
