#include "parallel/parallel_for.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace conicloc {

int resolve_thread_count(int threads) {
  if (threads >= 1) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void parallel_for(std::size_t count, int threads,
                  const std::function<void(std::size_t, std::size_t, int)>& body) {
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)),
                                                    std::max<std::size_t>(count, 1));
  if (workers <= 1) {
    body(0, count, 0);
    return;
  }
  std::vector<std::exception_ptr> errors(workers);
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  const auto run = [&](std::size_t w) {
    const std::size_t begin = count * w / workers;
    const std::size_t end = count * (w + 1) / workers;
    try {
      body(begin, end, static_cast<int>(w));
    } catch (...) {
      errors[w] = std::current_exception();
    }
  };
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(run, w);
  run(0);
  for (auto& thread : pool) thread.join();
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

void parallel_for_runs(std::size_t count, std::size_t run, int threads,
                       const std::function<void(std::size_t, std::size_t, int)>& body) {
  run = std::max<std::size_t>(run, 1);
  const std::size_t runs = (count + run - 1) / run;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  parallel_for(runs, threads, [&](std::size_t, std::size_t, int worker) {
    // A failed worker stops the others at their next run: the caller sees its exception.
    for (std::size_t r = next++; r < runs && !failed; r = next++) {
      try {
        body(r * run, std::min(count, (r + 1) * run), worker);
      } catch (...) {
        failed = true;
        throw;
      }
    }
  });
}

}  // namespace conicloc
