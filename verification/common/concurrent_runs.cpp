#include "concurrent_runs.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>

#include <omp.h>

namespace erythro::vv {

void run_concurrently(const std::vector<std::function<void()>>& jobs, int workers) {
  if (workers <= 0) workers = omp_get_max_threads();
  workers = std::min<int>(workers, static_cast<int>(jobs.size()));
  if (workers <= 1) {
    for (const auto& job : jobs) job();
    return;
  }
  std::vector<std::exception_ptr> errors(jobs.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    omp_set_num_threads(1);  // this thread's parallel regions: one thread (per-thread ICV)
    for (std::size_t i = next++; i < jobs.size(); i = next++) {
      try {
        jobs[i]();
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace erythro::vv
