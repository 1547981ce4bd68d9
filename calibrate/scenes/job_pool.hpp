#pragma once
// Independent simulations run side by side on threads of this process (the caller's thread among
// them): a scene's repeats, a trend study's levels and seeds. On a machine with few cores a small
// scene gains more from one thread per run and several runs at once than from several threads per
// run (README, "Threads and jobs"). What a task computes must not depend on which thread runs it or
// when, so the results are those of one job.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace seedcal {

// Calls task(k) once for every k in [0, n), at most `jobs` at a time, starting them in order of k
// as threads come free, and returns when all have returned. An exception thrown by a task is kept
// at its index (null where none); the other tasks still run.
template <class Task>
std::vector<std::exception_ptr> run_jobs(std::size_t n, int jobs, const Task& task) {
  std::vector<std::exception_ptr> errors(n);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t k; (k = next++) < n;) {
      try {
        task(k);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    }
  };
  {
    const std::size_t threads = std::min(static_cast<std::size_t>(std::max(jobs, 1)), n);
    std::vector<std::jthread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
  }  // the pool's threads join here
  return errors;
}

// Lowers `first` to k (a series' first failed run, when runs finish out of order).
inline void lower_to(std::atomic<std::size_t>& first, std::size_t k) {
  std::size_t f = first.load();
  while (k < f && !first.compare_exchange_weak(f, k)) {
  }
}

}  // namespace seedcal
