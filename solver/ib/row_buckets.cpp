#include "ib/row_buckets.hpp"

#include <omp.h>

#include <algorithm>

#include "ib/kernel.hpp"

namespace erythro::ib {

void RowBuckets::sort(std::span<const double> Y, int width, const geometry::Domain& domain, bool threads) {
  width_ = width;
  ny_ = domain.grid.ny;
  periodic_y_ = domain.periodic_y;
  const long markers = static_cast<long>(Y.size());
  const int nb = periodic_y_ ? ny_ : ny_ + width_ - 1;
  const int shares = threads ? omp_get_max_threads() : 1;
  const long per_share = (markers + shares - 1) / shares;
  bucket_of_marker_.resize(Y.size());
  share_next_.assign(static_cast<std::size_t>(shares) * static_cast<std::size_t>(nb), 0);
  start_.resize(static_cast<std::size_t>(nb) + 1);
  order_.resize(Y.size());  // trimmed to the markers with a bucket below
  int* const mb = bucket_of_marker_.data();
  int* const next = share_next_.data();
  long outside = 0;
#pragma omp parallel num_threads(shares) if (shares > 1) reduction(+ : outside)
  {
    // 1. Each share's markers: their buckets (−1: none) and the share's count per bucket.
#pragma omp for schedule(static, 1)
    for (int s = 0; s < shares; ++s) {
      const long lo = s * per_share, hi = std::min(markers, lo + per_share);
      int* const count = next + static_cast<std::size_t>(s) * static_cast<std::size_t>(nb);
      for (long m = lo; m < hi; ++m) {
        const int b = bucket_of(support_start(Y[static_cast<std::size_t>(m)], width_));
        if (b >= 0 && b < nb) {
          mb[m] = b;
          ++count[b];
        } else {
          mb[m] = -1;
          ++outside;
        }
      }
    }
    // 2. Bucket after bucket, share after share: where each share's markers of a bucket go.
#pragma omp single
    {
      int place = 0;
      for (int b = 0; b < nb; ++b) {
        start_[static_cast<std::size_t>(b)] = place;
        for (int s = 0; s < shares; ++s) {
          int& slot = next[static_cast<std::size_t>(s) * static_cast<std::size_t>(nb) + static_cast<std::size_t>(b)];
          const int count = slot;
          slot = place;
          place += count;
        }
      }
      start_[static_cast<std::size_t>(nb)] = place;
    }
    // 3. Each share places its markers, in ascending order.
#pragma omp for schedule(static, 1)
    for (int s = 0; s < shares; ++s) {
      const long lo = s * per_share, hi = std::min(markers, lo + per_share);
      int* const slot = next + static_cast<std::size_t>(s) * static_cast<std::size_t>(nb);
      for (long m = lo; m < hi; ++m)
        if (mb[m] >= 0) order_[static_cast<std::size_t>(slot[mb[m]]++)] = static_cast<int>(m);
    }
  }
  order_.resize(static_cast<std::size_t>(start_[static_cast<std::size_t>(nb)]));
  outside_.clear();
  if (outside > 0)  // beyond a wall only: rare, and kept in marker order
    for (long m = 0; m < markers; ++m)
      if (mb[m] < 0) outside_.push_back(static_cast<int>(m));
}

void RowBuckets::split_rows(int shares, std::vector<int>& first) const {
  const int nb = buckets();
  auto work_of_row = [&](int y) {
    long w = 1;
    for (int a = 0; a < width_; ++a) {
      const int b = bucket_of(y - a);
      if (b >= 0 && b < nb) w += start(b + 1) - start(b);
    }
    return w;
  };
  long total = 0;
  for (int y = 0; y < ny_; ++y) total += work_of_row(y);
  first.assign(static_cast<std::size_t>(shares) + 1, ny_);
  first[0] = 0;
  long done = 0;
  int s = 1;
  for (int y = 0; y < ny_ && s < shares; ++y) {
    done += work_of_row(y);
    while (s < shares && done * shares >= total * s) first[static_cast<std::size_t>(s++)] = y + 1;
  }
}

}  // namespace erythro::ib
