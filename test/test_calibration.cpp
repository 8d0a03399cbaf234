// calib/: corrections, mounting and scan poses recovered exactly from noise-free returns of known
// planes, and the stiff cases (a laser at 0° elevation, a plane through the sensor origin,
// near-parallel planes) flagged or solved, never given garbage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "calib/calibration_solver.hpp"
#include "calib/truth_comparison.hpp"
#include "localizer/conic/pose.hpp"
#include "sensor/builtin_calibration.hpp"
#include "sim/map_errors.hpp"
#include "synthetic_room.hpp"

namespace conicloc::calib {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kExact = 1e-9;  // metres and radians: noise-free data fit to rounding

struct Scene {
  maps::PlaneMap map;
  sensor::LaserCalibration decode = sensor::builtin_calibration(sensor::SensorModel::VLP16);
  std::vector<LaserCorrection> truth = std::vector<LaserCorrection>(16);
  // Tilted, so each laser meets the floor and ceiling at ranges varying over its turn (a level
  // sensor sees them at one range: vertical offset and elevation would not separate).
  Mounting mounting{1.2, 2.0 * kDeg, -1.5 * kDeg};
  // Scans taken on the move: forward at up to 1.2 m/s, sideways, turning at up to 40°/s, the
  // turn speeding up or slowing down at up to 3 rad/s².
  std::vector<ScanPose> poses = {{2.5, 2.0, 0.3, 0.0, 1.0, 0.0, 0.2, 3.0},
                                 {5.0, 3.5, 1.9, 0.0, 0.6, 0.1, -0.7, 0.0},
                                 {3.0, 4.5, -2.2, 0.0, 1.2, -0.1, 0.0, -2.0},
                                 {8.5, 4.0, 2.8, 0.0, 0.0, 0.0, 0.4, -3.0},
                                 {5.5, 1.5, -0.9, 0.0, 0.8, 0.05, 0.1, 1.0}};
};

// Small, varied true corrections. Vertical offsets are non-zero only on the two steepest
// lasers, opposite, and azimuth offsets sum to zero: the truth sits in the solver's gauge
// (mean Δo = 0, mean Δψ = 0), so it is the exact answer.
void set_truth(Scene& scene) {
  for (int k = 0; k < 16; ++k) {
    auto& c = scene.truth[k];
    c.elevation_rad = 0.08 * kDeg * std::sin(1.7 * k + 0.3);
    c.azimuth_rad = 0.15 * kDeg * std::cos(2.0 * M_PI * k / 16.0);
    c.range_m = 0.012 * std::cos(0.9 * k + 1.0);
  }
  scene.truth[0].vertical_offset_m = 0.003;   // −15°
  scene.truth[2].vertical_offset_m = -0.003;  // −13°
}

// Every laser fired every 2° from every scan pose at the true sensor, recorded as the decoder
// would report it with the decode calibration: θ − Δψ, r − Δd.
// Fired over the 0.1 s before each scan's end (τ from −0.1 to 0 with the azimuth) from where the
// carrier's velocities (ScanPose) have taken the sensor.
std::vector<Return> fire(const Scene& scene) {
  const auto truth = corrected(scene.decode, scene.truth);
  std::vector<Return> returns;
  for (int s = 0; s < static_cast<int>(scene.poses.size()); ++s) {
    for (int k = 0; k < 16; ++k) {
      const sensor::Laser& laser = truth.lasers[k];
      for (int step = 0; step < 180; ++step) {
        const double tau = 0.1 * (step / 180.0 - 1.0);
        const Eigen::Isometry3d T = map_from_fire(scene.mounting, scene.poses[s], tau);
        const double theta = step * 2.0 * kDeg + 0.37;
        const Eigen::Vector3d direction(std::cos(laser.elevation_rad) * std::cos(theta),
                                        std::cos(laser.elevation_rad) * std::sin(theta),
                                        std::sin(laser.elevation_rad));
        const double range = test::cast_ray(
            scene.map, T * Eigen::Vector3d(0, 0, laser.vertical_offset_m), T.linear() * direction);
        if (!std::isfinite(range) || range < 0.5) continue;
        Return r;
        r.laser = k;
        r.scan = s;
        r.azimuth_rad = theta - scene.truth[k].azimuth_rad;
        r.range_m = range - scene.truth[k].range_m;
        r.time_s = tau;
        returns.push_back(r);
      }
    }
  }
  return returns;
}

// `returns` with Gaussian range noise of σ, drawn from `seed`.
std::vector<Return> with_range_noise(std::vector<Return> returns, double sigma_m, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma_m);
  for (Return& ret : returns) ret.range_m += noise(rng);
  return returns;
}

// The map the rays were cast on, known exactly: its planes are held fixed.
CalibrationConfig exact_map() {
  CalibrationConfig config;
  config.map_sigma_m = 0.0;
  return config;
}

// The solver's start: nominal calibration, the mounting and poses a few cm and tenths of a
// degree off (as the localizer leaves them).
CalibrationResult solve(const Scene& scene, const std::vector<Return>& returns,
                        const CalibrationConfig& config = exact_map()) {
  std::vector<ScanPose> start = scene.poses;
  for (std::size_t s = 0; s < start.size(); ++s) {
    start[s].x_m += 0.03 * std::cos(1.0 + s);
    start[s].y_m -= 0.02 * std::sin(2.0 + s);
    start[s].yaw_rad += 0.3 * kDeg * std::cos(3.0 * s);
    start[s].vx_mps += 0.05 * std::sin(1.0 + s);  // the localizer's motion from the scan before
    start[s].vy_mps -= 0.03 * std::cos(2.0 + s);
    start[s].yaw_rate_rps += 2.0 * kDeg * std::sin(3.0 + s);
    start[s].yaw_acceleration_rps2 = 0.0;  // the localizer's motion has none
  }
  const Mounting mounting{scene.mounting.height_m - 0.03, scene.mounting.roll_rad - 0.3 * kDeg,
                          scene.mounting.pitch_rad + 0.2 * kDeg};
  return calibrate(scene.map, scene.decode, returns, mounting, start, config);
}

// Everything observable back to the truth.
void expect_exact(const Scene& scene, const CalibrationResult& result) {
  ASSERT_EQ(result.lasers.size(), 16u);
  for (int k = 0; k < 16; ++k) {
    const auto& e = result.lasers[k];
    const std::array<double, 4> estimate = {e.correction.elevation_rad,
                                            e.correction.vertical_offset_m,
                                            e.correction.azimuth_rad, e.correction.range_m};
    const std::array<double, 4> truth = {scene.truth[k].elevation_rad,
                                         scene.truth[k].vertical_offset_m,
                                         scene.truth[k].azimuth_rad, scene.truth[k].range_m};
    for (int i = 0; i < 4; ++i) {
      if (!e.observability.observable[i]) continue;
      EXPECT_NEAR(estimate[i], truth[i], kExact) << "laser " << k << " correction " << i;
    }
  }
  EXPECT_NEAR(result.mounting.height_m, scene.mounting.height_m, kExact);
  EXPECT_NEAR(result.mounting.roll_rad, scene.mounting.roll_rad, kExact);
  EXPECT_NEAR(result.mounting.pitch_rad, scene.mounting.pitch_rad, kExact);
  for (std::size_t s = 0; s < scene.poses.size(); ++s) {
    EXPECT_NEAR(result.poses[s].x_m, scene.poses[s].x_m, kExact);
    EXPECT_NEAR(result.poses[s].y_m, scene.poses[s].y_m, kExact);
    EXPECT_NEAR(result.poses[s].yaw_rad, scene.poses[s].yaw_rad, kExact);
    EXPECT_NEAR(result.poses[s].vx_mps, scene.poses[s].vx_mps, kExact);
    EXPECT_NEAR(result.poses[s].vy_mps, scene.poses[s].vy_mps, kExact);
    EXPECT_NEAR(result.poses[s].yaw_rate_rps, scene.poses[s].yaw_rate_rps, kExact);
    EXPECT_NEAR(result.poses[s].yaw_acceleration_rps2, scene.poses[s].yaw_acceleration_rps2,
                kExact);
  }
  EXPECT_LT(result.rms_m, kExact) << result.iterations << " iterations, converged "
                                  << result.converged;
  EXPECT_TRUE(result.converged);
}

// range_residual_gradient against central differences of range_residual itself, over every
// polygon of the room, lasers with corrections, a tilted mount, a carrier moving and turning
// through the scan (the returns fired up to 0.1 s before its end) and moved planes: the solver's
// Jacobian is the residual's derivative.
TEST(Calibration, TheRangeResidualsGradientIsItsDerivative) {
  Scene scene;
  scene.map = test::make_box_room();
  set_truth(scene);
  scene.truth[5].vertical_offset_m = 0.004;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int checked = 0;
  for (const maps::PlanarPolygon& polygon : scene.map.polygons) {
    const PlaneCorrection plane{0.02 * unit(rng), 0.004 * unit(rng), 0.003 * unit(rng)};
    for (int trial = 0; trial < 20; ++trial) {
      const int k = trial % 16;
      Return ret;
      ret.laser = k;
      ret.azimuth_rad = M_PI * unit(rng);
      ret.range_m = 4.0 + 2.0 * unit(rng);
      ret.time_s = -0.05 * (1.0 + unit(rng));
      const ScanPose pose{5.0 + unit(rng), 3.0 + unit(rng), M_PI * unit(rng), 0.0,
                          1.2 * unit(rng), 0.3 * unit(rng), 1.5 * unit(rng),  4.0 * unit(rng)};
      auto residual = [&](const RayGradient& v) {
        const LaserCorrection c{scene.truth[k].elevation_rad + v(0),
                                scene.truth[k].vertical_offset_m + v(1),
                                scene.truth[k].azimuth_rad + v(2), scene.truth[k].range_m + v(3)};
        const Mounting m{scene.mounting.height_m + v(4), scene.mounting.roll_rad + v(5),
                         scene.mounting.pitch_rad + v(6)};
        const ScanPose p{pose.x_m + v(7),           pose.y_m + v(8),
                         pose.yaw_rad + v(9),       pose.floor_z_m,
                         pose.vx_mps + v(10),       pose.vy_mps + v(11),
                         pose.yaw_rate_rps + v(12), pose.yaw_acceleration_rps2 + v(13)};
        const sensor::Laser& laser = scene.decode.lasers[k];
        const Eigen::Isometry3d T = map_from_fire(m, p, ret.time_s);
        return range_residual(polygon, plane, T * laser_origin(laser, c),
                              map_point(laser, c, m, p, ret));
      };
      const RayGradient zero = RayGradient::Zero();
      const Eigen::Isometry3d T = map_from_fire(scene.mounting, pose, ret.time_s);
      const sensor::Laser& laser = scene.decode.lasers[k];
      const Eigen::Vector3d origin = T * laser_origin(laser, scene.truth[k]);
      if (incidence_cosine(polygon, plane, origin,
                           map_point(laser, scene.truth[k], scene.mounting, pose, ret)) < 0.2) {
        continue;  // near grazing the residual is steep: differences need a finer step
      }
      const RayGradient analytic =
          range_residual_gradient(laser, scene.truth[k], scene.mounting, pose, ret, polygon, plane);
      constexpr double h = 1e-6;
      for (int j = 0; j < kRayParameters; ++j) {
        RayGradient plus = zero, minus = zero;
        plus(j) = h;
        minus(j) = -h;
        const double numeric = (residual(plus) - residual(minus)) / (2.0 * h);
        EXPECT_NEAR(analytic(j), numeric, 1e-6 * std::max(1.0, std::abs(numeric)))
            << "polygon " << &polygon - scene.map.polygons.data() << " laser " << k << " parameter "
            << j;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
}

// E(τ) is the motion of a carrier at constant speed and turn rate: integrated in small steps from
// the reference time back to τ, the carrier lands where E(τ) puts it but for the arc's length
// E gives its chord ((ω·τ)²/24 of the distance, calibration_model.hpp).
TEST(Calibration, TheCarriersMotionIsAConstantTwist) {
  ScanPose pose;
  pose.vx_mps = 1.1;
  pose.vy_mps = -0.2;
  pose.yaw_rate_rps = 0.9;
  for (const double tau : {-0.1, -0.037, 0.0}) {
    Eigen::Isometry3d integrated = Eigen::Isometry3d::Identity();
    constexpr int kSteps = 20000;
    const double dt = tau / kSteps;
    for (int i = 0; i < kSteps; ++i) {  // C(t + dt) = C(t)·(Rz(ω·dt), (v_x, v_y)·dt), midpoint
      Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
      step.linear() =
          Eigen::AngleAxisd(pose.yaw_rate_rps * dt, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      step.translation() =
          Eigen::AngleAxisd(0.5 * pose.yaw_rate_rps * dt, Eigen::Vector3d::UnitZ()) *
          Eigen::Vector3d(pose.vx_mps * dt, pose.vy_mps * dt, 0.0);
      integrated = integrated * step;
    }
    const Eigen::Isometry3d E = carrier_motion(pose, tau);
    const double distance = std::hypot(pose.vx_mps, pose.vy_mps) * std::abs(tau);
    // The arc's length L against its chord's, L·sin(h)/h with h = ω·τ/2: L·(ω·τ)²/24 to first
    // order.
    const double half = 0.5 * pose.yaw_rate_rps * tau;
    const double chord = half == 0.0 ? 0.0 : distance * (1.0 - std::sin(half) / half);
    EXPECT_NEAR((E.translation() - integrated.translation()).norm(), chord, 1e-9) << tau;
    EXPECT_LT((E.linear() - integrated.linear()).norm(), 1e-12) << tau;
  }
}

// With a yaw acceleration α the heading is θ(τ) = ω·τ + α·τ²/2, exactly, and the carrier moves
// along its mean heading θ̄ = ω·τ/2 + α·τ²/6: integrated in small steps, it lands within the
// spread of the heading about that mean, L·(θ(τ))²/8 (second order). Taken along ω·τ/2 + α·τ²/4
// instead (the half turn), it would miss by L·α·τ²/12, 13 times that bound at τ = −0.1 s.
TEST(Calibration, TheCarriersMotionFollowsATurnThatSpeedsUp) {
  ScanPose pose;
  pose.vx_mps = 1.1;
  pose.vy_mps = -0.2;
  pose.yaw_rate_rps = 0.0;
  pose.yaw_acceleration_rps2 = 20.0;
  for (const double tau : {-0.1, -0.037}) {
    Eigen::Isometry3d integrated = Eigen::Isometry3d::Identity();
    constexpr int kSteps = 20000;
    const double dt = tau / kSteps;
    for (int i = 0; i < kSteps; ++i) {  // the turn rate at the step's middle, ω + α·t
      const double rate = pose.yaw_rate_rps + pose.yaw_acceleration_rps2 * (i + 0.5) * dt;
      Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
      step.linear() = Eigen::AngleAxisd(rate * dt, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      step.translation() = Eigen::AngleAxisd(0.5 * rate * dt, Eigen::Vector3d::UnitZ()) *
                           Eigen::Vector3d(pose.vx_mps * dt, pose.vy_mps * dt, 0.0);
      integrated = integrated * step;
    }
    const Eigen::Isometry3d E = carrier_motion(pose, tau);
    const double turn = pose.yaw_acceleration_rps2 * tau * tau / 2.0;
    EXPECT_LT((E.linear() - integrated.linear()).norm(), 1e-9) << tau;
    EXPECT_NEAR(std::atan2(E.linear()(1, 0), E.linear()(0, 0)), turn, 1e-12) << tau;
    const double distance = std::hypot(pose.vx_mps, pose.vy_mps) * std::abs(tau);
    EXPECT_LT((E.translation() - integrated.translation()).norm(), distance * turn * turn / 8.0)
        << tau;
  }
}

// The start of the fit: the velocity that carries the pose of the scan before to the scan's
// (E(−I) = C_target⁻¹·C_previous on their planar parts, roll and pitch aside); a jump between
// them (a relocalization) starts the carrier at rest.
TEST(Calibration, TheStartingVelocityCarriesThePreviousPoseToTheScans) {
  const Eigen::Isometry3d tilt(Eigen::AngleAxisd(4.0 * kDeg, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(-2.0 * kDeg, Eigen::Vector3d::UnitX()));
  const Eigen::Isometry3d previous = localizer::make_pose(1.0, 2.0, 1.1, 179.0 * kDeg) * tilt;
  const Eigen::Isometry3d target = localizer::make_pose(0.93, 2.04, 1.1, -177.5 * kDeg) * tilt;
  constexpr double kInterval = 0.1;
  const ScanPose pose = scan_pose_between(previous, target, kInterval, 0.2);
  EXPECT_NEAR(pose.yaw_rate_rps, 3.5 * kDeg / kInterval, 1e-9);  // across ±180°
  EXPECT_DOUBLE_EQ(pose.x_m, 0.93);
  EXPECT_DOUBLE_EQ(pose.floor_z_m, 0.2);
  const Eigen::Isometry3d planar_previous = localizer::make_pose(1.0, 2.0, 0.2, 179.0 * kDeg);
  const Eigen::Isometry3d planar_target = localizer::make_pose(0.93, 2.04, 0.2, -177.5 * kDeg);
  const Eigen::Isometry3d expected = planar_target.inverse() * planar_previous;
  const Eigen::Isometry3d E = carrier_motion(pose, -kInterval);
  EXPECT_LT((E.translation() - expected.translation()).norm(), 1e-12);
  EXPECT_LT((E.linear() - expected.linear()).norm(), 1e-12);

  const ScanPose jumped =
      scan_pose_between(localizer::make_pose(4.0, 2.0, 1.1, 0.0), target, kInterval, 0.2);
  EXPECT_EQ(jumped.vx_mps, 0.0);
  EXPECT_EQ(jumped.vy_mps, 0.0);
  EXPECT_EQ(jumped.yaw_rate_rps, 0.0);
  EXPECT_NEAR(jumped.yaw_rad, -177.5 * kDeg, 1e-12);
}

TEST(Calibration, RecoversExactCorrectionsMountingAndPosesInABoxRoom) {
  Scene scene;
  scene.map = test::make_box_room();
  set_truth(scene);
  const CalibrationResult result = solve(scene, fire(scene));
  expect_exact(scene, result);
  // Every laser sees walls in four directions: elevation, azimuth and range offsets are
  // observable everywhere; lasers that reach neither floor nor ceiling cannot measure Δo.
  int without_vertical = 0;
  for (const auto& e : result.lasers) {
    EXPECT_TRUE(e.observability.observable[0] && e.observability.observable[2] &&
                e.observability.observable[3])
        << e.observability.missing;
    if (!e.observability.observable[1]) {
      ++without_vertical;
      EXPECT_NE(e.observability.missing.find("vertical offset"), std::string::npos);
    }
  }
  EXPECT_GT(without_vertical, 0);  // ±1° at 1.2 m in a 3 m room
  EXPECT_TRUE(result.lasers[0].observability.all());
  const TruthErrors errors =
      compare_to_truth(result, scene.decode, corrected(scene.decode, scene.truth));
  EXPECT_LT(errors.elevation_rms_rad, kExact);
  EXPECT_LT(errors.range_offset_rms_m, kExact);
  EXPECT_EQ(errors.compared[1] + errors.unobservable[1], 16);
}

TEST(Calibration, RangeNoiseAlongTheRayLeavesNoBias) {
  // Every return recorded twice, its range 3 cm long and 3 cm short. The residual along the ray
  // is ±3 cm with a Jacobian that does not see the range, and both twins weigh alike (q of the
  // incidence cosine, from the ray's direction), so they cancel exactly at the truth. Fitted to
  // the point-to-plane residual, whose Jacobian grows with the measured range, they would not:
  // E[Jᵀe] ∝ σ², every elevation ~0.03° too wide here (calibration_model.hpp).
  // The room without its pillar: where the pillar stands on the floor, the floor polygon has no
  // edge, and which of a twin pair lands nearer the pillar than the floor is the noise's choice
  // (plane_association.hpp: left to the margin only at a polygon's own edges).
  Scene scene;
  scene.map = test::make_box_room();
  scene.map.polygons.resize(6);
  scene.map.cells[0].polygons.resize(6);
  set_truth(scene);
  std::vector<Return> twins;
  for (const Return& ret : fire(scene)) {
    for (const double noise : {-0.03, 0.03}) {
      Return twin = ret;
      twin.range_m += noise;
      twins.push_back(twin);
    }
  }
  const CalibrationResult result = solve(scene, twins);
  constexpr double kTight = 1e-7;  // the cost is σ²-sized: converged to its relative tolerance
  for (int k = 0; k < 16; ++k) {
    const auto& e = result.lasers[k];
    EXPECT_NEAR(e.correction.elevation_rad, scene.truth[k].elevation_rad, kTight) << k;
    EXPECT_NEAR(e.correction.range_m, scene.truth[k].range_m, kTight) << k;
    EXPECT_NEAR(e.correction.azimuth_rad, scene.truth[k].azimuth_rad, kTight) << k;
  }
  EXPECT_NEAR(result.mounting.height_m, scene.mounting.height_m, kTight);
  EXPECT_NEAR(result.mounting.roll_rad, scene.mounting.roll_rad, kTight);
  EXPECT_NEAR(result.mounting.pitch_rad, scene.mounting.pitch_rad, kTight);
  // The fitted residual q·(r − r̂), q ≤ 1 (return_noise.hpp): at most the 3 cm along the ray.
  EXPECT_LE(result.rms_m, 0.03 + 1e-9);
}

TEST(Calibration, SigmasCountResidualsBeyondHubersKAsCarryingNoCurvature) {
  // Each return twice, ±a·k along the ray (a = 0.5), and again ±b·k (b = 1.5): the fit stays at
  // the truth (the twins cancel) and the returns beyond Huber's k weigh only through ψ = ±k.
  // The M-estimator's covariance is (Σψ'·JJᵀ)⁻¹·(Σψ²·JJᵀ)·(Σψ'·JJᵀ)⁻¹, with ψ' = 0 beyond k:
  // per ray 2·(a² + 1)·k²/2² = 0.625 k²·(JJᵀ)⁻¹, against 2·a²·k²/2² = 0.125 k²·(JJᵀ)⁻¹ with the
  // inner twins alone: every σ √5 times theirs. The fit's weights k/|e| in place of ψ' (and
  // Σψ·e for Σψ²) make it √(0.2625/0.125) = 1.45 times.
  Scene scene;
  scene.map = test::make_box_room();
  scene.map.polygons.resize(6);  // without the pillar (RangeNoiseAlongTheRayLeavesNoBias)
  scene.map.cells[0].polygons.resize(6);
  set_truth(scene);
  const CalibrationConfig config = exact_map();
  std::vector<Return> inner, both;
  for (const Return& ret : fire(scene)) {
    for (const double a : {-0.5, 0.5, -1.5, 1.5}) {
      Return twin = ret;
      twin.range_m += a * config.huber_m;
      both.push_back(twin);
      if (std::abs(a) < 1.0) inner.push_back(twin);
    }
  }
  const CalibrationResult near = solve(scene, inner, config);
  const CalibrationResult wide = solve(scene, both, config);
  const double expected = std::sqrt(5.0);
  for (int k = 0; k < 16; ++k) {
    for (int i : {0, 3}) {  // elevation and range offset: observed by every laser here
      ASSERT_GT(near.lasers[k].sigma[i], 0.0) << k;
      EXPECT_NEAR(wide.lasers[k].sigma[i] / near.lasers[k].sigma[i], expected, 0.01 * expected)
          << "laser " << k << " correction " << i;
    }
  }
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(wide.mounting_sigma[i] / near.mounting_sigma[i], expected, 0.01 * expected) << i;
  // The weights took every twin as range noise (q = 1 at every incidence): the ratio is the ψ's.
  EXPECT_EQ(wide.noise.surface_sigma_m, 0.0);
}

TEST(Calibration, TheReturnsNoiseIsReadOffTheirResiduals) {
  // Gaussian range noise of 2 cm on an exact map: the solver weighs the returns by range noise
  // (return_noise.hpp), not by the incidence cosine as if the surfaces were off.
  Scene scene;
  scene.map = test::make_box_room();
  set_truth(scene);
  const CalibrationResult result = solve(scene, with_range_noise(fire(scene), 0.02, 7));
  EXPECT_NEAR(result.noise.range_sigma_m, 0.02, 0.002);  // 10%: 10 bins of ~1,300 returns
  EXPECT_LT(result.noise.surface_sigma_m, 0.004);
  EXPECT_GT(result.noise.residual_scale(0.3), 0.9);
}

TEST(Calibration, SigmasWidenWhereTheReturnsOfAScanLineShareAnError) {
  // Each scan line (a laser in a scan) carries one range error of 1 cm, on top of 2 mm of white
  // noise. The model's σ²·H⁻¹ counts every return as independent (a range offset's σ ~0.3 mm);
  // the sandwich over scan lines (calibration_solver.hpp) sees the lines' spread. With 5 scans
  // the fit has more parameters (102) than scan lines (80) and its residuals keep only part of the
  // lines' errors, so the sandwich widens the sigmas 3–9 times and still falls short (measured:
  // range offsets off by 28.6 model σ RMS, 4.4 reported σ; white noise alone: the two agree).
  Scene scene;
  scene.map = test::make_box_room();
  set_truth(scene);
  std::mt19937 rng(11);
  std::normal_distribution<double> line_error(0.0, 0.01), white(0.0, 0.002);
  std::map<std::pair<int, int>, double> error_of_line;
  std::vector<Return> returns = fire(scene);
  for (Return& ret : returns) {
    const auto line = std::make_pair(ret.laser, ret.scan);
    if (!error_of_line.count(line)) error_of_line[line] = line_error(rng);
    ret.range_m += error_of_line[line] + white(rng);
  }
  const CalibrationResult result = solve(scene, returns);
  double z_model = 0.0, z = 0.0;
  for (int k = 0; k < 16; ++k) {
    const double error = result.lasers[k].correction.range_m - scene.truth[k].range_m;
    z_model += std::pow(error / result.lasers[k].model_sigma[3], 2) / 16.0;
    z += std::pow(error / result.lasers[k].sigma[3], 2) / 16.0;
    EXPECT_GT(result.lasers[k].sigma[3], 2.5 * result.lasers[k].model_sigma[3]) << k;
  }
  EXPECT_GT(std::sqrt(z_model), 10.0);  // the model's sigmas miss the shared errors
  EXPECT_LT(std::sqrt(z), std::sqrt(z_model) / 3.0);
}

TEST(Calibration, TheSameFitForAnyThreadCount) {
  // Noisy returns and adjusted planes, so every sum carries rounding: the blocks are summed
  // alone and added in order, so 1, 2 and 5 threads give the same bits.
  Scene scene;
  scene.map = test::make_box_room();
  set_truth(scene);
  const std::vector<Return> returns = with_range_noise(fire(scene), 0.01, 3);
  CalibrationConfig config;
  config.threads = 1;
  const CalibrationResult one = solve(scene, returns, config);
  for (const int threads : {2, 5}) {
    config.threads = threads;
    const CalibrationResult many = solve(scene, returns, config);
    EXPECT_EQ(many.iterations, one.iterations) << threads;
    EXPECT_EQ(many.sigma_m, one.sigma_m) << threads;
    EXPECT_EQ(many.noise.range_sigma_m, one.noise.range_sigma_m) << threads;
    EXPECT_EQ(many.noise.surface_sigma_m, one.noise.surface_sigma_m) << threads;
    EXPECT_EQ(many.mounting.height_m, one.mounting.height_m) << threads;
    EXPECT_EQ(many.mounting_sigma[0], one.mounting_sigma[0]) << threads;
    for (int k = 0; k < 16; ++k) {
      EXPECT_EQ(many.lasers[k].correction.elevation_rad, one.lasers[k].correction.elevation_rad);
      EXPECT_EQ(many.lasers[k].correction.range_m, one.lasers[k].correction.range_m);
      EXPECT_EQ(many.lasers[k].sigma[0], one.lasers[k].sigma[0]);
      EXPECT_EQ(many.lasers[k].model_sigma[0], one.lasers[k].model_sigma[0]);
    }
    ASSERT_EQ(many.planes.size(), one.planes.size());
    for (std::size_t j = 0; j < one.planes.size(); ++j)
      EXPECT_EQ(many.planes[j].correction.offset_m, one.planes[j].correction.offset_m);
  }
}

TEST(Calibration, AdjustedPlanesKeepMisplacedWallsOutOfTheLasers) {
  // The rays meet walls 2 cm off and out of plumb (the simulator's map error); the solver is
  // given the model's walls. Held fixed, the walls' errors go into the lasers; adjusted under
  // their prior, they stay with the walls (elevations 0.47° -> 0.018° RMS, range offsets 8.4 ->
  // 0.45 mm when written).
  Scene scene;
  scene.map = test::make_box_room();
  set_truth(scene);
  Scene built = scene;
  std::mt19937_64 rng(3);
  built.map.polygons = sim::perturb_walls(scene.map.polygons, 0.02, rng);
  const std::vector<Return> returns = fire(built);
  const sensor::LaserCalibration truth = corrected(scene.decode, scene.truth);
  const TruthErrors fixed = compare_to_truth(solve(scene, returns), scene.decode, truth);
  const CalibrationResult adjusted = solve(scene, returns, CalibrationConfig{});
  const TruthErrors errors = compare_to_truth(adjusted, scene.decode, truth);
  EXPECT_GT(fixed.elevation_rms_rad, 0.02 * kDeg);  // the case it is meant to be
  EXPECT_LT(errors.elevation_rms_rad, 0.25 * fixed.elevation_rms_rad);
  EXPECT_LT(errors.range_offset_rms_m, 0.25 * fixed.range_offset_rms_m);
  // Every wall the rays meet is adjusted. (Where each stands is known only up to the map's common
  // shift, which the prior holds: no per-wall offset is asserted.)
  int walls = 0;
  for (const PlaneEstimate& plane : adjusted.planes) {
    if (scene.map.polygons[plane.polygon].kind != maps::SurfaceKind::Wall) continue;
    ++walls;
    EXPECT_GT(plane.returns, 0) << plane.polygon;
  }
  // The room's four walls and three of the pillar's sides: its side at y = 1 faces away from
  // every scan (all stand at y > 1.5), so no ray meets it.
  EXPECT_EQ(walls, 7);
}

// The room's floor outlined with 99 more vertices along one edge: its frame (from the
// vertices' mean) and its area centroid (from which the slopes count) lie metres apart, as in
// a surveyed map's L-shaped or densely outlined floors.
void outline_floor_densely(maps::PlaneMap& map, double rise_m) {
  for (maps::PlanarPolygon& polygon : map.polygons) {
    // The room's floor, not the pillar's top (a floor too, at 3 m).
    if (polygon.kind != maps::SurfaceKind::Floor || polygon.centroid.z() > 1.0) continue;
    maps::Ring3 ring;
    for (std::size_t i = 0; i < polygon.outer.size(); ++i) {
      ring.push_back(polygon.outer[i]);
      if (i != 0) continue;
      const Eigen::Vector3d& from = polygon.outer[0];
      const Eigen::Vector3d& to = polygon.outer[1];
      for (int k = 1; k < 100; ++k) ring.push_back(from + (to - from) * (k / 100.0));
    }
    for (Eigen::Vector3d& p : ring) p.z() += rise_m;
    maps::PlanarPolygon outlined;
    ASSERT_TRUE(maps::make_planar_polygon(ring, {}, outlined));
    outlined.cell = polygon.cell;
    outlined.storey = polygon.storey;
    polygon = outlined;
  }
}

TEST(Calibration, TheHeightIsMeasuredFromTheFloorAsFitted) {
  // The real floor stands 4.5 cm above the model's, the ceiling where the model puts it. The
  // floor and the sensor moving together fit the returns alike, held by the planes' priors
  // alone, so the model's h (above the map's floor) lands between; the floor's returns fix the
  // height above the floor they measure, 4.5 cm less than above the map's: to 10 µm, as the
  // priors weigh against noise-free returns as if they had 1 mm of noise (kMinResidualSigmaM).
  Scene scene;
  scene.map = test::make_box_room();
  outline_floor_densely(scene.map, 0.0);
  for (const maps::PlanarPolygon& polygon : scene.map.polygons) {
    if (polygon.kind == maps::SurfaceKind::Floor && polygon.centroid.z() < 1.0) {  // its case
      ASSERT_GT((polygon.frame.origin - polygon.centroid).norm(), 1.0);
    }
  }
  set_truth(scene);
  Scene built = scene;
  built.map = test::make_box_room();
  constexpr double kRise = 0.045;
  outline_floor_densely(built.map, kRise);
  const CalibrationResult result = solve(scene, fire(built), CalibrationConfig{});
  const FloorHeight& floor = result.height_above_floor;
  EXPECT_EQ(floor.scans, static_cast<int>(scene.poses.size()));
  EXPECT_NEAR(floor.height_m, scene.mounting.height_m - kRise, 1e-5);
  EXPECT_GT(std::abs(result.mounting.height_m - floor.height_m), 0.005);  // h is not it
  EXPECT_GT(floor.sigma_m, 0.0);
  EXPECT_LT(floor.sigma_m, result.mounting_sigma[0]);
}

TEST(Calibration, AnObjectByAWallStaysOutOfTheLasers) {
  // The rays also meet a cupboard the map lacks: 2 m wide, 1 m high, its face 5 cm before the
  // wall at y = 6, within every gate of it. Kept, its returns pull the down-looking lasers that
  // see it; left out as a run standing off the wall (unmapped_objects.hpp), the fit is that of
  // the room without the cupboard, up to what leaving ~400 returns out moves within the sigmas.
  // Range noise 1 cm, so the run is 5σ off while each return alone is within the Huber width.
  // (Measured: elevations 0.145° RMS off kept, 0.069° left out, 0.056° without the cupboard;
  // per laser, kept 4.5–6σ off the room's fit on the nine lasers that see the cupboard, left out
  // within 1.32σ; 394 returns left out, 390 on the cupboard. Weighed by the cosine alone, as
  // before return_noise.hpp: 0.261°, 0.085°, 0.087°, within 1.31σ.)
  Scene scene;
  scene.map = test::make_box_room();
  set_truth(scene);
  Scene built = scene;
  test::add_box(built.map, 0, {2.0, 5.95, 0.0}, {4.0, 6.0, 1.0}, false);
  std::vector<Return> returns = fire(built);
  std::vector<Return> room_only = fire(scene);
  ASSERT_EQ(returns.size(), room_only.size());  // the cupboard only shortens rays on the wall
  std::mt19937_64 rng(4);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::size_t on_cupboard = 0;
  for (std::size_t i = 0; i < returns.size(); ++i) {
    on_cupboard += returns[i].range_m < room_only[i].range_m - 1e-9;
    const double e = noise(rng);
    returns[i].range_m += e;
    room_only[i].range_m += e;
  }
  const sensor::LaserCalibration truth = corrected(scene.decode, scene.truth);
  CalibrationConfig keep = exact_map();
  keep.unmapped_objects.median_sigmas = 0.0;
  const CalibrationResult kept = solve(scene, returns, keep);
  const CalibrationResult left_out = solve(scene, returns);
  const TruthErrors with_cupboard = compare_to_truth(kept, scene.decode, truth);
  const TruthErrors without = compare_to_truth(left_out, scene.decode, truth);
  const CalibrationResult room_fit = solve(scene, room_only);
  const TruthErrors room = compare_to_truth(room_fit, scene.decode, truth);
  EXPECT_GT(with_cupboard.elevation_rms_rad, 2.0 * room.elevation_rms_rad);  // the case it is for
  int pulled = 0;
  for (int k = 0; k < 16; ++k) {
    const double sigma = room_fit.lasers[k].model_sigma[0];  // white noise: the model's
    const double room_k = room_fit.lasers[k].correction.elevation_rad;
    pulled += std::abs(kept.lasers[k].correction.elevation_rad - room_k) > 4.0 * sigma;
    EXPECT_LT(std::abs(left_out.lasers[k].correction.elevation_rad - room_k), 1.5 * sigma) << k;
  }
  EXPECT_GE(pulled, 8);
  EXPECT_LT(without.range_offset_rms_m, 0.5 * with_cupboard.range_offset_rms_m);
  EXPECT_EQ(kept.unmapped_returns, 0u);
  // The room alone, white noise on exact planes: about one in 10⁴ by chance (measured 0 of 13,769).
  EXPECT_LE(room_fit.unmapped_returns, 5u);
  // About the cupboard's returns: less its edges, plus the wall's beside them where the cupboard
  // holds most of a window (unmapped_objects.hpp).
  EXPECT_GT(left_out.unmapped_returns, on_cupboard * 8 / 10);
  EXPECT_LT(left_out.unmapped_returns, on_cupboard * 12 / 10);
}

TEST(Calibration, HorizontalLaserDegenerateConicIsSolvedWhenTiltedAndFlaggedWhenLevel) {
  Scene scene;
  scene.map = test::make_box_room();
  set_truth(scene);
  scene.decode.lasers[1].elevation_rad = 0.0;  // the cone of laser 1 is a plane
  // Tilted (the scene's 2° roll): its scan line goes up and down the walls.
  const CalibrationResult tilted = solve(scene, fire(scene));
  expect_exact(scene, tilted);
  EXPECT_TRUE(tilted.lasers[1].observability.observable[0]);

  // Level, its points move with the elevation only as cos φ: flat at 0°, no information. (Level,
  // every laser also meets the floor at one range: no vertical offset is observable.)
  scene.mounting = {1.2, 0.0, 0.0};
  scene.truth[1].elevation_rad = 0.0;
  scene.truth[0].vertical_offset_m = scene.truth[2].vertical_offset_m = 0.0;
  const CalibrationResult level = solve(scene, fire(scene));
  EXPECT_FALSE(level.lasers[1].observability.observable[0]);
  EXPECT_FALSE(level.lasers[1].observability.observable[1]);
  EXPECT_NE(level.lasers[1].observability.missing.find("elevation"), std::string::npos);
  EXPECT_FALSE(level.lasers[0].observability.observable[1]);
  EXPECT_NE(level.lasers[0].observability.missing.find("one range"), std::string::npos)
      << level.lasers[0].observability.missing;
  expect_exact(scene, level);
}

TEST(Calibration, PlaneThroughTheSensorOriginDoesNotDisturbTheFit) {
  Scene scene;
  scene.map = test::make_box_room();
  // A shelf at exactly the sensor's height, around the first scan pose: the sensor origin lies
  // in its plane and every cone meets it at its apex (a degenerate section); most lasers are
  // blocked by it within centimetres (their apexes are mm above or below it), only some rays
  // of the tilted sensor get past.
  test::add_quad(scene.map, 0, {1.0, 1.0, 1.2}, {4.0, 1.0, 1.2}, {4.0, 3.0, 1.2}, {1.0, 3.0, 1.2});
  set_truth(scene);
  const auto returns = fire(scene);
  const auto first_scan =
      std::count_if(returns.begin(), returns.end(), [](const Return& r) { return r.scan == 0; });
  EXPECT_LT(first_scan, 16 * 180 / 10);
  EXPECT_GT(first_scan, 0);
  expect_exact(scene, solve(scene, returns));
}

TEST(Calibration, NearParallelPlanesAreFlaggedNotEstimated) {
  // A corridor of two walls 3° apart and nothing else: every laser sees only (near-)parallel
  // planes.
  Scene scene;
  scene.map.storeys.push_back({"ground", 0.0, 3.0});
  scene.map.cells.emplace_back();
  const double slope = std::tan(3.0 * kDeg);
  // Each faces into the corridor (the right-hand rule's normal): a ray meets a one-sided wall
  // only from the side it faces.
  test::add_quad(scene.map, 0, {-30, -1.5, 8}, {30, -1.5, 8}, {30, -1.5, -5}, {-30, -1.5, -5});
  test::add_quad(scene.map, 0, {30, 1.5 + 30 * slope, 8}, {-30, 1.5 - 30 * slope, 8},
                 {-30, 1.5 - 30 * slope, -5}, {30, 1.5 + 30 * slope, -5});
  scene.poses = {{0.0, 0.0, 0.1, 0.0}, {1.0, 0.2, -0.1, 0.0}, {2.0, -0.2, 0.05, 0.0}};
  set_truth(scene);
  const CalibrationResult result = solve(scene, fire(scene));
  for (const auto& e : result.lasers) {
    EXPECT_FALSE(e.observability.all());
    EXPECT_NE(e.observability.missing.find("parallel"), std::string::npos)
        << e.observability.missing;
    // Held at the decode calibration, not moved to whatever fits.
    EXPECT_EQ(e.correction.elevation_rad, 0.0);
    EXPECT_EQ(e.correction.range_m, 0.0);
    EXPECT_EQ(e.sigma[0], 0.0);
  }
}

TEST(Calibration, TooFewPlanesAndBadInputs) {
  LaserView one_plane;
  one_plane.normals_sensor = {Eigen::Vector3d::UnitX()};
  one_plane.planes_seen = 1;
  one_plane.returns = 500;
  const LaserObservability flagged = laser_observability(one_plane, {});
  EXPECT_FALSE(flagged.observable[0] || flagged.observable[1] || flagged.observable[2] ||
               flagged.observable[3]);
  EXPECT_NE(flagged.missing.find("1 plane"), std::string::npos) << flagged.missing;

  Scene scene;
  scene.map = test::make_box_room();
  std::vector<Return> bad(1);
  bad[0].laser = 16;
  EXPECT_THROW(calibrate(scene.map, scene.decode, bad, scene.mounting, scene.poses, {}),
               std::invalid_argument);
  std::vector<Return> far(1);
  far[0].range_m = 500.0;  // on no plane
  EXPECT_THROW(calibrate(scene.map, scene.decode, far, scene.mounting, scene.poses, {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace conicloc::calib
