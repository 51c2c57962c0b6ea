#include "aggregation/pair_sweep.hpp"

#include <omp.h>

#include <algorithm>

namespace erythro::aggregation {

namespace {

constexpr std::size_t kChunk = 64;  // markers whose entries are evaluated as one batch

// Into s: for markers first … last − 1 the entries from(m) … to(m) − 1 of their lists, each with
// the marker's and the partner's position and ℓ (pair_terms.hpp), the partner's index in
// s.partner and each marker's end in the batch in s.ends[m − first]. Returns the entry count.
template <class From, class To>
std::size_t gather(const SweepArrays& a, std::span<const std::size_t> list, std::size_t first, std::size_t last,
                   From from, To to, PairScratch& s) {
  // Each marker's range once (to(m) may be a binary search), its end kept in s.ends meanwhile.
  s.ends.resize(last - first);
  std::size_t n = 0;
  for (std::size_t m = first; m < last; ++m) {
    s.ends[m - first] = to(m);
    n += s.ends[m - first] - from(m);
  }
  s.resize(n);
  s.partner.resize(n);
  std::size_t i = 0;
  for (std::size_t m = first; m < last; ++m) {
    const std::size_t end = s.ends[m - first];
    for (std::size_t e = from(m); e < end; ++e, ++i) {
      const std::size_t p = list[e];
      s.partner[i] = p;
      s.cx[i] = a.x[p];
      s.cy[i] = a.y[p];
      s.cl[i] = a.ell[p];
      s.mx[i] = a.x[m];
      s.my[i] = a.y[m];
      s.ml[i] = a.ell[m];
    }
    s.ends[m - first] = i;
  }
  return n;
}

void store(const SweepArrays& a, std::size_t m, const PairSums& acc) {
  a.S[m] = acc.s;
  a.px[m] = acc.fx;
  a.py[m] = acc.fy;
  a.rmin[m] = acc.rmin;
  a.count[m] = acc.k;
}

// The pairs of markers lo … hi − 1 with partners below lo, each for its marker alone: the
// first terms of those markers' sums, in list (ascending) order.
void below_range(const geometry::Domain& d, const ContactPotential& potential, const PairLists& lists,
                 const SweepArrays& a, std::size_t lo, std::size_t hi, PairScratch& s, bool& coincident) {
  const std::span<const std::size_t> start = lists.start(), list = lists.list();
  auto from = [&](std::size_t m) { return start[m]; };
  auto to = [&](std::size_t m) {
    const auto first = list.begin() + static_cast<std::ptrdiff_t>(start[m]);
    const auto last = list.begin() + static_cast<std::ptrdiff_t>(start[m + 1]);
    return static_cast<std::size_t>(std::lower_bound(first, last, lo) - list.begin());
  };
  for (std::size_t first = lo; first < hi; first += kChunk) {
    const std::size_t last = std::min(hi, first + kChunk);
    const std::size_t n = gather(a, list, first, last, from, to, s);
    if (n == 0) continue;
    const std::size_t k = evaluate_pairs(d, potential, n, s, coincident);
    std::size_t q = 0;
    for (std::size_t m = first; m < last; ++m) {
      const std::size_t end = s.ends[m - first];
      if (q < k && s.hits[q] < end) store(a, m, marker_sums(s, q, k, end));
    }
  }
}

// Markers lo … hi − 1 in ascending order over their partners above them: each pair's terms to
// the swept marker (whose sums hold its partners below it by then) and, for a partner inside
// the range, to the partner as well (X_p − X_m = −dx; ℓ_m in place of ℓ_p).
void sweep_range(const geometry::Domain& d, const ContactPotential& potential, const PairLists& lists,
                 const SweepArrays& a, std::size_t lo, std::size_t hi, PairScratch& s, bool& coincident) {
  const std::span<const std::size_t> start = lists.start(), list = lists.list(), upper = lists.upper();
  auto from = [&](std::size_t m) { return upper[m]; };
  auto to = [&](std::size_t m) { return start[m + 1]; };
  for (std::size_t first = lo; first < hi; first += kChunk) {
    const std::size_t last = std::min(hi, first + kChunk);
    const std::size_t n = gather(a, list, first, last, from, to, s);
    if (n == 0) continue;  // no pair above these markers: their sums are complete
    const std::size_t k = evaluate_pairs(d, potential, n, s, coincident);
    std::size_t q = 0;
    for (std::size_t m = first; m < last; ++m) {
      const std::size_t end = s.ends[m - first];
      if (q >= k || s.hits[q] >= end) continue;
      PairSums acc{a.S[m], a.px[m], a.py[m], a.rmin[m], a.count[m]};
      for (; q < k && s.hits[q] < end; ++q) {
        if (!s.on[q]) continue;
        const std::size_t j = s.hits[q], p = s.partner[j];
        acc.s += s.phi[q] * s.cl[j];  // as marker_sums
        acc.fx -= s.w[q] * s.dx[j];
        acc.fy -= s.w[q] * s.dy[j];
        acc.rmin = std::min(acc.rmin, s.hr[q]);
        ++acc.k;
        if (p >= hi) continue;  // the thread above adds it to p
        a.S[p] += s.phi[q] * s.ml[j];
        a.px[p] -= s.w[q] * (-s.dx[j]);
        a.py[p] -= s.w[q] * (-s.dy[j]);
        a.rmin[p] = std::min(a.rmin[p], s.hr[q]);
        ++a.count[p];
      }
      store(a, m, acc);
    }
  }
}

}  // namespace

bool sweep_pair_lists(const geometry::Domain& domain, const ContactPotential& potential, const PairLists& lists,
                      const SweepArrays& a, int threads, std::vector<PairScratch>& per_thread) {
  const std::size_t N = a.x.size();
  if (per_thread.size() < static_cast<std::size_t>(std::max(threads, 1)))
    per_thread.resize(static_cast<std::size_t>(std::max(threads, 1)));
  bool coincident = false;
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(|| : coincident)
  {
    // One range per thread of the team as it is (the ranges change the work, not the bits).
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t T = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t lo = N * t / T, hi = N * (t + 1) / T;
    PairScratch& s = per_thread[t];
    if (lo > 0) below_range(domain, potential, lists, a, lo, hi, s, coincident);
    sweep_range(domain, potential, lists, a, lo, hi, s, coincident);
  }
  return coincident;
}

}  // namespace erythro::aggregation
