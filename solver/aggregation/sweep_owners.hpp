#pragma once
// Which thread adds up which markers' pair sums in the pair sweep (pair_sweep.hpp), and which
// markers each thread visits (docs/model.md §4, "Neighbour search").
//
// Every cell belongs to one thread. A pair of two cells of one thread is evaluated once; a pair
// between threads is evaluated by both, each for its own marker. So the fewer pairs between
// threads, the less work is done twice: the cells are given out in slabs across the domain
// (sorted by their centroids along one axis; equal work per slab, a cell's work being its
// markers plus their entries in the lists), along the axis whose slabs separate fewer pairs of
// the lists. The owners change the work, never the bits: every marker still adds its partners
// in ascending order (pair_sweep.hpp), whoever evaluates them.
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "aggregation/pair_lists.hpp"
#include "geometry/domain.hpp"

namespace erythro::aggregation {

class SweepOwners {
 public:
  // Whether this plan was made for these lists (their last build) and this thread count.
  bool fits(const PairLists& lists, int threads, std::size_t markers) const {
    return threads_ == threads && builds_ == lists.builds() && owner_.size() == markers;
  }
  // Slabs of cells, one per thread (1: every cell to thread 0), made with the lists;
  // cell_of[m]: marker m's cell, as the lists were built with.
  void assign_slabs(const geometry::Domain& domain, const MarkerView& v, std::span<const std::size_t> cell_of,
                    const PairLists& lists, int threads);
  // Any owner per cell (cell_owner[c] < threads), for the tests.
  void assign(std::span<const unsigned> cell_owner, const MarkerView& v, const PairLists& lists, int threads);

  int threads() const { return threads_; }
  // The thread that adds up marker m's sums.
  std::span<const unsigned> owner() const { return owner_; }
  // In ascending order, the markers thread t visits: its own, and the others' markers with a
  // partner of thread t above them in the lists (whose pair it evaluates for that partner).
  std::span<const std::size_t> visits(int t) const { return visit_[static_cast<std::size_t>(t)]; }

 private:
  int threads_ = 0;
  std::size_t builds_ = 0;
  std::vector<unsigned> owner_;
  std::vector<std::vector<std::size_t>> visit_;
  std::vector<unsigned> cell_owner_;
  std::vector<std::size_t> last_visit_;
  // assign_slabs' scratch, kept so that a new cut allocates nothing once grown: each cell's
  // work, the cut along x, the cells sorted by their centroids.
  std::vector<std::size_t> cell_work_;
  std::vector<unsigned> along_x_;
  std::vector<std::pair<double, std::size_t>> key_;
};

}  // namespace erythro::aggregation
