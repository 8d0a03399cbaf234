#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "sensor/azimuth_order.hpp"

namespace conicloc::sensor {
namespace {

// Returns whose time_s is their index in the input: the order a sort leaves shows in the times.
std::vector<Return> returns_at(const std::vector<double>& azimuths) {
  std::vector<Return> returns(azimuths.size());
  for (std::size_t i = 0; i < azimuths.size(); ++i) {
    returns[i].azimuth_rad = azimuths[i];
    returns[i].time_s = static_cast<double>(i);
  }
  return returns;
}

// The order std::stable_sort gives, as the input indices.
std::vector<double> stable_order(std::vector<Return> returns) {
  std::stable_sort(returns.begin(), returns.end(),
                   [](const Return& a, const Return& b) { return a.azimuth_rad < b.azimuth_rad; });
  std::vector<double> order;
  for (const Return& r : returns) order.push_back(r.time_s);
  return order;
}

std::vector<double> order_of(std::vector<Return> returns) {
  sort_by_azimuth(returns);
  std::vector<double> order;
  for (const Return& r : returns) order.push_back(r.time_s);
  return order;
}

// A de-skewed ring: `n` azimuths a step apart from `start`, wrapped into [0, 2π), one in 30 moved
// by up to `jitter` (the parallax of a near return), on a grid of `quantum` so that equal
// azimuths occur.
std::vector<double> ring_azimuths(std::size_t n, double start, double jitter, double quantum,
                                  std::mt19937& rng) {
  std::uniform_real_distribution<double> shift(-jitter, jitter);
  std::uniform_int_distribution<int> moved(0, 29);
  std::vector<double> azimuths;
  for (std::size_t i = 0; i < n; ++i) {
    double a = start + 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    if (moved(rng) == 0) a += shift(rng);
    a = std::fmod(a, 2.0 * M_PI);
    if (a < 0.0) a += 2.0 * M_PI;
    azimuths.push_back(std::round(a / quantum) * quantum);
  }
  return azimuths;
}

TEST(AzimuthOrder, ARingNearlyInOrderSortsAsStableSortDoes) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::uniform_real_distribution<double> start(-1.0, 7.0);
    // Returns moved by up to 4° (1 m off, the sensor moved 7 cm), azimuths on a 0.5° grid (ties).
    const auto azimuths = ring_azimuths(900, start(rng), 0.07, 0.5 * M_PI / 180.0, rng);
    const auto returns = returns_at(azimuths);
    ASSERT_EQ(order_of(returns), stable_order(returns)) << "trial " << trial;
  }
}

TEST(AzimuthOrder, WrapsAtBothEndsAndTiesAcrossThemKeepTheInputOrder) {
  // De-skew carried the first two past 0 (to just under 2π) and the last two past 2π (to just
  // over 0); 0.1 ties with a return of the main run and 6.2 with another.
  const auto returns = returns_at({6.2, 6.25, 0.1, 0.2, 3.0, 6.1, 6.2, 0.05, 0.1});
  EXPECT_EQ(order_of(returns), stable_order(returns));
  EXPECT_EQ(order_of(returns), (std::vector<double>{7, 2, 8, 3, 4, 5, 0, 6, 1}));
}

TEST(AzimuthOrder, AnyOtherOrderSortsAsStableSortDoes) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> grid(0, 40);  // few values: many ties
  for (const std::size_t n : {0u, 1u, 2u, 3u, 50u, 2000u}) {
    std::vector<double> azimuths;
    for (std::size_t i = 0; i < n; ++i) azimuths.push_back(0.15 * grid(rng));
    const auto returns = returns_at(azimuths);
    EXPECT_EQ(order_of(returns), stable_order(returns)) << n << " returns";
    // Descending, as a ring in firing order: left to the general sort.
    std::vector<double> reversed(azimuths);
    std::sort(reversed.rbegin(), reversed.rend());
    EXPECT_EQ(order_of(returns_at(reversed)), stable_order(returns_at(reversed)));
  }
}

}  // namespace
}  // namespace conicloc::sensor
