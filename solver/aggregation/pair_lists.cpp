#include "aggregation/pair_lists.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "aggregation/pair_terms.hpp"

namespace erythro::aggregation {

using detail::CellList;

namespace {

// Room for at least n elements, a quarter more than asked when it must grow: the lists grow
// by a little from build to build as cells close in, and room for exactly n would mean a new
// allocation at nearly every build.
template <class T>
void room_for(std::vector<T>& v, std::size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 4);
}

}  // namespace

PairLists::PairLists(const geometry::Domain& domain, double cutoff) : domain_(domain), cutoff_(cutoff) {
  skin_ = std::min(kSkin, 0.25 * cutoff);
  if (domain.periodic_x) skin_ = std::min(skin_, 0.99 * (0.5 * domain.grid.nx - cutoff));
  if (domain.periodic_y) skin_ = std::min(skin_, 0.99 * (0.5 * domain.grid.ny - cutoff));
  skin_ = std::max(skin_, 0.0);
  nbx_ = CellList::bins(domain.grid.nx, cutoff + skin_);
  nby_ = CellList::bins(domain.grid.ny, cutoff + skin_);
}

// The same cells, and no marker moved by skin/2 or more since the build (two markers then
// closed in by less than the skin). A whole cell shifted by a period moved by a period.
bool PairLists::valid(const MarkerView& v) const {
  if (offsets_.size() != v.offsets.size() || !std::equal(offsets_.begin(), offsets_.end(), v.offsets.begin()))
    return false;
  const double limit2 = 0.25 * skin_ * skin_ * (1.0 - 1e-9);
  double worst = 0.0;  // a maximum: the same in any order, so for any thread count
  const long long n = static_cast<long long>(v.x.size());
#pragma omp parallel for schedule(static) if (n >= 2000) reduction(max : worst)
  for (long long i = 0; i < n; ++i) {
    const std::size_t m = static_cast<std::size_t>(i);
    const double ex = v.x[m] - x_[m], ey = v.y[m] - y_[m];
    worst = std::max(worst, ex * ex + ey * ey);
  }
  return worst < limit2;
}

// Per bin (in parallel): one ascending candidate list from its ≤ 9 neighbouring bins, and for
// each of its markers the candidates of other cells within r_c + skin, appended to the
// thread's buffer; then laid out per marker in marker order (CSR).
void PairLists::build(const MarkerView& v, std::span<const std::size_t> cell_of, bool parallel) {
  const std::size_t N = v.x.size();
  const double reach = cutoff_ + skin_, reach2 = reach * reach;
  CellList& cl = bins_;
  cl.nbx = nbx_;
  cl.nby = nby_;
  cl.build(domain_, v, bin_of_);
  cl.find_owners(cell_of);
  // Every marker's entry is written below (a bin's markers, or none: an empty list).
  std::vector<std::size_t>& begin = found_at_;
  std::vector<std::size_t>& length = length_;
  begin.assign(N, 0);
  length.assign(N, 0);
  thread_of_.assign(N, 0);
  std::vector<int>& thread_of = thread_of_;
  const int nbins = nbx_ * nby_;
  const int threads = parallel ? omp_get_max_threads() : 1;
  if (per_thread_.size() < static_cast<std::size_t>(threads)) per_thread_.resize(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    ThreadBuffers& buf = per_thread_[static_cast<std::size_t>(t)];
    std::vector<std::size_t>& out = buf.found;
    out.clear();
    std::vector<int>& nb = buf.neighbours;
    std::vector<std::size_t>& cand = buf.candidates;
    std::vector<std::size_t>& merged = buf.merged;
    PairScratch& s = buf.separations;
    room_for(out, most_entries_);  // what any thread may find (a whole build)
    room_for(cand, most_candidates_);
    room_for(merged, most_candidates_);
    s.hold(most_candidates_ + most_candidates_ / 4);
    room_for(nb, 9);
#pragma omp for schedule(dynamic, 64)
    for (int b = 0; b < nbins; ++b) {
      const std::size_t b0 = cl.start[static_cast<std::size_t>(b)], b1 = cl.start[static_cast<std::size_t>(b) + 1];
      if (b0 == b1) continue;
      cl.neighbours(domain_, b % nbx_, b / nbx_, nb);
      if (cl.one_cell(nb)) continue;  // one cell's markers only: empty lists
      // The bins' ascending runs merged into one ascending candidate list for the bin.
      cand.clear();
      for (const int q : nb) {
        const auto first = cl.items.begin() + static_cast<std::ptrdiff_t>(cl.start[static_cast<std::size_t>(q)]);
        const auto last = cl.items.begin() + static_cast<std::ptrdiff_t>(cl.start[static_cast<std::size_t>(q) + 1]);
        if (first == last) continue;
        merged.resize(cand.size() + static_cast<std::size_t>(last - first));
        std::merge(cand.begin(), cand.end(), first, last, merged.begin());
        cand.swap(merged);
      }
      const std::size_t n = cand.size();
      buf.most_candidates = std::max(buf.most_candidates, n);
      s.hold(n);
      for (std::size_t i = 0; i < n; ++i) {
        s.cx[i] = v.x[cand[i]];
        s.cy[i] = v.y[cand[i]];
      }
      for (std::size_t k = b0; k < b1; ++k) {
        const std::size_t m = cl.items[k], c = cell_of[m];
        std::fill_n(s.mx.begin(), n, v.x[m]);
        std::fill_n(s.my.begin(), n, v.y[m]);
        pair_separations(domain_, n, s);
        begin[m] = out.size();
        thread_of[m] = t;
        for (std::size_t i = 0; i < n; ++i) {
          if (s.r2[i] < reach2 && (cand[i] < v.offsets[c] || cand[i] >= v.offsets[c + 1])) out.push_back(cand[i]);
        }
        length[m] = out.size() - begin[m];
      }
    }
  }
  start_.assign(N + 1, 0);
  for (std::size_t m = 0; m < N; ++m) start_[m + 1] = start_[m] + length[m];
  list_.resize(start_[N]);
  upper_.resize(N);
  for (std::size_t m = 0; m < N; ++m) {
    const std::vector<std::size_t>& src = per_thread_[static_cast<std::size_t>(thread_of[m])].found;
    const auto first = list_.begin() + static_cast<std::ptrdiff_t>(start_[m]);
    const auto last = list_.begin() + static_cast<std::ptrdiff_t>(start_[m + 1]);
    std::copy_n(src.begin() + static_cast<std::ptrdiff_t>(begin[m]), length[m], first);
    upper_[m] = static_cast<std::size_t>(std::upper_bound(first, last, m) - list_.begin());  // ascending lists
  }
  build_runs(cell_of);
  most_entries_ = std::max(most_entries_, list_.size());
  for (const ThreadBuffers& buf : per_thread_) most_candidates_ = std::max(most_candidates_, buf.most_candidates);
  x_.assign(v.x.begin(), v.x.end());
  y_.assign(v.y.begin(), v.y.end());
  offsets_.assign(v.offsets.begin(), v.offsets.end());
  ++builds_;
}

// Each marker's entries above it cut into runs: a run ends where the next partner is not the
// next marker index or belongs to another cell (so each run lies in one cell).
void PairLists::build_runs(std::span<const std::size_t> cell_of) {
  const std::size_t N = upper_.size();
  run_start_.assign(N + 1, 0);
  run_first_.clear();
  run_length_.clear();
  for (std::size_t m = 0; m < N; ++m) {
    for (std::size_t e = upper_[m]; e < start_[m + 1]; ++e) {
      const std::size_t n = list_[e];
      if (e > upper_[m] && n == list_[e - 1] + 1 && cell_of[n] == cell_of[n - 1]) {
        ++run_length_.back();
      } else {
        run_first_.push_back(n);
        run_length_.push_back(1);
      }
    }
    run_start_[m + 1] = run_first_.size();
  }
}

}  // namespace erythro::aggregation
