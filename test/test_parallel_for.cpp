// The data-parallel loop (parallel/parallel_for.hpp): every index once, for any thread count, and
// a worker's exception rethrown to the caller.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "parallel/parallel_for.hpp"

TEST(ParallelFor, CoversEveryIndexOnceForAnyThreadCount) {
  for (const int threads : {1, 2, 3, 8}) {
    std::vector<int> hits(1001, 0);
    conicloc::parallel_for(hits.size(), threads, [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t i = begin; i < end; ++i) ++hits[i];
    });
    EXPECT_EQ(std::count(hits.begin(), hits.end(), 1), 1001) << threads;
  }
  EXPECT_GE(conicloc::resolve_thread_count(0), 1);
  EXPECT_EQ(conicloc::resolve_thread_count(3), 3);
}

TEST(ParallelFor, AWorkersExceptionReachesTheCaller) {
  for (const int threads : {1, 2, 4}) {
    EXPECT_THROW(conicloc::parallel_for(100, threads,
                                        [](std::size_t begin, std::size_t end, int) {
                                          if (begin <= 99 && 99 < end)
                                            throw std::runtime_error("last index");
                                        }),
                 std::runtime_error)
        << threads;
  }
}
