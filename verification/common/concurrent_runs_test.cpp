// vv::run_concurrently: every job runs once, each worker's parallel regions get one OpenMP
// thread, one worker runs the jobs in order on the caller, and a failing job's exception
// reaches the caller after all jobs ran.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include <omp.h>

#include "common/concurrent_runs.hpp"

using erythro::vv::run_concurrently;

TEST(ConcurrentRuns, EveryJobOnceWithOneOpenMpThread) {
  std::vector<int> done(7, 0), threads(7, 0);
  std::vector<std::function<void()>> jobs;
  for (std::size_t i = 0; i < done.size(); ++i)
    jobs.push_back([&, i] {
      ++done[i];
      threads[i] = omp_get_max_threads();
    });
  run_concurrently(jobs, 2);
  for (std::size_t i = 0; i < done.size(); ++i) {
    EXPECT_EQ(done[i], 1);
    EXPECT_EQ(threads[i], 1);
  }
}

TEST(ConcurrentRuns, OneWorkerRunsInOrderOnTheCaller) {
  std::vector<int> order;
  const std::thread::id caller = std::this_thread::get_id();
  bool same_thread = true;
  std::vector<std::function<void()>> jobs;
  for (int i = 0; i < 4; ++i)
    jobs.push_back([&, i] {
      order.push_back(i);
      same_thread = same_thread && std::this_thread::get_id() == caller;
    });
  run_concurrently(jobs, 1);
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_TRUE(same_thread);
}

TEST(ConcurrentRuns, FailureIsRethrownAfterAllJobs) {
  std::atomic<int> ran{0};
  std::vector<std::function<void()>> jobs = {[&] { ++ran; }, [&] {
                                               ++ran;
                                               throw std::runtime_error("job 1 failed");
                                             },
                                             [&] { ++ran; }, [&] { ++ran; }};
  EXPECT_THROW(run_concurrently(jobs, 2), std::runtime_error);
  EXPECT_EQ(ran.load(), 4);
}
