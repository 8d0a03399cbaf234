// `conicloc decode CAPTURE`: Velodyne packets (pcap/pcapng file, bag or live UDP) or a bag of
// point clouds → scans, as CSV, PLY files and statistics.
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>

#include "io/input_error.hpp"
#include "io/open_capture.hpp"
#include "io/scan_assembler.hpp"
#include "io/scan_source.hpp"
#include "io/udp_receiver.hpp"
#include "io/velodyne_model_guess.hpp"
#include "io/velodyne_stream.hpp"
#include "io/veloview_calibration.hpp"
#include "sensor/builtin_calibration.hpp"
#include "tools/capture_report.hpp"
#include "tools/commands.hpp"
#include "tools/point_csv.hpp"

namespace conicloc::tools {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

struct DecodeOptions {
  std::string capture;
  std::string topic;
  std::string model_name;
  std::string calibration_xml;
  std::string csv_path;
  std::string ply_dir;
  bool stats = false;
  int port = io::velodyne::kDataPort;
  int position_port = io::velodyne::kPositionPort;
  double cut_deg = 0.0;
  double max_range_m = 130.0;
  double idle_timeout_s = 0.0;
};

// Ctrl-C ends a live decode cleanly (the handler may only touch a lock-free atomic).
std::atomic<io::UdpReceiver*> g_live_receiver{nullptr};
extern "C" void stop_live_receiver(int) {
  if (auto* receiver = g_live_receiver.load()) receiver->stop();
}

struct ScanTotals {
  std::size_t scans = 0, partial = 0, valid = 0, no_return = 0, out_of_range = 0;
};

const char* csv_return_label(sensor::ReturnKind kind, bool dual_mode) {
  if (dual_mode) return kind == sensor::ReturnKind::Dual ? "dual_strongest" : "dual_last";
  return kind == sensor::ReturnKind::Last ? "last" : "strongest";
}

void write_csv_rows(std::ofstream& csv, const sensor::Scan& scan, bool dual_mode) {
  for (const auto& ring : scan.rings) {
    for (const auto& ret : ring.returns) {
      if (ret.range_m <= 0.0) continue;
      const Eigen::Vector3d p = sensor::sensor_point(ring, ret);
      csv << fmt::format("{},{},{:.4f},{:.3f},{},{:.6f},{:.4f},{:.4f},{:.4f},{}\n", scan.index,
                         ring.ring, ret.azimuth_rad * kRadToDeg, ret.range_m, ret.intensity,
                         ret.time_s, p.x(), p.y(), p.z(), csv_return_label(ret.kind, dual_mode));
    }
  }
}

// Binary little-endian PLY of the valid returns: x y z (float, metres), intensity, ring, time.
void write_ply(const std::string& dir, const sensor::Scan& scan) {
  const std::string path = fmt::format("{}/scan_{:06d}.ply", dir, scan.index);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw io::InputError(path, "", "cannot write PLY file");
  out << "ply\nformat binary_little_endian 1.0\ncomment conicloc decode, sensor frame REP-103\n"
      << "element vertex " << scan.valid_returns() << "\n"
      << "property float x\nproperty float y\nproperty float z\nproperty uchar intensity\n"
      << "property ushort ring\nproperty double time\nend_header\n";
  for (const auto& ring : scan.rings) {
    for (const auto& ret : ring.returns) {
      if (ret.status != sensor::ReturnStatus::Valid) continue;
      const Eigen::Vector3f p = sensor::sensor_point(ring, ret).cast<float>();
      const auto ring_index = static_cast<std::uint16_t>(ring.ring);
      out.write(reinterpret_cast<const char*>(p.data()), 3 * sizeof(float));
      out.write(reinterpret_cast<const char*>(&ret.intensity), 1);
      out.write(reinterpret_cast<const char*>(&ring_index), sizeof ring_index);
      out.write(reinterpret_cast<const char*>(&ret.time_s), sizeof ret.time_s);
    }
  }
  if (!out) throw io::InputError(path, "", "write failed");
}

sensor::SensorModel choose_model(const DecodeOptions& options, bool live) {
  if (!options.model_name.empty()) {
    const auto model = sensor::parse_sensor_model(options.model_name);
    if (!model) throw CLI::ValidationError("--model", "unknown model " + options.model_name);
    spdlog::info("model {} (from --model)", options.model_name);
    return *model;
  }
  if (!live) {
    if (const auto guess = io::guess_model_from_capture(
            options.capture, static_cast<std::uint16_t>(options.port), 200, options.topic)) {
      spdlog::info("model {} (guessed: {})", sensor::sensor_model_name(guess->model),
                   guess->reason);
      return guess->model;
    }
  }
  spdlog::info("model vlp16 (default; name another with --model)");
  return sensor::SensorModel::VLP16;
}

void print_stats(const io::StreamStats& s, const io::CaptureCounts* capture,
                 const ScanTotals& totals, sensor::SensorModel model, const std::string& source) {
  fmt::print("source: {}\n", source);
  fmt::print("model: {}\n", sensor::sensor_model_name(model));
  fmt::print("return_mode: {}\n",
             s.return_mode ? io::velodyne::return_mode_name(*s.return_mode) : "unknown");
  fmt::print("product_byte: {}\n", s.product_id ? fmt::format("0x{:02x}", *s.product_id) : "none");
  if (capture) fmt::print("capture_records: {}\n", capture->records);
  fmt::print("packets_read: {}\n", s.datagrams);
  fmt::print("data_packets: {}\n", s.data_packets);
  fmt::print("position_packets: {}\n", s.position_packets);
  fmt::print("rejected_packets: {}\n", s.rejected_total() + s.bad_position_packets);
  for (std::size_t r = 1; r < io::kPacketCheckCount; ++r) {
    if (s.rejected[r]) {
      fmt::print("  rejected_{}: {}\n", io::packet_check_name(static_cast<io::PacketCheck>(r)),
                 s.rejected[r]);
    }
  }
  if (s.bad_position_packets) fmt::print("  rejected_position_size: {}\n", s.bad_position_packets);
  if (capture) {
    fmt::print("skipped_records: {}\n", capture->truncated_records + capture->snap_length_cut +
                                            capture->not_ipv4_udp + capture->malformed +
                                            capture->foreign_port);
    fmt::print("  truncated_records: {}\n", capture->truncated_records);
    fmt::print("  snap_length_cut: {}\n", capture->snap_length_cut);
    fmt::print("  not_ipv4_udp: {}\n", capture->not_ipv4_udp);
    fmt::print("  malformed_ip_udp: {}\n", capture->malformed);
    fmt::print("  foreign_port: {}\n", capture->foreign_port);
    fmt::print("ip_length_mismatch_kept: {}\n", capture->ip_length_mismatch);
    if (capture->bad_chunks) fmt::print("bag_chunks_skipped: {}\n", capture->bad_chunks);
    if (capture->bad_messages) fmt::print("bag_messages_skipped: {}\n", capture->bad_messages);
  }
  fmt::print("packets_lost_estimate: {}\n", s.packets_lost);
  fmt::print("clock_wraps: {}\n", s.clock_wraps);
  fmt::print("scans: {} ({} partial)\n", totals.scans, totals.partial);
  fmt::print("points: {} valid, {} no-return, {} out-of-range\n", totals.valid, totals.no_return,
             totals.out_of_range);
  fmt::print("rotation_rpm: {:.1f}\n", s.rotation_rpm());
  fmt::print("device_time_s: {:.6f} .. {:.6f}\n", s.first_time_s, s.last_time_s);
  if (s.utc_hour_start_s) fmt::print("utc_hour_start_s: {:.0f}\n", *s.utc_hour_start_s);
  if (s.last_position) {
    fmt::print("pps: {}\n", io::pps_status_name(s.last_position->pps_status));
    const auto& fix = s.last_position->gprmc;
    if (fix && fix->latitude_deg && fix->longitude_deg) {
      fmt::print("gps: {:.6f} {:.6f} ({})\n", *fix->latitude_deg, *fix->longitude_deg,
                 fix->valid ? "valid" : "void");
    }
  }
}

void print_cloud_stats(const io::CaptureCounts& counts, const ScanTotals& totals,
                       sensor::SensorModel model, const std::string& source) {
  fmt::print("source: {}\n", source);
  fmt::print("model: {}\n", sensor::sensor_model_name(model));
  fmt::print("point_clouds: {}\n", counts.records);
  fmt::print("bag_messages_skipped: {}\n", counts.bad_messages);
  fmt::print("truncated_records: {}\n", counts.truncated_records);
  fmt::print("scans: {} ({} partial)\n", totals.scans, totals.partial);
  fmt::print("points: {} valid, {} no-return, {} out-of-range\n", totals.valid, totals.no_return,
             totals.out_of_range);
}

void run_decode(const DecodeOptions& options) {
  const bool live = options.capture.rfind("udp://", 0) == 0;
  std::uint16_t port = static_cast<std::uint16_t>(options.port);
  if (live) {
    const auto colon = options.capture.rfind(':');
    if (colon != std::string::npos && colon > 5 && colon + 1 < options.capture.size()) {
      port = static_cast<std::uint16_t>(std::stoi(options.capture.substr(colon + 1)));
    }
  }
  const sensor::SensorModel model = choose_model(options, live);
  sensor::LaserCalibration calibration = sensor::builtin_calibration(model);
  if (!options.calibration_xml.empty()) {
    auto loaded = io::read_veloview_calibration(options.calibration_xml, model);
    for (const auto& warning : loaded.warnings) spdlog::warn("{}", warning);
    calibration = loaded.calibration;
    spdlog::info("calibration from {}", options.calibration_xml);
  }

  io::ScanSourceOptions source_options;
  source_options.capture = {.ports = {port, static_cast<std::uint16_t>(options.position_port)},
                            .topic = options.topic};
  // A live receiver only listens on the data port; position packets need their own socket.
  source_options.stream.data_port = port;
  source_options.stream.position_port = static_cast<std::uint16_t>(options.position_port);
  source_options.assembler.cut_azimuth_rad = options.cut_deg / kRadToDeg;
  source_options.assembler.max_range_m = options.max_range_m;
  source_options.cloud.max_range_m = options.max_range_m;

  // Live packets are read here; a file (packets or point clouds) by its scan source.
  std::unique_ptr<io::UdpReceiver> receiver;
  std::unique_ptr<io::VelodyneStream> live_stream;
  std::unique_ptr<io::ScanAssembler> live_assembler;
  std::unique_ptr<io::ScanSource> file;
  if (live) {
    receiver = std::make_unique<io::UdpReceiver>(port, options.idle_timeout_s);
    g_live_receiver.store(receiver.get());
    std::signal(SIGINT, stop_live_receiver);
    spdlog::info("listening on {} (Ctrl-C to stop)", receiver->name());
    live_stream =
        std::make_unique<io::VelodyneStream>(*receiver, calibration, source_options.stream);
    live_assembler = std::make_unique<io::ScanAssembler>(calibration, source_options.assembler);
  } else {
    file = io::open_scan_source(options.capture, calibration, source_options);
    spdlog::info("{}: {}{}", options.capture, file->format(),
                 file->stream() ? "" : ", point clouds");
  }
  const io::VelodyneStream* stream = live ? live_stream.get() : file->stream();
  const std::string source_name = live ? receiver->name() : file->name();

  std::ofstream csv;
  if (!options.csv_path.empty()) {
    csv.open(options.csv_path);
    if (!csv) throw io::InputError(options.csv_path, "", "cannot write CSV");
    csv << kPointCsvHeader;
  }
  if (!options.ply_dir.empty()) std::filesystem::create_directories(options.ply_dir);

  ScanTotals totals;
  auto emit = [&](const sensor::Scan& scan) {
    const bool dual = stream && stream->stats().return_mode ==
                                    static_cast<std::uint8_t>(io::velodyne::ReturnMode::Dual);
    ++totals.scans;
    totals.partial += scan.partial ? 1 : 0;
    for (const auto& ring : scan.rings) {
      for (const auto& ret : ring.returns) {
        totals.valid += ret.status == sensor::ReturnStatus::Valid;
        totals.no_return += ret.status == sensor::ReturnStatus::NoReturn;
        totals.out_of_range += ret.status == sensor::ReturnStatus::OutOfRange;
      }
    }
    if (csv.is_open()) write_csv_rows(csv, scan, dual);
    if (!options.ply_dir.empty()) write_ply(options.ply_dir, scan);
    spdlog::debug("scan {}: {} valid returns{}", scan.index, scan.valid_returns(),
                  scan.partial ? " (partial)" : "");
  };
  if (live) {
    std::vector<io::DecodedPoint> points;
    std::vector<sensor::Scan> scans;
    while (live_stream->next(points)) {
      live_assembler->add(points, scans);
      for (const auto& scan : scans) emit(scan);
      scans.clear();
    }
    if (auto last = live_assembler->finish()) emit(*last);
    g_live_receiver.store(nullptr);
  } else {
    while (const auto scan = file->next()) emit(*scan);
  }

  const io::CaptureCounts* counts = file ? &file->counts() : nullptr;
  if (!stream) {  // point clouds
    log_capture_problems(options.capture, counts, io::StreamStats{}, {});
    spdlog::info("{} point clouds, {} valid returns", totals.scans, totals.valid);
    if (options.stats) print_cloud_stats(*counts, totals, model, source_name);
    if (csv.is_open()) {
      csv.close();
      if (!csv) throw io::InputError(options.csv_path, "", "write failed");
    }
    if (totals.scans == 0) {
      spdlog::error("{}: no point cloud decoded", source_name);
      throw CLI::RuntimeError(2);
    }
    return;
  }
  for (const auto& warning : stream->warnings()) spdlog::warn("{}", warning);
  const auto& s = stream->stats();
  log_capture_problems(options.capture, counts, s, stream->first_rejections());
  if (s.rejected_total())
    spdlog::warn("{} data packets rejected (see --stats)", s.rejected_total());
  spdlog::info("{} data packets, {} scans, {} valid returns", s.data_packets, totals.scans,
               totals.valid);
  if (options.stats) print_stats(s, counts, totals, model, source_name);
  if (csv.is_open()) {
    csv.close();
    if (!csv) throw io::InputError(options.csv_path, "", "write failed");
  }
  if (s.data_packets == 0) {
    spdlog::error("{}: no Velodyne data packets on port {}", source_name, port);
    throw CLI::RuntimeError(2);
  }
}

}  // namespace

void add_decode_command(CLI::App& app) {
  auto options = std::make_shared<DecodeOptions>();
  auto* cmd = app.add_subcommand(
      "decode",
      "Decode Velodyne packets into scans (VLP-16, Puck LITE/Hi-Res, HDL-32E, VLP-32C).\n"
      "CAPTURE is a pcap/pcapng file, a ROS bag (MCAP, ROS 2 .db3 file or folder, ROS 1 .bag)\n"
      "of velodyne_msgs/VelodyneScan or sensor_msgs/PointCloud2 (one scan per cloud), or\n"
      "udp://:PORT for live packets (Ctrl-C stops).\n"
      "CSV columns: scan,ring,azimuth_deg,range_m,intensity,time_s,x,y,z,return - one row per\n"
      "return with range > 0; azimuth counter-clockwise from x (REP-103), x y z in the sensor\n"
      "frame (m), time_s device time unwrapped (s). return: strongest | last, or in dual mode\n"
      "dual_last (the last echo; an identical pair is written once as dual_last) and\n"
      "dual_strongest (the strongest other echo).");
  cmd->add_option("CAPTURE", options->capture,
                  "pcap/pcapng file, ROS bag (MCAP, .db3, .bag), or udp://:PORT")
      ->required();
  cmd->add_option(
      "--topic", options->topic,
      "Bag topic of velodyne_msgs/VelodyneScan or sensor_msgs/PointCloud2 (default: the "
      "only one)");
  cmd->add_option("--model", options->model_name,
                  "vlp16|puck-lite|puck-hires|hdl32e|vlp32c (default: guessed from packet "
                  "timing and the product byte, which old VLP-16 firmware sets to 0x21)");
  cmd->add_option("--calibration", options->calibration_xml, "VeloView XML calibration")
      ->check(CLI::ExistingFile);
  cmd->add_option("--csv", options->csv_path, "Write returns as CSV");
  cmd->add_option("--ply", options->ply_dir, "Write one binary PLY per scan into this directory");
  cmd->add_flag(
      "--stats", options->stats,
      "Print packets read and rejected by reason, scans, points, return mode, model, rpm");
  cmd->add_option("--port", options->port, "UDP port of data packets")->capture_default_str();
  cmd->add_option("--position-port", options->position_port, "UDP port of position packets")
      ->capture_default_str();
  cmd->add_option("--cut-deg", options->cut_deg,
                  "Azimuth (deg, REP-103) where a scan starts and ends")
      ->capture_default_str();
  cmd->add_option("--max-range", options->max_range_m, "Returns beyond (m) are out of range")
      ->capture_default_str();
  cmd->add_option("--idle-timeout", options->idle_timeout_s,
                  "Live: stop after this many seconds without packets (0: never)")
      ->capture_default_str();
  cmd->callback([options] { run_decode(*options); });
}

}  // namespace conicloc::tools
