// Velodyne decode throughput (points/s) and capture read rate (MB/s), on the shared VLP-16
// recording (skipped when absent) and on an encoded synthetic buffer. Baseline in the same run: a
// straightforward decoder that calls cos/sin per point.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>

#include "io/packet_encoder.hpp"
#include "io/pcap_reader.hpp"
#include "io/pcap_writer.hpp"
#include "io/velodyne_decoder.hpp"
#include "sensor/builtin_calibration.hpp"

namespace {

using namespace conicloc;
using Payload = std::array<std::uint8_t, io::velodyne::kDataPacketBytes>;

const std::string kCapture =
    std::string(CONICLOC_SHARED_DATA) + "/velodyne/vlp-16-test-90deg-1-50-frames.pcap";

std::vector<Payload> synthetic_packets(int count) {
  io::PacketEncoder encoder;
  for (int i = 0; i < count * 24; ++i) {
    io::FiringSequence s;
    s.time_s = i * 55.296e-6;
    s.azimuth_rad = -2 * M_PI * 10.0 * s.time_s;
    for (int k = 0; k < 16; ++k) {
      s.range_m[k] = 2.0 + std::fmod(i * 0.37 + k, 40.0);
      s.intensity[k] = static_cast<std::uint8_t>(i + k);
    }
    encoder.add(s);
  }
  std::vector<Payload> out;
  for (const auto& p : encoder.take_packets()) out.push_back(p.payload);
  return out;
}

std::vector<Payload> capture_packets() {
  std::vector<Payload> out;
  io::PcapReader reader(kCapture, {io::velodyne::kDataPort});
  while (auto d = reader.next()) {
    if (d->payload.size() != io::velodyne::kDataPacketBytes) continue;
    Payload p;
    std::copy(d->payload.begin(), d->payload.end(), p.begin());
    out.push_back(p);
  }
  return out;
}

void run_decode(benchmark::State& state, const std::vector<Payload>& packets) {
  const io::VelodyneDecoder decoder(sensor::builtin_calibration(sensor::SensorModel::VLP16));
  std::vector<io::DecodedPoint> points;
  points.reserve(packets.size() * 384);
  std::size_t total = 0;
  for (auto _ : state) {
    points.clear();
    double t = 0.0;
    for (const auto& p : packets) {
      total += decoder.decode(p, t, points);
      t += 1.3e-3;
    }
    benchmark::DoNotOptimize(points.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(total));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * packets.size() *
                                                    io::velodyne::kDataPacketBytes));
}

void BM_DecodeSynthetic(benchmark::State& state) {
  static const auto packets = synthetic_packets(2000);
  run_decode(state, packets);
}
BENCHMARK(BM_DecodeSynthetic)->Unit(benchmark::kMillisecond);

void BM_DecodeVlp16Capture(benchmark::State& state) {
  if (!std::filesystem::exists(kCapture)) {
    state.SkipWithError("shared VLP-16 capture absent");
    return;
  }
  static const auto packets = capture_packets();
  run_decode(state, packets);
}
BENCHMARK(BM_DecodeVlp16Capture)->Unit(benchmark::kMillisecond);

// Baseline: per-point trig, per-firing interpolation, double math.
void BM_DecodeNaiveTrigBaseline(benchmark::State& state) {
  static const auto packets = synthetic_packets(2000);
  const auto calibration = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  struct Point {
    double x, y, z, t;
  };
  std::vector<Point> points;
  points.reserve(packets.size() * 384);
  std::size_t total = 0;
  for (auto _ : state) {
    points.clear();
    for (const auto& p : packets) {
      for (int b = 0; b < 12; ++b) {
        const std::uint8_t* block = p.data() + b * 100;
        const int az = io::velodyne::read_u16(block + 2);
        const int next = b < 11 ? io::velodyne::read_u16(block + 102) : az + 40;
        const double step = std::fmod(next - az + 36000.0, 36000.0);
        for (int r = 0; r < 32; ++r) {
          const int k = r % 16, s = r / 16;
          const double alpha = (az + step * (55.296 * s + 2.304 * k) / 110.592) * M_PI / 18000.0;
          const double range = io::velodyne::read_u16(block + 4 + 3 * r) * 0.002;
          const double phi = calibration.lasers[k].elevation_rad;
          points.push_back({range * std::cos(phi) * std::cos(-alpha),
                            range * std::cos(phi) * std::sin(-alpha), range * std::sin(phi), 0.0});
          ++total;
        }
      }
    }
    benchmark::DoNotOptimize(points.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(total));
}
BENCHMARK(BM_DecodeNaiveTrigBaseline)->Unit(benchmark::kMillisecond);

void run_read(benchmark::State& state, const std::string& path) {
  const auto bytes = std::filesystem::file_size(path);
  std::size_t datagrams = 0;
  for (auto _ : state) {
    io::PcapReader reader(path, {io::velodyne::kDataPort, io::velodyne::kPositionPort});
    while (auto d = reader.next()) {
      benchmark::DoNotOptimize(d->payload.data());
      ++datagrams;
    }
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
  state.SetItemsProcessed(static_cast<std::int64_t>(datagrams));
}

void BM_ReadVlp16Capture(benchmark::State& state) {
  if (!std::filesystem::exists(kCapture)) {
    state.SkipWithError("shared VLP-16 capture absent");
    return;
  }
  run_read(state, kCapture);
}
BENCHMARK(BM_ReadVlp16Capture)->Unit(benchmark::kMillisecond);

void BM_ReadSyntheticCapture(benchmark::State& state) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "conicloc_bench_decode.pcap").string();
  {
    io::PcapWriter writer(path);
    double t = 1.7e9;
    for (const auto& p : synthetic_packets(5000)) writer.write_udp(p, t += 1.327e-3);
  }
  run_read(state, path);
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadSyntheticCapture)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
