#include "aggregation/pair_sweep.hpp"

#include <omp.h>

#include <algorithm>

namespace erythro::aggregation {

namespace {

constexpr std::size_t kChunk = 64;  // visited markers whose entries are evaluated as one batch

// Into s: for the visits first … last − 1 of thread t, the entries of each marker m above it
// in the lists (upper()[m] … start()[m + 1] − 1; of another thread's marker only those whose
// partner is t's), each with the marker's and the partner's position and ℓ (pair_terms.hpp),
// the partner's index in s.partner and each visit's end in the batch in s.ends[i − first].
// Returns the entry count. kOneOwner: every marker is t's (one thread), no owner is looked up.
template <bool kOneOwner>
std::size_t gather(const SweepArrays& a, const PairLists& lists, const SweepOwners& owners, unsigned t,
                   std::span<const std::size_t> visits, std::size_t first, std::size_t last, PairScratch& s) {
  const std::span<const std::size_t> start = lists.start(), list = lists.list(), upper = lists.upper();
  const std::span<const unsigned> owner = owners.owner();
  std::size_t n = 0;
  for (std::size_t i = first; i < last; ++i) {
    const std::size_t m = kOneOwner ? i : visits[i];  // one owner visits every marker, in order
    if (kOneOwner || owner[m] == t) {
      n += start[m + 1] - upper[m];
    } else {
      for (std::size_t e = upper[m]; e < start[m + 1]; ++e) n += owner[list[e]] == t;
    }
  }
  s.resize(n);
  s.partner.resize(n);
  s.ends.resize(last - first);
  auto put = [&](std::size_t j, std::size_t m, std::size_t p) {
    s.partner[j] = p;
    s.cx[j] = a.x[p];
    s.cy[j] = a.y[p];
    s.cl[j] = a.ell[p];
    s.mx[j] = a.x[m];
    s.my[j] = a.y[m];
    s.ml[j] = a.ell[m];
  };
  std::size_t j = 0;
  for (std::size_t i = first; i < last; ++i) {
    const std::size_t m = kOneOwner ? i : visits[i];
    const std::size_t end = start[m + 1];
    if (kOneOwner || owner[m] == t) {
      for (std::size_t e = upper[m]; e < end; ++e, ++j) put(j, m, list[e]);
    } else {
      for (std::size_t e = upper[m]; e < end; ++e)
        if (owner[list[e]] == t) put(j++, m, list[e]);
    }
    s.ends[i - first] = j;
  }
  return n;
}

// Pair q's terms (entry j) to the partner p = s.partner[j]: X_p − X_m = −dx, ℓ_m in place of ℓ_p.
// Inlined by force: a call per pair cost the one-thread sweep about 5 % (perf).
[[gnu::always_inline]] inline void add_to_partner(const SweepArrays& a, const PairScratch& s, std::size_t q,
                                                  std::size_t j) {
  const std::size_t p = s.partner[j];
  a.S[p] += s.phi[q] * s.ml[j];
  a.px[p] -= s.w[q] * (-s.dx[j]);
  a.py[p] -= s.w[q] * (-s.dy[j]);
  a.rmin[p] = std::min(a.rmin[p], s.hr[q]);
  ++a.count[p];
}

// Thread t's visits in ascending order (pair_sweep.hpp): an own marker's pairs above it to the
// marker and to its partners of thread t; another thread's marker's pairs to its partners.
template <bool kOneOwner>
void sweep_owner(const geometry::Domain& d, const ContactPotential& potential, const PairLists& lists,
                 const SweepOwners& owners, const SweepArrays& a, unsigned t, PairScratch& s, bool& coincident) {
  // One owner visits every marker in order and looks nothing up (its owners may be empty).
  const std::span<const std::size_t> visits =
      kOneOwner ? std::span<const std::size_t>{} : owners.visits(static_cast<int>(t));
  const std::span<const unsigned> owner = owners.owner();
  const std::size_t count = kOneOwner ? a.x.size() : visits.size();
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t last = std::min(count, first + kChunk);
    const std::size_t n = gather<kOneOwner>(a, lists, owners, t, visits, first, last, s);
    if (n == 0) continue;  // no pair above these markers: their sums are complete
    const std::size_t k = evaluate_pairs(d, potential, n, s, coincident);
    std::size_t q = 0;
    for (std::size_t i = first; i < last; ++i) {
      const std::size_t end = s.ends[i - first];
      if (q >= k || s.hits[q] >= end) continue;
      const std::size_t m = kOneOwner ? i : visits[i];
      if (!kOneOwner && owner[m] != t) {
        for (; q < k && s.hits[q] < end; ++q)
          if (s.on[q]) add_to_partner(a, s, q, s.hits[q]);
        continue;
      }
      PairSums acc{a.S[m], a.px[m], a.py[m], a.rmin[m], a.count[m]};
      for (; q < k && s.hits[q] < end; ++q) {
        if (!s.on[q]) continue;
        const std::size_t j = s.hits[q];
        acc.s += s.phi[q] * s.cl[j];  // as marker_sums
        acc.fx -= s.w[q] * s.dx[j];
        acc.fy -= s.w[q] * s.dy[j];
        acc.rmin = std::min(acc.rmin, s.hr[q]);
        ++acc.k;
        if (kOneOwner || owner[s.partner[j]] == t) add_to_partner(a, s, q, j);  // else its thread adds it
      }
      a.S[m] = acc.s;
      a.px[m] = acc.fx;
      a.py[m] = acc.fy;
      a.rmin[m] = acc.rmin;
      a.count[m] = acc.k;
    }
  }
}

}  // namespace

bool sweep_pair_lists(const geometry::Domain& domain, const ContactPotential& potential, const PairLists& lists,
                      const SweepOwners& owners, int threads, const SweepArrays& a,
                      std::vector<PairScratch>& per_thread) {
  threads = std::max(threads, 1);
  if (per_thread.size() < static_cast<std::size_t>(threads)) per_thread.resize(static_cast<std::size_t>(threads));
  bool coincident = false;
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(|| : coincident)
  {
    // Each owner's sweep writes only its own markers' sums: a team smaller than asked for
    // takes the owners in turns (the owners change the work, not the bits).
    const int i = omp_get_thread_num(), team = omp_get_num_threads();
    PairScratch& s = per_thread[static_cast<std::size_t>(i)];
    if (threads == 1) sweep_owner<true>(domain, potential, lists, owners, a, 0, s, coincident);
    else
      for (int t = i; t < threads; t += team)
        sweep_owner<false>(domain, potential, lists, owners, a, static_cast<unsigned>(t), s, coincident);
  }
  return coincident;
}

}  // namespace erythro::aggregation
