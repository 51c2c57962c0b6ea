// The markers sorted by the first row of their support: on any number of threads, the
// stable sort by bucket (ascending marker order within a bucket), and the markers beyond a
// wall left out, in marker order.
#include "ib/row_buckets.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "ib/kernel.hpp"

using namespace erythro;
using namespace erythro::ib;
using geometry::Domain;

namespace {

// Heights over and beyond the grid: periodic y wraps them, walls drop the supports beyond.
std::vector<double> heights(int ny, int markers) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> y(-8.0, ny + 8.0);
  std::vector<double> Y(static_cast<std::size_t>(markers));
  for (double& v : Y) v = y(rng);
  return Y;
}

struct Expected {
  std::vector<int> sorted, outside, start;
};

// The reference: each marker's bucket as RowBuckets documents it, then std::stable_sort.
Expected reference(const std::vector<double>& Y, int width, const Domain& d) {
  const int ny = d.grid.ny, nb = d.periodic_y ? ny : ny + width - 1;
  std::vector<int> bucket(Y.size());
  Expected e;
  std::vector<int> all(Y.size());
  std::iota(all.begin(), all.end(), 0);
  for (std::size_t m = 0; m < Y.size(); ++m) {
    const int j0 = support_start(Y[m], width);
    const int b = d.periodic_y ? ((j0 % ny) + ny) % ny : j0 + width - 1;
    bucket[m] = b >= 0 && b < nb ? b : -1;
    if (bucket[m] < 0) e.outside.push_back(static_cast<int>(m));
  }
  std::stable_sort(all.begin(), all.end(), [&](int a, int b) { return bucket[a] < bucket[b]; });
  for (const int m : all)
    if (bucket[m] >= 0) e.sorted.push_back(m);
  for (int b = 0; b <= nb; ++b)
    e.start.push_back(
        static_cast<int>(std::count_if(bucket.begin(), bucket.end(), [&](int k) { return k >= 0 && k < b; })));
  return e;
}

}  // namespace

TEST(RowBuckets, StableSortByBucketOnAnyNumberOfThreads) {
  const int threads_before = omp_get_max_threads();  // restored for the tests after this one
  for (const bool periodic : {true, false}) {
    for (const int width : {4, 3, 2}) {
      const Domain d{Grid{64, 48}, true, periodic};
      const std::vector<double> Y = heights(d.grid.ny, 3001);
      const Expected e = reference(Y, width, d);
      EXPECT_EQ(e.outside.empty(), periodic);  // the heights reach beyond the walls
      for (const int threads : {1, 2, 3}) {
        omp_set_num_threads(threads);
        RowBuckets rb;
        rb.sort(Y, width, d, threads > 1);
        rb.sort(Y, width, d, threads > 1);  // a second sort reuses the scratch
        ASSERT_EQ(rb.sorted(), e.sorted) << "periodic " << periodic << ", width " << width << ", threads " << threads;
        ASSERT_EQ(rb.outside(), e.outside);
        ASSERT_EQ(rb.buckets() + 1, static_cast<int>(e.start.size()));
        for (int b = 0; b <= rb.buckets(); ++b) ASSERT_EQ(rb.start(b), e.start[static_cast<std::size_t>(b)]) << b;
      }
    }
  }
  omp_set_num_threads(threads_before);
}

TEST(RowBuckets, SharesOfRowsCoverTheGridInOrderWithAboutEqualWork) {
  const Domain d{Grid{64, 48}, true, true};
  std::vector<double> Y = heights(d.grid.ny, 2000);
  for (double& y : Y) y = 0.25 * y;  // the markers crowd the lowest quarter of the rows
  RowBuckets rb;
  rb.sort(Y, 4, d, false);
  auto work_of_row = [&](int y) {  // one per row, plus the markers whose support reaches it
    long w = 1;
    for (int a = 0; a < 4; ++a) {
      const int b = rb.bucket_of(y - a);
      w += rb.start(b + 1) - rb.start(b);
    }
    return w;
  };
  long total = 0, largest_row = 0;
  for (int y = 0; y < d.grid.ny; ++y) {
    total += work_of_row(y);
    largest_row = std::max(largest_row, work_of_row(y));
  }
  for (const int shares : {1, 2, 3, 7}) {
    std::vector<int> first;
    rb.split_rows(shares, first);
    ASSERT_EQ(first.size(), static_cast<std::size_t>(shares) + 1);
    EXPECT_EQ(first.front(), 0);
    EXPECT_EQ(first.back(), d.grid.ny);
    for (int s = 0; s < shares; ++s) {
      ASSERT_LE(first[s], first[s + 1]) << shares;
      long w = 0;
      for (int y = first[s]; y < first[s + 1]; ++y) w += work_of_row(y);
      // A share ends at the first row that takes it to its part of the total: at most one row more.
      EXPECT_LE(std::abs(w - total / shares), largest_row) << "share " << s << " of " << shares;
    }
  }
}
