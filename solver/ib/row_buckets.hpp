#pragma once
// The markers sorted by the first grid row of their kernel support (docs/model.md §2), for
// spreading row by row (ib/transfer.hpp): a stable counting sort, so that the markers of a
// bucket stay in ascending marker order.
//
// Buckets: periodic y, bucket = j0 mod ny (ny buckets); walls, bucket = j0 + W − 1 ∈
// [0, ny + W − 1) (the rows above a wall's first row), and a marker whose whole support lies
// beyond a wall gets none (outside()).
//
// On threads, each thread counts and places the markers of its own share (a range of marker
// indices); a bucket takes the shares' markers share after share, so the order is the one of
// the serial sort for any thread count.
#include <span>
#include <vector>

#include "geometry/domain.hpp"
#include "geometry/grid_polygon.hpp"

namespace erythro::ib {

class RowBuckets {
 public:
  // Sorts the markers at heights Y for a kernel of the given width on `domain`.
  void sort(std::span<const double> Y, int width, const geometry::Domain& domain, bool threads);

  int buckets() const { return static_cast<int>(start_.size()) - 1; }
  // The bucket of the markers whose first support row is j0 (may be outside [0, buckets())).
  int bucket_of(int j0) const { return periodic_y_ ? geometry::wrap_periodic(j0, ny_) : j0 + width_ - 1; }
  // Bucket b holds sorted()[start(b)] … sorted()[start(b + 1) − 1].
  int start(int b) const { return start_[static_cast<std::size_t>(b)]; }
  // Every marker with a bucket, bucket after bucket, ascending within one.
  const std::vector<int>& sorted() const { return order_; }
  // The markers without a bucket, ascending.
  const std::vector<int>& outside() const { return outside_; }

  // Rows first[s] … first[s + 1] − 1 for share s = 0 … shares − 1: neighbouring rows, each share
  // about as much of spreading's work as the others (a row costs one, plus one per marker whose
  // support reaches it). first gets shares + 1 entries.
  void split_rows(int shares, std::vector<int>& first) const;

 private:
  int width_ = 0, ny_ = 0;
  bool periodic_y_ = false;
  std::vector<int> bucket_of_marker_, start_, order_, outside_;
  std::vector<int> share_next_;  // per share and bucket: the next place of the share's markers
};

}  // namespace erythro::ib
