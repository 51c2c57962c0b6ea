#pragma once
// Every marker's pair sums over the pair lists (docs/model.md §4, §4b; cell_contacts.hpp), each
// pair's terms evaluated once where the threads allow it and added to both of its markers.
//
// The markers are split into one contiguous range per thread. A thread first adds to each of
// its markers the pairs with partners below its range (evaluated for that marker alone), then
// sweeps its markers in ascending order over their partners above them: a pair inside the
// range goes to both markers, a pair reaching above the range to the swept marker alone (the
// thread above adds it to its own). So every marker adds its partners in ascending order, as a
// marker summing its own list would: below its range, then inside it (from the sweeps of the
// markers below it), then above it (its own sweep). Each pair's terms are the same bits seen
// from either end (Φ, Φ', r and w are symmetric in (m, n) and X_n − X_m = −(X_m − X_n)
// exactly: pair_terms.hpp), so the sums are the same bits for any thread count. On one thread
// every pair is evaluated once; on T threads the pairs between ranges twice.
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

// The sums of every marker over the lists; `threads` ranges (1: one thread). Returns whether
// two markers of different cells sit on one point (a pair at r = 0, which has no direction).
bool sweep_pair_lists(const geometry::Domain& domain, const ContactPotential& potential, const PairLists& lists,
                      const SweepArrays& a, int threads, std::vector<PairScratch>& per_thread);

}  // namespace erythro::aggregation
