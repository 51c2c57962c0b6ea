#pragma once
// Every marker's pair sums over the pair lists (docs/model.md §4, §4b; cell_contacts.hpp), each
// pair's terms evaluated once where the threads allow it and added to both of its markers.
//
// Every cell belongs to one thread (sweep_owners.hpp). A thread visits in ascending order its
// own markers and the other threads' markers with a partner of its own above them. An own
// marker is swept over all its partners above it: each pair's terms to the marker (whose sums
// hold its partners below it by then) and, for a partner of the same thread, to the partner as
// well. Another thread's marker is swept over its partners of this thread above it, their terms
// to those partners alone (its own thread adds them to it). So every marker adds its partners in
// ascending order, as a marker summing its own list would, whoever evaluates them. Each pair's
// terms are the same bits seen from either end (Φ, Φ', r and w are symmetric in (m, n) and
// X_n − X_m = −(X_m − X_n) exactly: pair_terms.hpp), so the sums are the same bits for any
// owners and any thread count. On one thread every pair is evaluated once; on T threads the
// pairs between threads twice.
//
// A marker's partners above it come as runs of consecutive markers of one cell (pair_lists.hpp):
// the separations, the pair law and the partners' shares are vector loops over a run's stretch
// of the marker arrays (a partner appears once per run, so its lanes never collide); only the
// marker's own sums, which must add its partners one after another, are scalar (two markers'
// sums side by side).
#include <cstddef>
#include <span>
#include <vector>

#include "aggregation/contact_law.hpp"
#include "aggregation/pair_lists.hpp"
#include "aggregation/pair_terms.hpp"
#include "aggregation/sweep_owners.hpp"
#include "geometry/domain.hpp"

namespace erythro::aggregation {

// The per-marker arrays of the sweep: what it reads (positions and ℓ_m) and the sums it adds
// to (S_m, the pair force, the closest partner, the pair count), which start at 0 (rmin at +∞).
struct SweepArrays {
  std::span<const double> x, y, ell;
  std::span<double> S, px, py, rmin;
  std::span<std::size_t> count;
};

// One thread's buffers for a batch of visited markers: per evaluated partner (in run order) the
// separation X_m − X_n, r², r, ℓ_m, ℓ_n, Φ, Φ', w, the marker's terms and whether the pair
// interacts; per run its marker, first partner, length, place in the batch and whether its
// partners are this thread's. They grow once and are reused.
struct SweepScratch {
  struct Run {
    std::size_t marker, first, length, at;
    bool to_partners;
  };
  struct OwnMarker {
    std::size_t m, q0, q1;  // an own marker and its entries q0 … q1 − 1
  };
  std::vector<double> dx, dy, r2, hr, ml, cl, phi, dphi, w;
  // The marker's terms: Φ ℓ_n, w dx, w dy, r; where the pair does not interact, no-ops (tr = +∞,
  // by which add_to_partners tells such a pair).
  std::vector<double> ts, tx, ty, tr;
  std::vector<unsigned char> on;
  std::vector<Run> runs;
  std::vector<std::size_t> run_ends;  // per visited marker of the batch: the end of its runs
  std::vector<OwnMarker> own;         // the batch's own markers with entries, in order
  // Room for n entries: the buffers only grow (a batch writes every entry it reads, so what an
  // earlier batch left beyond its own entries is never read).
  void hold(std::size_t n);
};

// The sums of every marker over the lists on `threads` threads: on one, in marker order (the
// owners are not read); on more, by the owners (made for these lists and this thread count).
// Returns whether two markers of different cells sit on one point (a pair at r = 0, which has
// no direction).
bool sweep_pair_lists(const geometry::Domain& domain, const ContactPotential& potential, const PairLists& lists,
                      const SweepOwners& owners, int threads, const SweepArrays& a,
                      std::vector<SweepScratch>& per_thread);

}  // namespace erythro::aggregation
