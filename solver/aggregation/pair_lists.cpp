#include "aggregation/pair_lists.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "aggregation/pair_terms.hpp"

namespace erythro::aggregation {

namespace {

// Cell list over the domain: nb bins per axis of side n/nb ≥ r_c + skin (at least 1 bin).
struct CellList {
  static constexpr std::size_t kMixed = SIZE_MAX;
  int nbx = 1, nby = 1;
  std::vector<std::size_t> start, items;  // markers of bin b: items[start[b] … start[b+1]), ascending
  std::vector<std::size_t> owner;         // per bin: the one cell of its markers, kMixed, or none (empty)

  static int bins(int n, double rc) {
    // floor(n / r_c), with a 1e-9 margin so round-off in the bin index can never put two
    // markers closer than r_c two bins apart.
    return std::max(1, static_cast<int>(std::floor(double(n) / (rc * (1.0 + 1e-9)))));
  }

  static int bin_of(double x, int n, int nb, bool periodic) {
    double t = x / n;
    if (periodic) t -= std::floor(t);
    // Clamped before the conversion (no overflow): on a non-periodic axis markers beyond a
    // wall join the edge bin; on a periodic one it only catches t·nb rounding up to nb.
    return static_cast<int>(std::clamp(std::floor(t * nb), 0.0, double(nb - 1)));
  }

  void build(const geometry::Domain& d, const MarkerView& v, std::vector<int>& bin) {
    const std::size_t N = v.x.size();
    bin.resize(N);
    start.assign(static_cast<std::size_t>(nbx * nby) + 1, 0);
    for (std::size_t m = 0; m < N; ++m) {
      bin[m] = bin_of(v.y[m], d.grid.ny, nby, d.periodic_y) * nbx + bin_of(v.x[m], d.grid.nx, nbx, d.periodic_x);
      ++start[static_cast<std::size_t>(bin[m]) + 1];
    }
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    items.resize(N);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t m = 0; m < N; ++m) items[fill[static_cast<std::size_t>(bin[m])]++] = m;  // ascending per bin
  }

  // owner[b] for every bin: markers are ascending per bin and a cell's markers are one
  // index range, so the bin holds one cell iff its first and last marker share it.
  void find_owners(std::span<const std::size_t> cell_of) {
    const std::size_t bins = start.size() - 1;
    owner.assign(bins, 0);
    for (std::size_t b = 0; b < bins; ++b) {
      if (start[b] == start[b + 1]) continue;
      const std::size_t first = cell_of[items[start[b]]], last = cell_of[items[start[b + 1] - 1]];
      owner[b] = first == last ? first : kMixed;
    }
  }

  // Whether every marker of the (non-empty) bins `nb` belongs to one cell: then no marker
  // of them has a partner of another cell, and their pair sums stay zero.
  bool one_cell(const std::vector<int>& nb) const {
    std::size_t cell = kMixed;
    for (const int q : nb) {
      const std::size_t b = static_cast<std::size_t>(q);
      if (start[b] == start[b + 1]) continue;
      if (owner[b] == kMixed || (cell != kMixed && owner[b] != cell)) return false;
      cell = owner[b];
    }
    return true;
  }

  // The distinct bins within ±1 of (bx, by), wrapped on periodic axes, ascending.
  void neighbours(const geometry::Domain& d, int bx, int by, std::vector<int>& out) const {
    out.clear();
    if (bx >= 1 && bx + 1 < nbx && by >= 1 && by + 1 < nby) {  // inside: nine distinct bins, row by row
      for (int j = by - 1; j <= by + 1; ++j)
        for (int i = bx - 1; i <= bx + 1; ++i) out.push_back(j * nbx + i);
      return;
    }
    for (int oy = -1; oy <= 1; ++oy) {
      int j = by + oy;
      if (d.periodic_y) j = (j + nby) % nby;
      else if (j < 0 || j >= nby) continue;
      for (int ox = -1; ox <= 1; ++ox) {
        int i = bx + ox;
        if (d.periodic_x) i = (i + nbx) % nbx;
        else if (i < 0 || i >= nbx) continue;
        out.push_back(j * nbx + i);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
};

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
  CellList cl;
  cl.nbx = nbx_;
  cl.nby = nby_;
  std::vector<int> bin;
  cl.build(domain_, v, bin);
  cl.find_owners(cell_of);
  std::vector<std::size_t> begin(N, 0), length(N, 0);
  std::vector<int> thread_of(N, 0);
  const int nbins = nbx_ * nby_;
  const int threads = parallel ? omp_get_max_threads() : 1;
  std::vector<std::vector<std::size_t>> found(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    std::vector<std::size_t>& out = found[static_cast<std::size_t>(t)];
    out.clear();
    std::vector<int> nb;
    std::vector<std::size_t> cand, merged;
    PairScratch s;
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
    const std::vector<std::size_t>& src = found[static_cast<std::size_t>(thread_of[m])];
    const auto first = list_.begin() + static_cast<std::ptrdiff_t>(start_[m]);
    const auto last = list_.begin() + static_cast<std::ptrdiff_t>(start_[m + 1]);
    std::copy_n(src.begin() + static_cast<std::ptrdiff_t>(begin[m]), length[m], first);
    upper_[m] = static_cast<std::size_t>(std::upper_bound(first, last, m) - list_.begin());  // ascending lists
  }
  build_runs(cell_of);
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
