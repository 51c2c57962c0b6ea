#include "aggregation/pair_sweep.hpp"

#include <omp.h>

#include <algorithm>

namespace erythro::aggregation {

namespace {

constexpr std::size_t kChunk = 64;  // markers whose entries are evaluated as one batch

// Into s: for markers first … last − 1 their pairs above them (entries upper(m) … start(m + 1) − 1),
// each with the marker's and the partner's position and ℓ (pair_terms.hpp), the entry's index in
// s.entry and each marker's end in the batch in s.ends[m − first]. Returns the entry count.
std::size_t gather(const SweepArrays& a, const PairLists& lists, std::size_t first, std::size_t last,
                   PairScratch& s) {
  const std::span<const std::size_t> start = lists.start(), list = lists.list(), upper = lists.upper();
  std::size_t n = 0;
  for (std::size_t m = first; m < last; ++m) n += start[m + 1] - upper[m];
  s.resize(n);
  s.entry.resize(n);
  s.ends.resize(last - first);
  std::size_t i = 0;
  for (std::size_t m = first; m < last; ++m) {
    for (std::size_t e = upper[m]; e < start[m + 1]; ++e, ++i) {
      const std::size_t p = list[e];
      s.entry[i] = e;
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

// The one-thread sweep: markers in ascending order over their partners above them, each pair's
// terms to the swept marker (whose sums hold its partners below it by then) and to the partner
// (X_p − X_m = −dx; ℓ_m in place of ℓ_p).
void sweep_all(const geometry::Domain& d, const ContactPotential& potential, const PairLists& lists,
               const SweepArrays& a, PairScratch& s, bool& coincident) {
  const std::span<const std::size_t> list = lists.list();
  const std::size_t N = a.x.size();
  for (std::size_t first = 0; first < N; first += kChunk) {
    const std::size_t last = std::min(N, first + kChunk);
    const std::size_t n = gather(a, lists, first, last, s);
    if (n == 0) continue;  // no pair above these markers: their sums are complete
    const std::size_t k = evaluate_pairs(d, potential, n, s, coincident);
    std::size_t q = 0;
    for (std::size_t m = first; m < last; ++m) {
      const std::size_t end = s.ends[m - first];
      if (q >= k || s.hits[q] >= end) continue;
      PairSums acc{a.S[m], a.px[m], a.py[m], a.rmin[m], a.count[m]};
      for (; q < k && s.hits[q] < end; ++q) {
        if (!s.on[q]) continue;
        const std::size_t j = s.hits[q], p = list[s.entry[j]];
        acc.s += s.phi[q] * s.cl[j];  // as marker_sums
        acc.fx -= s.w[q] * s.dx[j];
        acc.fy -= s.w[q] * s.dy[j];
        acc.rmin = std::min(acc.rmin, s.hr[q]);
        ++acc.k;
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

// Phase 1 of several threads: the pairs owned by markers lo … hi − 1 (their upper entries),
// each evaluated once, its terms kept at its entry.
void evaluate_owned(const geometry::Domain& d, const ContactPotential& potential, const PairLists& lists,
                    const SweepArrays& a, std::size_t lo, std::size_t hi, PairScratch& s, PairTermStore& t,
                    bool& coincident) {
  for (std::size_t first = lo; first < hi; first += kChunk) {
    const std::size_t last = std::min(hi, first + kChunk);
    const std::size_t n = gather(a, lists, first, last, s);
    if (n == 0) continue;
    const std::size_t k = evaluate_pairs(d, potential, n, s, coincident);
    for (std::size_t i = 0; i < n; ++i) t.on[s.entry[i]] = 0;
    for (std::size_t q = 0; q < k; ++q) {
      if (!s.on[q]) continue;
      const std::size_t j = s.hits[q], e = s.entry[j];
      t.on[e] = 1;
      t.phi[e] = s.phi[q];
      t.w[e] = s.w[q];
      t.dx[e] = s.dx[j];
      t.dy[e] = s.dy[j];
      t.r[e] = s.hr[q];
    }
  }
}

// Phase 2: the sums of markers lo … hi − 1 from the kept terms, each marker's partners in
// ascending order: those below it at their mirror entries (seen from the partner: X_m − X_p =
// −dx, ℓ_p), then those above it at its own entries. The same additions as sweep_all's.
void sum_kept(const PairLists& lists, const SweepArrays& a, std::size_t lo, std::size_t hi, const PairTermStore& t) {
  const std::span<const std::size_t> start = lists.start(), list = lists.list(), upper = lists.upper(),
                                     mirror = lists.mirror();
  for (std::size_t m = lo; m < hi; ++m) {
    PairSums acc{a.S[m], a.px[m], a.py[m], a.rmin[m], a.count[m]};
    for (std::size_t e = start[m]; e < upper[m]; ++e) {
      const std::size_t f = mirror[e];
      if (!t.on[f]) continue;
      acc.s += t.phi[f] * a.ell[list[e]];
      acc.fx -= t.w[f] * (-t.dx[f]);
      acc.fy -= t.w[f] * (-t.dy[f]);
      acc.rmin = std::min(acc.rmin, t.r[f]);
      ++acc.k;
    }
    for (std::size_t e = upper[m]; e < start[m + 1]; ++e) {
      if (!t.on[e]) continue;
      acc.s += t.phi[e] * a.ell[list[e]];
      acc.fx -= t.w[e] * t.dx[e];
      acc.fy -= t.w[e] * t.dy[e];
      acc.rmin = std::min(acc.rmin, t.r[e]);
      ++acc.k;
    }
    store(a, m, acc);
  }
}

// The first marker of thread t's share of T when marker m weighs prefix[m + 1] − prefix[m] (the
// shares cover all markers: share T starts at the end).
std::size_t share_start(std::span<const std::size_t> prefix, std::size_t t, std::size_t T) {
  if (t >= T) return prefix.size() - 1;
  const std::size_t goal = prefix.back() / T * t + prefix.back() % T * t / T;  // total·t/T without overflow
  return static_cast<std::size_t>(std::lower_bound(prefix.begin(), prefix.end() - 1, goal) - prefix.begin());
}

}  // namespace

void PairTermStore::resize(std::size_t entries) {
  on.resize(entries);
  for (auto* v : {&phi, &w, &dx, &dy, &r}) v->resize(entries);
}

bool sweep_pair_lists(const geometry::Domain& domain, const ContactPotential& potential, const PairLists& lists,
                      const SweepArrays& a, int threads, std::vector<PairScratch>& per_thread,
                      PairTermStore& terms) {
  const std::size_t T = static_cast<std::size_t>(std::max(threads, 1));
  if (per_thread.size() < T) per_thread.resize(T);
  bool coincident = false;
  if (T == 1) {
    sweep_all(domain, potential, lists, a, per_thread[0], coincident);
    return coincident;
  }
  terms.resize(lists.list().size());
#pragma omp parallel num_threads(threads) reduction(|| : coincident)
  {
    // Shares of the team as it is (the shares change the work, not the bits).
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t n = static_cast<std::size_t>(omp_get_num_threads());
    const std::span<const std::size_t> owned = lists.owned_before(), entries = lists.start();
    evaluate_owned(domain, potential, lists, a, share_start(owned, t, n), share_start(owned, t + 1, n),
                   per_thread[t], terms, coincident);
#pragma omp barrier
    sum_kept(lists, a, share_start(entries, t, n), share_start(entries, t + 1, n), terms);
  }
  return coincident;
}

}  // namespace erythro::aggregation
