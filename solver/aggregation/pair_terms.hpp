#pragma once
// The pair terms of the contact forces (docs/model.md §4, §4b; cell_contacts.hpp), computed
// for many (marker, candidate) pairs at once in vector loops: each lane does the IEEE
// operations a single pair would, so the result is the same bit for bit however the pairs
// are grouped. Three passes over a batch held in a PairScratch:
//   1. separations X_m − X_n (minimum image) and r²                     (pair_separations)
//   2. the pairs with 0 < r² < r_c², in batch order                    (pairs_within)
//   3. r, the pair law Φ, Φ' and the weight w = Φ'(ℓ_m ℓ_n)/r           (pair_weights)
// and then one marker's sums over its pairs in batch order             (marker_sums).
// Lattice units; used by cell_contacts.cpp (pair lists, brute force) and pair_lists.cpp
// (building the lists).
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "aggregation/contact_law.hpp"
#include "geometry/domain.hpp"

namespace erythro::aggregation {

// One batch: for candidate i its marker m's position and ℓ_m (mx, my, ml) and its own (cx,
// cy, cl); the passes fill the rest. Buffers grow once and are reused.
struct PairScratch {
  std::vector<double> mx, my, ml, cx, cy, cl;  // per candidate: m's position and ℓ_m, the candidate's
  std::vector<double> dx, dy, r2;              // per candidate: X_m − X_n, r²
  std::vector<std::size_t> hits;               // the candidates within the cut-off, in order
  std::vector<double> hr, phi, dphi, w;        // per pair within the cut-off: r, Φ, Φ', w
  std::vector<unsigned char> on;               // per pair: whether it interacts (ContactPotential)
  void hold(std::size_t n);                    // room for n candidates (the passes read only what they wrote)
};

// A marker's sums over its pairs (cell_contacts.hpp): S_m = Σ Φ ℓ_n, the pair force
// −Σ Φ' ℓ_m ℓ_n (X_m − X_n)/r, the closest partner and the pair count.
struct PairSums {
  double s = 0.0, fx = 0.0, fy = 0.0;
  double rmin = std::numeric_limits<double>::infinity();
  std::size_t k = 0;
};

// Minimum-image difference on a periodic axis of length L, inv = 1/L. Symmetric:
// image(−d) = −image(d) bit for bit (−d·inv = −(d·inv) exactly, and round-to-nearest-even
// of nearbyint is odd-symmetric).
inline double image(double d, bool periodic, double L, double inv) {
  return periodic ? d - L * std::nearbyint(d * inv) : d;
}

// The weight w = Φ'(r) ℓ_m ℓ_n / r of a pair (its force is −w (X_m − X_n)): ℓ_m ℓ_n first, so
// the same bits from either end. The one place the formula is written (pair_weights, and the
// pair sweep's batches, pair_sweep.cpp).
inline double pair_weight(double dphi, double ell_m, double ell_n, double r) { return dphi * (ell_m * ell_n) / r; }

// Pass 1 over candidates 0 … n − 1: s.dx, s.dy, s.r2 from s.mx, s.my, s.cx, s.cy.
void pair_separations(const geometry::Domain& d, std::size_t n, PairScratch& s);
// Pass 2: the candidates with 0 < r² < rc2 into s.hits, in order; returns their count.
// `coincident` is set when some r² is 0 (two markers of different cells on one point).
std::size_t pairs_within(double rc2, std::size_t n, PairScratch& s, bool& coincident);
// Pass 3 over the k pairs of s.hits: s.hr, s.phi, s.dphi, s.on and s.w.
void pair_weights(const ContactPotential& potential, std::size_t k, PairScratch& s);
// Passes 1–3 over the n candidates of s with the potential's cut-off; returns the pairs within
// it (`coincident` as pairs_within).
std::size_t evaluate_pairs(const geometry::Domain& d, const ContactPotential& potential, std::size_t n,
                           PairScratch& s, bool& coincident);
// One marker's sums over the pairs q … whose candidate index is below `end`, in order; q is
// left at the next marker's first pair.
PairSums marker_sums(const PairScratch& s, std::size_t& q, std::size_t k, std::size_t end);

}  // namespace erythro::aggregation
