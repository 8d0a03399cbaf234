#pragma once
// Data-parallel loop with std::thread, shared by the localizer (particles, rings, poses), the
// calibration and the simulator (packets, poses). Each index is processed exactly once by a pure
// function of its inputs, so results do not depend on the number of threads.

#include <cstddef>
#include <functional>

namespace conicloc {

/// The number of worker threads for a `threads` option: itself when ≥ 1, else all cores.
int resolve_thread_count(int threads);

/// Calls body(begin, end, worker) on contiguous chunks covering [0, count), one chunk per
/// worker (worker in [0, threads)), and returns when all are done. Runs inline for one thread or
/// small counts. An exception from a worker is rethrown here (that of the lowest-numbered worker).
void parallel_for(std::size_t count, int threads,
                  const std::function<void(std::size_t begin, std::size_t end, int worker)>& body);

/// Calls body(begin, end, worker) on runs of `run` consecutive indices covering [0, count), each
/// handed, in order, to whichever worker is free: for work whose cost varies along the indices,
/// where parallel_for's equal shares leave a worker waiting for the slowest. A worker's runs
/// come in increasing order. Inline for one thread; a worker's exception is rethrown here, and
/// the others take no run after it.
void parallel_for_runs(
    std::size_t count, std::size_t run, int threads,
    const std::function<void(std::size_t begin, std::size_t end, int worker)>& body);

}  // namespace conicloc
