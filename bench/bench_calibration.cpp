// The calibration solver (calib/calibration_solver.hpp) on the tests' box room: a tilted VLP-16
// on a carrier moving through 8 scans, every laser fired every 0.5° over 0.1 s per scan, 2 cm of
// range noise, the planes adjusted (~55,000 returns).
// BM_RayJacobian: one return's ∂(r − r̂)/∂(14 ray parameters), analytic (range_residual_gradient,
// what the solver uses) against the central differences it replaced (28 residual evaluations),
// in the same run. BM_Calibrate: the whole fit on 1 and 2 threads (the same result on any).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "calib/calibration_solver.hpp"
#include "sensor/builtin_calibration.hpp"
#include "test/synthetic_room.hpp"

namespace cc = conicloc::calib;

namespace {

constexpr double kDeg = M_PI / 180.0;

struct Scene {
  conicloc::maps::PlaneMap map = conicloc::test::make_box_room();
  conicloc::sensor::LaserCalibration decode =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  cc::Mounting mounting{1.2, 2.0 * kDeg, -5.0 * kDeg};
  std::vector<cc::ScanPose> poses;
  std::vector<cc::Return> returns;
};

const Scene& scene() {
  static const Scene built = [] {
    Scene s;
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 0.02);
    for (int k = 0; k < 8; ++k) {
      s.poses.push_back({2.5 + 0.7 * k, 2.0 + 0.3 * (k % 3), 0.4 * k, 0.0, 0.8, 0.05, 0.2});
    }
    for (int scan = 0; scan < static_cast<int>(s.poses.size()); ++scan) {
      for (int laser = 0; laser < 16; ++laser) {
        const conicloc::sensor::Laser& l = s.decode.lasers[laser];
        for (int step = 0; step < 720; ++step) {
          const double tau = 0.1 * (step / 720.0 - 1.0);
          const Eigen::Isometry3d T = cc::map_from_fire(s.mounting, s.poses[scan], tau);
          const double theta = step * 0.5 * kDeg;
          const Eigen::Vector3d direction(std::cos(l.elevation_rad) * std::cos(theta),
                                          std::cos(l.elevation_rad) * std::sin(theta),
                                          std::sin(l.elevation_rad));
          const double range = conicloc::test::cast_ray(
              s.map, T * Eigen::Vector3d(0, 0, l.vertical_offset_m), T.linear() * direction);
          if (!std::isfinite(range) || range < 0.5) continue;
          s.returns.push_back({laser, scan, theta, range + noise(rng), tau});
        }
      }
    }
    return s;
  }();
  return built;
}

// One return on the room's first wall, the ray's parameters at the truth.
struct OneRay {
  const conicloc::sensor::Laser& laser = scene().decode.lasers[3];
  cc::LaserCorrection correction{};
  cc::Return ret{3, 0, 0.3, 4.0, -0.05};
  const conicloc::maps::PlanarPolygon& polygon = scene().map.polygons[1];
};

void BM_RayJacobian_Analytic(benchmark::State& state) {
  const OneRay r;
  const cc::ScanPose& pose = scene().poses[0];
  for (auto _ : state) {
    benchmark::DoNotOptimize(cc::range_residual_gradient(r.laser, r.correction, scene().mounting,
                                                         pose, r.ret, r.polygon, {}));
  }
}

void BM_RayJacobian_CentralDifferences(benchmark::State& state) {
  const OneRay r;
  const cc::ScanPose& pose = scene().poses[0];
  const auto residual = [&](const cc::RayGradient& v) {
    const cc::LaserCorrection c{v(0), v(1), v(2), v(3)};
    const cc::Mounting m{scene().mounting.height_m + v(4), scene().mounting.roll_rad + v(5),
                         scene().mounting.pitch_rad + v(6)};
    const cc::ScanPose p{pose.x_m + v(7),           pose.y_m + v(8),
                         pose.yaw_rad + v(9),       pose.floor_z_m,
                         pose.vx_mps + v(10),       pose.vy_mps + v(11),
                         pose.yaw_rate_rps + v(12), pose.yaw_acceleration_rps2 + v(13)};
    const Eigen::Isometry3d T = cc::map_from_fire(m, p, r.ret.time_s);
    return cc::range_residual(r.polygon, {}, T * cc::laser_origin(r.laser, c),
                              cc::map_point(r.laser, c, m, p, r.ret));
  };
  for (auto _ : state) {
    cc::RayGradient gradient;
    for (int j = 0; j < cc::kRayParameters; ++j) {
      cc::RayGradient plus = cc::RayGradient::Zero(), minus = cc::RayGradient::Zero();
      plus(j) = 1e-6;
      minus(j) = -1e-6;
      gradient(j) = (residual(plus) - residual(minus)) / 2e-6;
    }
    benchmark::DoNotOptimize(gradient);
  }
}

void BM_Calibrate(benchmark::State& state) {
  const Scene& s = scene();
  cc::CalibrationConfig config;
  config.threads = static_cast<int>(state.range(0));
  std::vector<cc::ScanPose> start = s.poses;
  for (auto& pose : start) {  // as the localizer leaves them
    pose.x_m += 0.02;
    pose.yaw_rad -= 0.2 * kDeg;
    pose.vx_mps -= 0.05;
  }
  const cc::Mounting mounting{s.mounting.height_m - 0.02, s.mounting.roll_rad + 0.2 * kDeg,
                              s.mounting.pitch_rad};
  for (auto _ : state) {
    benchmark::DoNotOptimize(cc::calibrate(s.map, s.decode, s.returns, mounting, start, config));
  }
  state.counters["returns"] = static_cast<double>(s.returns.size());
}

}  // namespace

BENCHMARK(BM_RayJacobian_Analytic);
BENCHMARK(BM_RayJacobian_CentralDifferences);
BENCHMARK(BM_Calibrate)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
