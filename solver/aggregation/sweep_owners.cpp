#include "aggregation/sweep_owners.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>

namespace erythro::aggregation {

namespace {

// A cell's share of the sweep's work: its markers and their entries in the lists (each pair
// is in the lists of both its markers; a thread evaluates the pairs of its own markers).
void cell_work(const MarkerView& v, const PairLists& lists, std::vector<std::size_t>& work) {
  const std::span<const std::size_t> start = lists.start();
  work.resize(v.offsets.size() - 1);
  for (std::size_t c = 0; c < work.size(); ++c) {
    const std::size_t o = v.offsets[c], e = v.offsets[c + 1];
    work[c] = (e - o) + (start[e] - start[o]);
  }
}

// The cells sorted by their centroids along one axis and given out in `threads` slabs of equal
// work, each cell to the slab holding the middle of its work. key: scratch.
void slabs_along(bool along_y, const geometry::Domain& d, const MarkerView& v, std::span<const std::size_t> work,
                 int threads, std::vector<std::pair<double, std::size_t>>& key, std::vector<unsigned>& cell_owner) {
  const std::size_t cells = v.offsets.size() - 1;
  std::size_t total = 0;
  for (const std::size_t w : work) total += w;
  const std::span<const double> coord = along_y ? v.y : v.x;
  const bool periodic = along_y ? d.periodic_y : d.periodic_x;
  const double L = along_y ? d.grid.ny : d.grid.nx;
  key.resize(cells);  // (centroid, cell)
  for (std::size_t c = 0; c < cells; ++c) {
    double sum = 0.0;
    for (std::size_t m = v.offsets[c]; m < v.offsets[c + 1]; ++m) sum += coord[m];
    double mean = sum / static_cast<double>(v.offsets[c + 1] - v.offsets[c]);
    if (periodic) mean -= L * std::floor(mean / L);  // markers may be unwrapped by whole periods
    key[c] = {mean, c};
  }
  std::sort(key.begin(), key.end());
  const auto T = static_cast<std::size_t>(threads);
  cell_owner.assign(cells, 0);
  std::size_t before = 0;
  for (const auto& [centre, c] : key) {
    cell_owner[c] = static_cast<unsigned>(std::min((2 * before + work[c]) * T / (2 * total), T - 1));
    before += work[c];
  }
}

// The pairs of the lists (each once) whose markers belong to different threads.
std::size_t pairs_between(std::span<const unsigned> cell_owner, std::span<const std::size_t> cell_of,
                          const PairLists& lists) {
  const std::span<const std::size_t> start = lists.start(), list = lists.list(), upper = lists.upper();
  std::size_t between = 0;
  for (std::size_t m = 0; m + 1 < start.size(); ++m)
    for (std::size_t e = upper[m]; e < start[m + 1]; ++e)
      between += cell_owner[cell_of[m]] != cell_owner[cell_of[list[e]]];
  return between;
}

}  // namespace

void SweepOwners::assign_slabs(const geometry::Domain& d, const MarkerView& v, std::span<const std::size_t> cell_of,
                               const PairLists& lists, int threads) {
  const std::size_t cells = v.offsets.size() - 1;
  if (cell_of.size() != v.x.size()) throw std::invalid_argument("SweepOwners::assign_slabs: cell_of does not match");
  cell_owner_.assign(cells, 0);
  if (threads > 1 && !v.x.empty()) {
    // Slabs along x and along y; the cut that separates fewer pairs is kept (along y on a
    // tie). Where the cells crowd (the core of a channel) a cut along the flow parts more.
    cell_work(v, lists, cell_work_);
    slabs_along(false, d, v, cell_work_, threads, key_, along_x_);
    slabs_along(true, d, v, cell_work_, threads, key_, cell_owner_);
    if (pairs_between(along_x_, cell_of, lists) < pairs_between(cell_owner_, cell_of, lists))
      cell_owner_.swap(along_x_);
  }
  assign(cell_owner_, v, lists, threads);
}

void SweepOwners::assign(std::span<const unsigned> cell_owner, const MarkerView& v, const PairLists& lists,
                         int threads) {
  const std::size_t cells = v.offsets.size() - 1, N = v.x.size();
  if (threads < 1 || cell_owner.size() != cells || lists.start().size() != N + 1)
    throw std::invalid_argument("SweepOwners::assign: owners, cells and pair lists do not match");
  const auto T = static_cast<std::size_t>(threads);
  owner_.resize(N);
  for (std::size_t c = 0; c < cells; ++c) {
    if (cell_owner[c] >= T) throw std::invalid_argument("SweepOwners::assign: an owner beyond the threads");
    std::fill(owner_.begin() + static_cast<std::ptrdiff_t>(v.offsets[c]),
              owner_.begin() + static_cast<std::ptrdiff_t>(v.offsets[c + 1]), cell_owner[c]);
  }
  // Visits in ascending marker order: a marker to its owner, and once to every other thread
  // owning one of its partners above it.
  visit_.resize(T);
  for (auto& vis : visit_) {  // room for every marker: a new cut never makes them grow again
    vis.clear();
    vis.reserve(N);
  }
  last_visit_.assign(T, SIZE_MAX);
  const std::span<const std::size_t> start = lists.start(), list = lists.list(), upper = lists.upper();
  for (std::size_t m = 0; m < N; ++m) {
    visit_[owner_[m]].push_back(m);
    last_visit_[owner_[m]] = m;
    for (std::size_t e = upper[m]; e < start[m + 1]; ++e) {
      const unsigned t = owner_[list[e]];
      if (last_visit_[t] != m) {
        visit_[t].push_back(m);
        last_visit_[t] = m;
      }
    }
  }
  threads_ = threads;
  builds_ = lists.builds();
}

}  // namespace erythro::aggregation
