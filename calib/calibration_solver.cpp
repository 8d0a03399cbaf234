#include "calib/calibration_solver.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "calib/huber.hpp"
#include "calib/levenberg_marquardt.hpp"
#include "calib/plane_association.hpp"
#include "calib/return_noise.hpp"
#include "calib/unmapped_objects.hpp"
#include "maps/plane_index.hpp"
#include "parallel/parallel_for.hpp"

namespace conicloc::calib {
namespace {

constexpr int kLocal = kRayParameters;
using Local = Eigen::Matrix<double, kLocal, 1>;

struct State {
  std::vector<LaserCorrection> lasers;
  Mounting mounting;
  std::vector<ScanPose> poses;
  std::vector<PlaneCorrection> planes;  ///< per adjusted polygon (Problem::polygon_of_slot)
};

// State-vector layout: lasers, then the mounting, then the scans, then the adjusted planes.
struct Layout {
  int lasers = 0;
  int scans = 0;
  int planes = 0;
  int laser(int k) const { return kLaserParameters * k; }
  int mount() const { return kLaserParameters * lasers; }
  int scan(int s) const { return mount() + kMountParameters + kScanParameters * s; }
  int plane(int j) const { return scan(scans) + kPlaneParameters * j; }
  int size() const { return plane(planes); }
};

// A tilt's prior is the offset's spread over the surface's extent (the edge moves by about σ),
// the extent floored so a sliver of a polygon does not get an unbounded tilt.
constexpr double kMinTiltExtentM = 0.5;
constexpr double kMinResidualSigmaM = 1e-3;

// The returns' sums run over this many fixed blocks, each summed alone and the blocks added in
// order: threads change who sums a block, never the order of the additions.
constexpr std::size_t kBlocks = 16;

// Calls body(begin, end, block) for blocks [first_block, last_block) of the kBlocks blocks of
// [0, count), on `threads`.
template <class Body>
void for_blocks(std::size_t count, int threads, const Body& body, std::size_t first_block = 0,
                std::size_t last_block = kBlocks) {
  conicloc::parallel_for(last_block - first_block, threads,
                         [&](std::size_t first, std::size_t last, int) {
                           for (std::size_t b = first_block + first; b < first_block + last; ++b)
                             body(count * b / kBlocks, count * (b + 1) / kBlocks, b);
                         });
}

Local gather(const State& x, const Return& ret) {
  const LaserCorrection& c = x.lasers[ret.laser];
  const ScanPose& p = x.poses[ret.scan];
  Local v;
  v << c.elevation_rad, c.vertical_offset_m, c.azimuth_rad, c.range_m, x.mounting.height_m,
      x.mounting.roll_rad, x.mounting.pitch_rad, p.x_m, p.y_m, p.yaw_rad, p.vx_mps, p.vy_mps,
      p.yaw_rate_rps, p.yaw_acceleration_rps2;
  return v;
}

std::array<int, kLocal> indices(const Layout& layout, const Return& ret) {
  std::array<int, kLocal> index{};
  for (int i = 0; i < kLaserParameters; ++i) index[i] = layout.laser(ret.laser) + i;
  for (int i = 0; i < kMountParameters; ++i) index[kLaserParameters + i] = layout.mount() + i;
  for (int i = 0; i < kScanParameters; ++i) {
    index[kLaserParameters + kMountParameters + i] = layout.scan(ret.scan) + i;
  }
  return index;
}

// A return's ray in the map: where its laser fires from and where the return lands.
struct RayPoint {
  Eigen::Vector3d origin;
  Eigen::Vector3d point;
};

RayPoint local_ray(const sensor::Laser& laser, const Local& v, double floor_z, const Return& ret) {
  const LaserCorrection c{v(0), v(1), v(2), v(3)};
  const Mounting m{v(4), v(5), v(6)};
  const ScanPose p{v(7), v(8), v(9), floor_z, v(10), v(11), v(12), v(13)};
  const Eigen::Isometry3d T = map_from_fire(m, p, ret.time_s);
  return {T * laser_origin(laser, c), T * sensor_point(laser, c, ret.azimuth_rad, ret.range_m)};
}

void add(State& x, const Eigen::VectorXd& delta, const Layout& layout) {
  for (int k = 0; k < layout.lasers; ++k) {
    auto& c = x.lasers[k];
    c.elevation_rad += delta(layout.laser(k));
    c.vertical_offset_m += delta(layout.laser(k) + 1);
    c.azimuth_rad += delta(layout.laser(k) + 2);
    c.range_m += delta(layout.laser(k) + 3);
  }
  x.mounting.height_m += delta(layout.mount());
  x.mounting.roll_rad += delta(layout.mount() + 1);
  x.mounting.pitch_rad += delta(layout.mount() + 2);
  for (int s = 0; s < layout.scans; ++s) {
    x.poses[s].x_m += delta(layout.scan(s));
    x.poses[s].y_m += delta(layout.scan(s) + 1);
    x.poses[s].yaw_rad += delta(layout.scan(s) + 2);
    x.poses[s].vx_mps += delta(layout.scan(s) + 3);
    x.poses[s].vy_mps += delta(layout.scan(s) + 4);
    x.poses[s].yaw_rate_rps += delta(layout.scan(s) + 5);
    x.poses[s].yaw_acceleration_rps2 += delta(layout.scan(s) + 6);
  }
  for (int j = 0; j < layout.planes; ++j) {
    x.planes[j].offset_m += delta(layout.plane(j));
    x.planes[j].slope_u += delta(layout.plane(j) + 1);
    x.planes[j].slope_v += delta(layout.plane(j) + 2);
  }
}

// The gauge: stiff pseudo-residuals mean Δo = 0 and mean Δψ = 0 over the lasers where each is
// free. Each row of `gauge` is one pseudo-residual's gradient a (residual aᵀx).
// The planes' corrections have a Gaussian prior, N(0, σ²) per entry (`prior_sigma`), weighed
// against the returns as their residual variance σ_e² allows: the MAP cost is
//   Σ ρ(e_i) + ½·Σ_j (σ_e/σ_j)²·x_j²
// in the residuals' units (ρ ≈ e²/2), so the precision added to entry j is (σ_e/σ_j)².
struct Problem {
  const maps::PlaneMap& map;
  const sensor::LaserCalibration& decode;
  const std::vector<Return>& returns;
  const Layout layout;
  double huber_m;
  std::vector<int> plane;   ///< per return: polygon index, −1 unassociated
  std::vector<bool> fixed;  ///< per state entry
  std::vector<Eigen::VectorXd> gauge;
  double gauge_weight = 0.0;
  std::vector<int> slot;             ///< per polygon: its adjusted plane, −1 held fixed
  std::vector<int> polygon_of_slot;  ///< per adjusted plane
  Eigen::VectorXd prior_sigma;       ///< per state entry: the prior's σ, 0 for no prior
  double residual_variance = 0.0;    ///< σ_e², set each round
  double edge_margin_m = 0.0;        ///< plane_association.hpp
  int threads = 1;                   ///< resolved (≥ 1)

  double prior_precision(int i) const {
    return prior_sigma(i) > 0.0 ? residual_variance / (prior_sigma(i) * prior_sigma(i)) : 0.0;
  }

  // Return i's ray in the map for the local parameters `v`.
  RayPoint ray(const State& x, std::size_t i, const Local& v) const {
    const Return& ret = returns[i];
    return local_ray(decode.lasers[ret.laser], v, x.poses[ret.scan].floor_z_m, ret);
  }

  // The correction of return i's polygon (none when the polygon is held).
  PlaneCorrection correction(const State& x, std::size_t i) const {
    const int j = slot[plane[i]];
    return j >= 0 ? x.planes[j] : PlaneCorrection{};
  }

  // The range residual of return i against its polygon, moved by that polygon's adjustment
  // (calibration_model.hpp: along the ray, where the noise is).
  double residual(const State& x, std::size_t i, const RayPoint& r) const {
    return range_residual(map.polygons[plane[i]], correction(x, i), r.origin, r.point);
  }
  // The incidence cosines c and the residuals' scales q(c) (return_noise.hpp), held through a
  // Levenberg–Marquardt step: the fit weighs q(c)·(r − r̂), (r − r̂) over its standard deviation
  // in metres at normal incidence. Re-taken at each step's start, the cost the step is judged by
  // and its gradient agree, and at convergence Σ q²·J·(r − r̂) = 0 with nothing of the noise in
  // q or J (calibration_model.hpp).
  std::vector<double> cosines;
  std::vector<double> scales;
  ReturnNoise noise;  ///< fitted each round from the second on; none (q = c) before
  void hold_cosines(const State& x) {
    cosines.assign(returns.size(), 0.0);
    for_blocks(returns.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) {
        if (plane[i] < 0) continue;
        const RayPoint r = ray(x, i, gather(x, returns[i]));
        cosines[i] = incidence_cosine(map.polygons[plane[i]], correction(x, i), r.origin, r.point);
      }
    });
    scale_residuals();
  }
  void scale_residuals() {
    scales.assign(cosines.size(), 0.0);
    for (std::size_t i = 0; i < cosines.size(); ++i)
      if (plane[i] >= 0) scales[i] = noise.residual_scale(cosines[i]);
  }

  // The range residuals r − r̂ of the associated returns at `x` (0 for the others).
  std::vector<double> range_residuals(const State& x) const {
    std::vector<double> out(returns.size(), 0.0);
    for_blocks(returns.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
        if (plane[i] >= 0) out[i] = residual(x, i, ray(x, i, gather(x, returns[i])));
    });
    return out;
  }

  // σ_r and σ_s from the residuals at `x` and the cosines held (return_noise.hpp), and the
  // scales they give.
  void fit_noise(const State& x, const ReturnNoiseConfig& config) {
    const std::vector<double> all = range_residuals(x);
    std::vector<double> residual, cosine;
    for (std::size_t i = 0; i < returns.size(); ++i) {
      if (plane[i] < 0) continue;
      residual.push_back(all[i]);
      cosine.push_back(cosines[i]);
    }
    noise = fit_return_noise(residual, cosine, config);
    scale_residuals();
  }

  Eigen::VectorXd state_vector(const State& x) const {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(layout.size());
    add_to(v, x);
    return v;
  }
  void add_to(Eigen::VectorXd& v, const State& x) const {
    for (int k = 0; k < layout.lasers; ++k) {
      v(layout.laser(k)) = x.lasers[k].elevation_rad;
      v(layout.laser(k) + 1) = x.lasers[k].vertical_offset_m;
      v(layout.laser(k) + 2) = x.lasers[k].azimuth_rad;
      v(layout.laser(k) + 3) = x.lasers[k].range_m;
    }
    for (int j = 0; j < layout.planes; ++j) {
      v(layout.plane(j)) = x.planes[j].offset_m;
      v(layout.plane(j) + 1) = x.planes[j].slope_u;
      v(layout.plane(j) + 2) = x.planes[j].slope_v;
    }
  }

  double cost(const State& x) const {
    std::array<double, kBlocks> block_total{};
    for_blocks(returns.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t b) {
      for (std::size_t i = begin; i < end; ++i) {
        if (plane[i] < 0) continue;
        block_total[b] +=
            huber_cost(scales[i] * residual(x, i, ray(x, i, gather(x, returns[i]))), huber_m);
      }
    });
    double total = 0.0;
    for (const double t : block_total) total += t;
    const Eigen::VectorXd v = state_vector(x);
    for (const auto& a : gauge) total += 0.5 * gauge_weight * std::pow(a.dot(v), 2);
    for (int i = 0; i < layout.size(); ++i) total += 0.5 * prior_precision(i) * v(i) * v(i);
    return total;
  }

  // JᵀWJ and JᵀWe over the associated returns (gauge, priors and fixed entries not yet
  // applied), summed per block of returns and the blocks added in order.
  struct Sums {
    Eigen::MatrixXd H;
    Eigen::VectorXd g;
    HuberSums residuals;
  };
  // What H weighs each return's JJᵀ by: the fit's IRLS weight w = ψ(e)/e, or the curvature
  // ψ'(e) of the cost the fit minimises (the covariance's).
  enum class HessianWeight { Fit, Curvature };
  // The blocks run `threads` at a time, each into its own buffer, and are added in block order:
  // the memory is threads·n², not kBlocks·n² (n ~ 1,300 for 60 scans and 300 planes: 14 MB each).
  void normal_equations(const State& x, Eigen::MatrixXd& H, Eigen::VectorXd& g, double& weighted_sq,
                        double& sq, std::size_t& count) const {
    Sums total = normal_sums(x, HessianWeight::Fit);
    H = std::move(total.H);
    g = std::move(total.g);
    weighted_sq = total.residuals.weighted_sq;
    sq = total.residuals.sq;
    count = total.residuals.count;
  }
  Sums normal_sums(const State& x, HessianWeight weight) const {
    Sums total;
    total.H.setZero(layout.size(), layout.size());
    total.g.setZero(layout.size());
    const std::size_t wave = std::min<std::size_t>(kBlocks, static_cast<std::size_t>(threads));
    std::vector<Sums> buffers(wave);
    for (std::size_t first = 0; first < kBlocks; first += wave) {
      const std::size_t blocks = std::min(wave, kBlocks - first);
      for_blocks(
          returns.size(), threads,
          [&](std::size_t begin, std::size_t end, std::size_t block) {
            add_returns(x, begin, end, weight, buffers[block - first]);
          },
          first, first + blocks);
      for (std::size_t b = 0; b < blocks; ++b) {
        const Sums& block = buffers[b];
        if (block.residuals.count == 0) continue;
        total.H += block.H;
        total.g += block.g;
        total.residuals += block.residuals;
      }
    }
    return total;
  }

  // One associated return's row: its weighted residual e = q·(r − r̂), the range residual, and
  // de/dx over the state entries `index` (the first n).
  static constexpr int kWithPlane = kLocal + kPlaneParameters;
  struct Row {
    Eigen::Matrix<double, kWithPlane, 1> J = Eigen::Matrix<double, kWithPlane, 1>::Zero();
    std::array<int, kWithPlane> index{};
    int n = kLocal;
    double e = 0.0;
    double range_e = 0.0;
  };
  Row row(const State& x, std::size_t i) const {
    Row out;
    const Return& ret = returns[i];
    const Local v = gather(x, ret);
    const RayPoint r = ray(x, i, v);
    out.range_e = residual(x, i, r);
    const double q = scales[i];  // q(c), held: a weight, not differentiated
    out.e = q * out.range_e;
    // The laser, mounting and scan entries at the predicted hit (range_residual_gradient);
    // the plane's: e = q·(r − r̂) with r̂ = −D(o)/(a·d), so d e / d(δ, s_u, s_v) =
    // −q·(1, û, v̂)/(a·d) at p̂ = p − (r − r̂)·d (calibration_model.hpp), when it is adjusted.
    out.J.head<kLocal>() =
        q * range_residual_gradient(decode.lasers[ret.laser], x.lasers[ret.laser], x.mounting,
                                    x.poses[ret.scan], ret, map.polygons[plane[i]],
                                    correction(x, i));
    const auto local = indices(layout, ret);
    std::copy(local.begin(), local.end(), out.index.begin());
    if (const int j = slot[plane[i]]; j >= 0) {
      const maps::PlanarPolygon& polygon = map.polygons[plane[i]];
      const Eigen::Vector3d d = (r.point - r.origin).normalized();
      const double scale = -q / corrected_normal(polygon, x.planes[j]).dot(d);
      const Eigen::Vector2d uv = centroid_uv(polygon, r.point - out.range_e * d);
      out.J.tail<kPlaneParameters>() << scale, scale * uv.x(), scale * uv.y();
      for (int k = 0; k < kPlaneParameters; ++k) out.index[kLocal + k] = layout.plane(j) + k;
      out.n = kWithPlane;
    }
    return out;
  }

  // The sums of returns [begin, end), into `sums` (overwritten).
  void add_returns(const State& x, std::size_t begin, std::size_t end, HessianWeight weight,
                   Sums& sums) const {
    Eigen::MatrixXd& H = sums.H;
    Eigen::VectorXd& g = sums.g;
    H.setZero(layout.size(), layout.size());
    g.setZero(layout.size());
    sums.residuals = HuberSums{};
    for (std::size_t i = begin; i < end; ++i) {
      if (plane[i] < 0) continue;
      const Row r = row(x, i);
      const double w = huber_weight(r.e, huber_m);
      const double h = weight == HessianWeight::Fit ? w : huber_curvature(r.e, huber_m);
      for (int a = 0; a < r.n; ++a) {
        g(r.index[a]) += w * r.J(a) * r.e;
        for (int b = 0; b < r.n; ++b) H(r.index[a], r.index[b]) += h * r.J(a) * r.J(b);
      }
      sums.residuals.add(r.e, huber_m);
    }
  }

  // The spread of the gradient over scan lines, Σ_lines s·sᵀ with s = Σ_line w·e·J (the
  // sandwich's middle, below): returns on one line share what the model leaves out along it.
  Eigen::MatrixXd score_spread(const State& x,
                               const std::vector<std::vector<std::size_t>>& lines) const {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(layout.size(), layout.size());
    std::map<int, double> score;
    for (const auto& line : lines) {
      score.clear();
      for (const std::size_t i : line) {
        if (plane[i] < 0) continue;
        const Row r = row(x, i);
        const double w = huber_weight(r.e, huber_m);
        for (int a = 0; a < r.n; ++a) score[r.index[a]] += w * r.e * r.J(a);
      }
      for (const auto& [a, sa] : score)
        for (const auto& [b, sb] : score) M(a, b) += sa * sb;
    }
    return M;
  }

  // Adds the gauge rows and the priors, and pins the fixed entries (and any entry the returns
  // inform only to rounding, e.g. the height when no laser sees a floor or ceiling).
  void constrain(const State& x, Eigen::MatrixXd& H, Eigen::VectorXd& g) const {
    const double negligible = 1e-14 * H.diagonal().maxCoeff();
    const Eigen::VectorXd v = state_vector(x);
    for (const auto& a : gauge) {
      H += gauge_weight * a * a.transpose();
      g += gauge_weight * a * a.dot(v);
    }
    for (int i = 0; i < layout.size(); ++i) {
      H(i, i) += prior_precision(i);
      g(i) += prior_precision(i) * v(i);
    }
    for (int i = 0; i < layout.size(); ++i) {
      if (!fixed[i] && H(i, i) > negligible) continue;
      H.row(i).setZero();
      H.col(i).setZero();
      H(i, i) = 1.0;
      g(i) = 0.0;
    }
  }
};

void associate(Problem& problem, const State& x, const maps::PlaneIndex& index, double gate_m) {
  for_blocks(problem.returns.size(), problem.threads,
             [&](std::size_t begin, std::size_t end, std::size_t) {
               for (std::size_t i = begin; i < end; ++i) {
                 const RayPoint r = problem.ray(x, i, gather(x, problem.returns[i]));
                 problem.plane[i] = associated_polygon(problem.map, index, r.origin, r.point,
                                                       gate_m, problem.edge_margin_m);
               }
             });
}

// What each laser saw in the first round, and which of its corrections that measures.
std::vector<LaserView> laser_views(const Problem& problem, const State& x, const Eigen::MatrixXd& H,
                                   const ObservabilityConfig& config) {
  const int lasers = problem.layout.lasers;
  std::vector<std::map<int, int>> counts(lasers);
  std::vector<std::map<int, Eigen::Vector3d>> normals(lasers);
  std::vector<Eigen::Vector3d> floor_ranges(lasers, Eigen::Vector3d::Zero());  // n, Σr, Σr²
  for (std::size_t i = 0; i < problem.returns.size(); ++i) {
    if (problem.plane[i] < 0) continue;
    const Return& ret = problem.returns[i];
    ++counts[ret.laser][problem.plane[i]];
    const Eigen::Matrix3d R_map_sensor =
        map_from_fire(x.mounting, x.poses[ret.scan], ret.time_s).linear();
    const Eigen::Vector3d n_sensor =
        R_map_sensor.transpose() * problem.map.polygons[problem.plane[i]].plane.normal;
    normals[ret.laser][problem.plane[i]] = n_sensor;
    if (std::abs(n_sensor.z()) >= config.min_normal_component) {
      floor_ranges[ret.laser] += Eigen::Vector3d(1.0, ret.range_m, ret.range_m * ret.range_m);
    }
  }
  std::vector<LaserView> views(lasers);
  for (int k = 0; k < lasers; ++k) {
    for (const auto& [polygon, count] : counts[k]) {
      views[k].returns += count;
      ++views[k].planes_seen;
      if (count >= config.min_plane_returns) {
        views[k].normals_sensor.push_back(normals[k][polygon]);
      }
    }
    const Eigen::Vector3d& f = floor_ranges[k];
    if (f(0) > 0) {
      views[k].floor_range_mean_m = f(1) / f(0);
      views[k].floor_range_sd_m = std::sqrt(
          std::max(0.0, f(2) / f(0) - views[k].floor_range_mean_m * views[k].floor_range_mean_m));
    }
    const int at = problem.layout.laser(k);
    views[k].information = H.block<4, 4>(at, at);
  }
  return views;
}

void set_gauge(Problem& problem, const std::vector<LaserObservability>& observability) {
  problem.gauge.clear();
  for (const int parameter : {1, 2}) {  // Δo, Δψ
    Eigen::VectorXd a = Eigen::VectorXd::Zero(problem.layout.size());
    int n = 0;
    for (int k = 0; k < problem.layout.lasers; ++k) n += observability[k].observable[parameter];
    for (int k = 0; k < problem.layout.lasers; ++k) {
      if (observability[k].observable[parameter]) a(problem.layout.laser(k) + parameter) = 1.0 / n;
    }
    if (n > 0) problem.gauge.push_back(a);
  }
}

// FloorHeight (calibration_solver.hpp): the floor polygon under each scan's carrier (its plane
// holds (x, y, floor_z) within 1 cm and its outline contains it), and the sensor's height above
// that floor as fitted, h + D(carrier) with D = corrected_distance (the carrier's distance above
// the adjusted plane; for a held floor, above the map's), averaged over those scans as a·x with
// its variance aᵀΣa (the larger of the sandwich's and the model's, as every sigma).
constexpr double kFloorMatchM = 0.01;

FloorHeight height_above_floor(const maps::PlaneMap& map, const Problem& problem, const State& x,
                               const Eigen::MatrixXd& covariance,
                               const Eigen::MatrixXd& model_covariance) {
  const Layout& layout = problem.layout;
  Eigen::VectorXd a = Eigen::VectorXd::Zero(layout.size());
  double above = 0.0;
  FloorHeight out;
  for (const ScanPose& pose : x.poses) {
    const Eigen::Vector3d carrier(pose.x_m, pose.y_m, pose.floor_z_m);
    for (std::size_t k = 0; k < map.polygons.size(); ++k) {
      const maps::PlanarPolygon& polygon = map.polygons[k];
      if (polygon.kind != maps::SurfaceKind::Floor ||
          std::abs(polygon.plane.signed_distance(carrier)) > kFloorMatchM ||
          !polygon.contains_uv(polygon.frame.project(carrier))) {
        continue;
      }
      const int j = problem.slot[k];
      above += corrected_distance(polygon, j >= 0 ? x.planes[j] : PlaneCorrection{}, carrier);
      if (j >= 0) {  // ∂D/∂(δ, s_u, s_v) = −(1, u, v), (u, v) from the centroid
        const Eigen::Vector2d uv = centroid_uv(polygon, carrier);
        a.segment<kPlaneParameters>(layout.plane(j)) -= Eigen::Vector3d(1.0, uv.x(), uv.y());
      }
      ++out.scans;
      break;
    }
  }
  const double n = std::max(1, out.scans);
  a /= n;
  a(layout.mount()) = 1.0;
  for (int i = 0; i < layout.size(); ++i)
    if (problem.fixed[i]) a(i) = 0.0;
  out.height_m = x.mounting.height_m + above / n;
  out.sigma_m = std::sqrt(std::max({0.0, a.dot(covariance * a), a.dot(model_covariance * a)}));
  return out;
}

bool within(const std::vector<LaserCorrection>& lasers, const std::array<double, 4>& bound) {
  return std::all_of(lasers.begin(), lasers.end(), [&](const LaserCorrection& c) {
    return std::abs(c.elevation_rad) <= bound[0] && std::abs(c.vertical_offset_m) <= bound[1] &&
           std::abs(c.azimuth_rad) <= bound[2] && std::abs(c.range_m) <= bound[3];
  });
}

}  // namespace

CalibrationResult calibrate(const maps::PlaneMap& map, const sensor::LaserCalibration& decode,
                            const std::vector<Return>& returns, const Mounting& mounting,
                            const std::vector<ScanPose>& poses, const CalibrationConfig& config) {
  const int lasers = decode.ring_count();
  const int scans = static_cast<int>(poses.size());
  for (const Return& ret : returns) {
    if (ret.laser < 0 || ret.laser >= lasers || ret.scan < 0 || ret.scan >= scans) {
      throw std::invalid_argument("calibrate: a return names laser " + std::to_string(ret.laser) +
                                  " of " + std::to_string(lasers) + " or scan " +
                                  std::to_string(ret.scan) + " of " + std::to_string(scans));
    }
  }
  if (config.gates_m.empty()) throw std::invalid_argument("calibration: no association gate");
  State x{std::vector<LaserCorrection>(lasers), mounting, poses, {}};
  const maps::PlaneIndex index(map);
  // The planes adjusted: every polygon a return falls on under the first (widest) gate.
  std::vector<int> slot(map.polygons.size(), -1);
  std::vector<int> polygon_of_slot;
  if (config.map_sigma_m > 0.0) {
    for (const Return& ret : returns) {
      const Eigen::Isometry3d T = map_from_fire(mounting, poses[ret.scan], ret.time_s);
      const sensor::Laser& laser = decode.lasers[ret.laser];
      const int polygon = associated_polygon(
          map, index, T * laser_origin(laser, {}),
          T * sensor_point(laser, {}, ret.azimuth_rad, ret.range_m), config.gates_m.front(),
          config.edge_margin_m);
      if (polygon < 0 || slot[polygon] >= 0) continue;
      slot[polygon] = static_cast<int>(polygon_of_slot.size());
      polygon_of_slot.push_back(polygon);
    }
  }
  const Layout layout{lasers, scans, static_cast<int>(polygon_of_slot.size())};
  x.planes.resize(polygon_of_slot.size());
  Eigen::VectorXd prior_sigma = Eigen::VectorXd::Zero(layout.size());
  std::vector<bool> fixed(layout.size(), false);
  for (int j = 0; j < layout.planes; ++j) {
    Eigen::AlignedBox2d extent;
    for (const Eigen::Vector2d& uv : map.polygons[polygon_of_slot[j]].outer_uv) extent.extend(uv);
    const Eigen::Vector2d size = extent.sizes().cwiseMax(kMinTiltExtentM);
    const maps::SurfaceKind kind = map.polygons[polygon_of_slot[j]].kind;
    const bool level = kind == maps::SurfaceKind::Floor || kind == maps::SurfaceKind::Ceiling;
    prior_sigma.segment<kPlaneParameters>(layout.plane(j)) << config.map_sigma_m,
        level ? config.level_tilt_sigma : config.map_sigma_m / size.x(),
        level ? config.level_tilt_sigma : config.map_sigma_m / size.y();
    // A level surface's tilt of σ 0 is held at 0 (not left free, as a prior of 0 would).
    for (int i = 1; i < kPlaneParameters; ++i)
      fixed[layout.plane(j) + i] = !(prior_sigma(layout.plane(j) + i) > 0.0);
  }
  Problem problem{map,
                  decode,
                  returns,
                  layout,
                  config.huber_m,
                  std::vector<int>(returns.size(), -1),
                  std::move(fixed),
                  {},
                  0.0,
                  std::move(slot),
                  std::move(polygon_of_slot),
                  std::move(prior_sigma),
                  0.0,
                  config.edge_margin_m,
                  conicloc::resolve_thread_count(config.threads),
                  {},
                  {},
                  {}};
  CalibrationResult result;
  result.lasers.resize(layout.lasers);
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  double weighted_sq = 0.0, sq = 0.0;
  std::size_t count = 0;
  const bool leave_out = config.unmapped_objects.median_sigmas > 0.0;
  const auto lines = leave_out ? scan_lines(returns) : std::vector<std::vector<std::size_t>>{};

  // The scheduled gates, then the last gate again while the associations still change (a round
  // converges to the best fit of its associations; wrong ones go only when re-associated).
  for (std::size_t round = 0; round < config.gates_m.size() + config.max_extra_rounds; ++round) {
    const double gate_m = config.gates_m[std::min(round, config.gates_m.size() - 1)];
    const std::vector<int> previous = problem.plane;
    const std::vector<bool> previous_fixed = problem.fixed;
    associate(problem, x, index, gate_m);
    // From the second round: the first one's fit is where a residual says "off the surface".
    // (unmapped_objects.hpp: judged on the range residuals at x.)
    result.unmapped_returns =
        leave_out && round > 0 ? leave_out_unmapped_objects(lines, problem.range_residuals(x),
                                                            problem.plane, config.unmapped_objects)
                               : 0;
    problem.hold_cosines(x);
    // From the second round too: the first round's residuals are the start's errors.
    const ReturnNoise fitted_before = problem.noise;
    if (round > 0) problem.fit_noise(x, config.return_noise);
    // Observability is judged anew each round at the current state: what a laser measures
    // depends on the mounting (a level laser at 0° learns nothing of its elevation on walls,
    // a tilted one does). A correction found unobservable goes back to 0 and stays there; the
    // rounds end when neither the associations nor this verdict change.
    problem.normal_equations(x, H, g, weighted_sq, sq, count);
    if (count == 0) throw std::invalid_argument("calibrate: no return lies on a map plane");
    // Floored at (1 mm)²: noise-free returns would otherwise take the priors away, and with
    // them what holds the map's common shift (the planes and the scans' poses moved together).
    problem.residual_variance =
        std::max(weighted_sq / static_cast<double>(count), kMinResidualSigmaM * kMinResidualSigmaM);
    const auto views = laser_views(problem, x, H, config.observability);
    std::vector<LaserObservability> observability;
    for (int k = 0; k < layout.lasers; ++k) {
      observability.push_back(laser_observability(views[k], config.observability));
      result.lasers[k].observability = observability.back();
      result.lasers[k].planes = static_cast<int>(views[k].normals_sensor.size());
      const std::array<double*, 4> value = {&x.lasers[k].elevation_rad,
                                            &x.lasers[k].vertical_offset_m,
                                            &x.lasers[k].azimuth_rad, &x.lasers[k].range_m};
      for (int i = 0; i < kLaserParameters; ++i) {
        problem.fixed[layout.laser(k) + i] = !observability.back().observable[i];
        if (problem.fixed[layout.laser(k) + i]) *value[i] = 0.0;
      }
    }
    if (round >= config.gates_m.size() && problem.plane == previous &&
        problem.fixed == previous_fixed) {
      // No step follows: the solution and its covariance are those of the weights it was
      // fitted with, not of a noise read off it afresh.
      problem.noise = fitted_before;
      break;
    }
    set_gauge(problem, observability);
    // The data are exactly flat along the gauge, so any weight pins it; one on the scale of
    // the data's largest curvature keeps the system well conditioned.
    problem.gauge_weight = std::max(1.0, H.diagonal().maxCoeff());
    double lambda = 1e-6;
    result.converged = false;
    for (int iteration = 0; iteration < config.max_iterations; ++iteration) {
      problem.hold_cosines(x);
      problem.normal_equations(x, H, g, weighted_sq, sq, count);
      problem.constrain(x, H, g);
      State trial;
      const StepOutcome step = levenberg_marquardt_step(
          H, g, problem.cost(x), lambda,
          [&](const Eigen::VectorXd& delta) {
            trial = x;
            add(trial, delta, layout);
            return within(trial.lasers, config.max_correction)
                       ? problem.cost(trial)
                       : std::numeric_limits<double>::infinity();
          },
          [&](const Eigen::VectorXd&) { x = trial; }, config.step_tolerance,
          config.cost_tolerance);
      ++result.iterations;
      result.converged = step.converged;
      if (result.converged) break;
    }
  }

  problem.hold_cosines(x);
  // The covariance's H weighs each return by the curvature ψ'(e) of the cost the fit minimises,
  // not by the fit's weight ψ(e)/e: a residual beyond Huber's k pulls with a constant force, so
  // it moves the solution by its noise (ψ = ±k, in M) and holds it by nothing (ψ' = 0).
  Problem::Sums sums = problem.normal_sums(x, Problem::HessianWeight::Curvature);
  problem.constrain(x, sums.H, sums.g);
  const Eigen::MatrixXd& H_curvature = sums.H;
  count = sums.residuals.count;
  const double dof = std::max(
      1.0, static_cast<double>(count) -
               static_cast<double>(std::count(problem.fixed.begin(), problem.fixed.end(), false)));
  result.sigma_m = sums.residuals.sigma(dof);
  result.rms_m = sums.residuals.rms();
  result.returns = count;
  // The M-estimator's covariance H⁻¹·(M + σ_e²·P)·H⁻¹ (the sandwich, calibration_solver.hpp), H
  // = Σ ψ'·JJᵀ (+ priors, gauge), M the gradient's spread over scan lines and P the priors'
  // precisions (their score p·x has the variance p²·σ_j² = p·σ_e²). Beside it the model's, for
  // independent returns: M ≈ (Σψ²/n)·ΣJJᵀ and H ≈ ρ·ΣJJᵀ with ρ = Σψ'/n the share within k, so
  //   Σ_model = (Σψ²/dof)/ρ · H⁻¹   (HuberSums::model_scale; σ²·H⁻¹ when all lie within k).
  // With the fit's H and Σψ·e/dof in their place, at 3 cm of range noise and k = 5 cm (~10% of
  // the returns beyond k) the sigmas came out 5–9% narrow.
  const Eigen::MatrixXd H_inverse =
      H_curvature.ldlt().solve(Eigen::MatrixXd::Identity(layout.size(), layout.size()));
  const auto all_lines = leave_out ? std::vector<std::vector<std::size_t>>{} : scan_lines(returns);
  Eigen::MatrixXd M = problem.score_spread(x, leave_out ? lines : all_lines);
  for (int i = 0; i < layout.size(); ++i) {
    M(i, i) += problem.prior_precision(i) * problem.residual_variance;
    if (!problem.fixed[i]) continue;
    M.row(i).setZero();
    M.col(i).setZero();
  }
  const Eigen::MatrixXd covariance = H_inverse * M * H_inverse;
  const Eigen::VectorXd variance = covariance.diagonal();
  const Eigen::MatrixXd model_covariance = H_inverse * sums.residuals.model_scale(dof);
  const Eigen::VectorXd model_variance = model_covariance.diagonal();
  auto sigma_of = [&](const Eigen::VectorXd& v, int i) {
    return problem.fixed[i] ? 0.0 : std::sqrt(std::max(0.0, v(i)));
  };
  // The larger of the two: the sandwich reads the spread off the data, which with few scan lines
  // (a scan's entries: 16) can come out below what white noise alone leaves.
  auto sigma = [&](int i) { return std::max(sigma_of(variance, i), sigma_of(model_variance, i)); };
  std::vector<int> associated(layout.lasers, 0);
  for (std::size_t i = 0; i < returns.size(); ++i)
    associated[returns[i].laser] += problem.plane[i] >= 0;
  for (int k = 0; k < layout.lasers; ++k) {
    result.lasers[k].correction = x.lasers[k];
    result.lasers[k].returns = associated[k];
    for (int i = 0; i < kLaserParameters; ++i) {
      result.lasers[k].sigma[i] = sigma(layout.laser(k) + i);
      result.lasers[k].model_sigma[i] = sigma_of(model_variance, layout.laser(k) + i);
    }
  }
  std::vector<int> on_plane(layout.planes, 0);
  for (std::size_t i = 0; i < returns.size(); ++i) {
    if (problem.plane[i] >= 0 && problem.slot[problem.plane[i]] >= 0)
      ++on_plane[problem.slot[problem.plane[i]]];
  }
  for (int j = 0; j < layout.planes; ++j) {
    PlaneEstimate& plane = result.planes.emplace_back();
    plane.polygon = problem.polygon_of_slot[j];
    plane.correction = x.planes[j];
    plane.returns = on_plane[j];
    for (int i = 0; i < kPlaneParameters; ++i) plane.sigma[i] = sigma(layout.plane(j) + i);
  }
  result.mounting = x.mounting;
  for (int i = 0; i < kMountParameters; ++i) result.mounting_sigma[i] = sigma(layout.mount() + i);
  result.height_above_floor = height_above_floor(map, problem, x, covariance, model_covariance);
  result.noise = problem.noise;
  result.poses = x.poses;
  return result;
}

}  // namespace conicloc::calib
