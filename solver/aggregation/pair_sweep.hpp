#pragma once
// Every marker's pair sums over the pair lists (docs/model.md §4, §4b; cell_contacts.hpp), each
// pair's terms evaluated once and added to both of its markers, every marker adding its partners
// in ascending order (below it, then above it), so the sums are the same bits for any thread
// count. Each pair's terms are the same bits seen from either end (Φ, Φ', r and w are symmetric
// in (m, n) and X_n − X_m = −(X_m − X_n) exactly: pair_terms.hpp).
//
// One thread sweeps the markers in ascending order over their partners above them and adds each
// pair to both markers at once: a marker's partners below it have been added by their own sweeps
// by the time it is swept.
//
// Several threads work in two phases. First each thread evaluates the pairs of its share of the
// owners (a pair belongs to its lower marker; the shares hold equal numbers of pairs) and keeps
// each pair's terms at its list entry (PairTermStore). Then, after a barrier, each thread sums
// its share of the markers: a marker reads its pairs with the partners below it through
// PairLists::mirror() and those above it at its own entries. No pair is evaluated twice and no
// marker is written by two threads.
#include <cstddef>
#include <span>
#include <vector>

#include "aggregation/contact_law.hpp"
#include "aggregation/pair_lists.hpp"
#include "aggregation/pair_terms.hpp"
#include "geometry/domain.hpp"

namespace erythro::aggregation {

// The per-marker arrays of the sweep: what it reads (positions and ℓ_m) and the sums it adds
// to (S_m, the pair force, the closest partner, the pair count), which start at 0 (rmin at +∞).
struct SweepArrays {
  std::span<const double> x, y, ell;
  std::span<double> S, px, py, rmin;
  std::span<std::size_t> count;
};

// The terms of every evaluated pair at its entry of the lists (the two-phase sweep): whether it
// interacts (within the cut-off and on), Φ, w, X_m − X_n of its owner m and r.
struct PairTermStore {
  std::vector<unsigned char> on;
  std::vector<double> phi, w, dx, dy, r;
  void resize(std::size_t entries);
};

// The sums of every marker over the lists, on `threads` threads (1: the one-thread sweep).
// Returns whether two markers of different cells sit on one point (a pair at r = 0, which has no
// direction).
bool sweep_pair_lists(const geometry::Domain& domain, const ContactPotential& potential, const PairLists& lists,
                      const SweepArrays& a, int threads, std::vector<PairScratch>& per_thread,
                      PairTermStore& terms);

}  // namespace erythro::aggregation
