// parallel::for_each_chunk (common/chunk_stealing.hpp): every chunk exactly once on any thread
// count (and every item once in for_each_range's ranges), each share's owner from its front,
// another thread only from its back, and in order on the caller's thread inside a parallel region.
#include "common/chunk_stealing.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace {

using erythro::parallel::for_each_chunk;
using erythro::parallel::for_each_range;

TEST(ChunkStealing, EveryChunkExactlyOnce) {
  for (const int threads : {1, 2, 3, 4, 8}) {
    for (const long chunks : {0L, 1L, 2L, 3L, 7L, 64L, 65L, 1000L}) {
      std::vector<std::atomic<int>> runs(static_cast<std::size_t>(chunks));
      for_each_chunk(chunks, threads, [&](long c) { runs[static_cast<std::size_t>(c)].fetch_add(1); });
      for (long c = 0; c < chunks; ++c)
        ASSERT_EQ(runs[static_cast<std::size_t>(c)].load(), 1)
            << threads << " threads, " << chunks << " chunks, chunk " << c;
    }
  }
}

TEST(ChunkStealing, RangesCoverEveryItemOnceInWholeChunks) {
  for (const int threads : {1, 2, 3}) {
    for (const long items : {0L, 1L, 127L, 128L, 129L, 1000L}) {
      std::vector<std::atomic<int>> runs(static_cast<std::size_t>(items));
      for_each_range(items, 128, threads, [&](long first, long last) {
        EXPECT_EQ(first % 128, 0) << "a range starts inside a chunk";
        EXPECT_TRUE(last - first == 128 || last == items) << "a short range before the end: " << first << " " << last;
        for (long i = first; i < last; ++i) runs[static_cast<std::size_t>(i)].fetch_add(1);
      });
      for (long i = 0; i < items; ++i)
        ASSERT_EQ(runs[static_cast<std::size_t>(i)].load(), 1)
            << threads << " threads, " << items << " items, item " << i;
    }
  }
}

// Two threads, 20 chunks, each thread's chunks slept through: 1 ms on thread 0, 4 ms on thread 1.
// Whatever the timing, each share's owner runs a first stretch of it and the other thread the
// rest (taken from the back: chunks taken from the front would interleave with the owner's);
// with these speeds thread 0 finishes its share first and takes some of thread 1's.
TEST(ChunkStealing, AFastThreadTakesTheBackOfASlowThreadsShare) {
  constexpr long kChunks = 20, kShare = kChunks / 2;
  std::vector<int> ran_on(kChunks, -1);
  for_each_chunk(kChunks, 2, [&](long c) {
    const int t = omp_get_thread_num();
    ran_on[static_cast<std::size_t>(c)] = t;
    std::this_thread::sleep_for(std::chrono::milliseconds(t == 1 ? 4 : 1));
  });
  long taken_from_thread_1 = 0;
  for (int owner = 0; owner < 2; ++owner) {
    const long first = owner * kShare, last = first + kShare;
    long c = first;
    while (c < last && ran_on[static_cast<std::size_t>(c)] == owner) ++c;
    if (owner == 1) taken_from_thread_1 = last - c;
    for (; c < last; ++c)
      EXPECT_NE(ran_on[static_cast<std::size_t>(c)], owner)
          << "share " << owner << ": chunk " << c << " run by its owner after another thread's";
  }
  EXPECT_GT(taken_from_thread_1, 0) << "thread 0 took nothing from the slower thread";
}

TEST(ChunkStealing, InsideAParallelRegionRunsInOrderOnTheCallersThread) {
  std::vector<long> order;
  int caller = -1;
  std::vector<int> threads_seen;
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    {
      caller = omp_get_thread_num();
      for_each_chunk(6, 2, [&](long c) {
        order.push_back(c);
        threads_seen.push_back(omp_get_thread_num());
      });
    }
  }
  EXPECT_EQ(order, (std::vector<long>{0, 1, 2, 3, 4, 5}));
  for (const int t : threads_seen) EXPECT_EQ(t, caller);
}

}  // namespace
