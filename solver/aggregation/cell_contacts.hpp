#pragma once
// The forces between the membranes of DIFFERENT cells (docs/model.md §4, §4b): Morse
// aggregation, short-range repulsion, or both (contact_law.hpp), as a discrete energy and
// its exact negative gradient. Lattice units, per unit depth.
//
// Each marker m carries the membrane length ℓ_m = (|X_m − X_{m−1}| + |X_{m+1} − X_m|)/2
// (half its two adjacent edges, CURRENT lengths). The energy is the pair sum over
// markers of different cells within the cut-off (Φ = Φ_s + Φ_r, contact_law.hpp),
// plus, with wall repulsion, each marker's energy against the walls (eq 4.13):
//
//   E = Σ_{m<n, cell(m)≠cell(n)} Φ(r_mn) ℓ_m ℓ_n + Σ_m W(s_m) ℓ_m
//     = Σ_m ℓ_m (½ S_m + W_m),   S_m = Σ_n Φ(r_mn) ℓ_n,
//
// a quadrature of the continuum ∮∮ Φ(|X(s) − Y(t)|) ds dt. Its gradient has two parts:
//
//   pair  F_m −= Σ_n Φ'(r_mn) ℓ_m ℓ_n (X_m − X_n)/r_mn               (central, ± per pair)
//         F_m −= W'(s_m) ℓ_m ∂s_m/∂X_m                                 (wall: along its normal)
//   edge  ∂E/∂ℓ_m = S_m + W_m and ℓ_m = (L_{m−1} + L_m)/2, so edge e (markers e → e+1) carries
//         T_e = (S_e + W_e + S_{e+1} + W_{e+1})/2 and  F_e += T_e u_e,  F_{e+1} −= T_e u_e
//
// The pair part and the edge part are central forces between two markers, so without
// walls the total force and torque on the markers vanish to round-off; the edge part
// also has zero net force and torque on each cell. Separations use the minimum image on
// periodic axes (markers may be unwrapped: ImmersedCells shifts whole cells only), so the cut-off must be < half the
// period (checked). Within a cell the edges use the plain coordinate differences.
//
// Neighbour search: pair (Verlet) lists (pair_lists.hpp). Each marker keeps the markers of other cells
// that were within r_c + skin when the lists were built, in ASCENDING index order; the
// lists are kept between calls and rebuilt (through a cell list of bins of side
// ≥ r_c + skin, O(N) in markers) once some marker has moved skin/2 since, or the cells
// changed. Until then every pair within r_c is in them (two markers close by less than
// the skin). A marker sums over its list in that order, dropping the pairs beyond r_c:
// exactly the pairs and the order of the brute-force loop over all n
// (add_forces_brute_force, which tests every pair with the same arithmetic), so the two
// give BITWISE identical forces and energies whenever the lists were built (asserted in
// verification.aggregation_forces and the unit tests with moving markers). Each pair term
// uses exactly antisymmetric arithmetic (X_m − X_n = −(X_n − X_m) in IEEE, odd-symmetric
// minimum image; the weight Φ'(r)(ℓ_mℓ_n)/r is symmetric), so the force marker n gets
// from m is bit for bit minus the force m gets from n; only their accumulation into
// different sums rounds. The separations, the pair law and the weights run as vector
// loops over many pairs at once (pair_terms.hpp) (the exponential is numeric::exp_portable, the same bits
// in every lane); each marker writes only its own sums: parallel over markers (OpenMP,
// from kParallelMarkers markers on), deterministic for any thread count.
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "aggregation/contact_law.hpp"
#include "aggregation/pair_lists.hpp"
#include "aggregation/pair_sweep.hpp"
#include "aggregation/pair_terms.hpp"
#include "aggregation/sweep_owners.hpp"
#include "common/state_record.hpp"
#include "geometry/domain.hpp"

namespace erythro::membrane {
class ImmersedCells;
}

namespace erythro::aggregation {

namespace detail {
// What a call of add_forces needs beyond its inputs, kept so that a step allocates nothing
// once the buffers have grown: the per-marker arrays and each thread's scratch.
struct ContactWorkspace {
  std::vector<std::size_t> cell_of, count, offsets;
  std::vector<double> edge, ell, S, px, py, rmin, W;
  std::vector<double> cell_closest;     // per cell: its markers' closest partner (the statistics)
  std::vector<std::size_t> cell_pairs;  // per cell: its markers' partners within the cut-off
  std::vector<SweepScratch> per_thread;
  SweepOwners owners;  // remade with the pair lists, or for another thread count
};
}  // namespace detail

struct ContactStats {
  std::size_t pairs = 0;   // marker pairs of different cells within the cut-off (each once)
  double energy = 0.0;     // E (lattice energy per depth), walls included
  double max_force = 0.0;  // largest |F_m| of the contact force
  std::size_t wall_markers = 0;  // markers within the repulsion range of a wall
  // The closest two markers of different cells, and the closest marker to a wall, among
  // those within the cut-off (+inf when none is).
  double min_pair_distance = std::numeric_limits<double>::infinity();
  double min_wall_distance = std::numeric_limits<double>::infinity();
};

class CellContacts {
 public:
  // Throws std::invalid_argument on bad parameters, or a cut-off ≥ half a periodic side.
  CellContacts(const geometry::Domain& domain, const ContactLaw& law);
  // Morse aggregation alone.
  CellContacts(const geometry::Domain& domain, const MorseParameters& morse)
      : CellContacts(domain, ContactLaw{morse, std::nullopt}) {}

  // ADDS the contact forces to cells.marker_fx()/marker_fy() (call after
  // cells.compute_forces(), which overwrites them) and returns the statistics.
  ContactStats add_forces(membrane::ImmersedCells& cells);
  double energy(const membrane::ImmersedCells& cells) const;

  // The same on raw arrays (fx, fy sized as x).
  ContactStats add_forces(const MarkerView& markers, std::span<double> fx, std::span<double> fy);
  double energy(const MarkerView& markers) const;

  // |F_m| of the contact force of the last add_forces call, per marker.
  std::span<const double> force_magnitude() const { return magnitude_; }
  // Checkpoint (common/state_record.hpp): those magnitudes, the one thing kept between
  // steps (read by the contact diagnostics of the state after a step).
  void save_state(StateRecord& record, const std::string& prefix) const { record.put(prefix + "force_magnitude", magnitude_); }
  void restore_state(const StateRecord& record, const std::string& prefix) {
    magnitude_ = record.get(prefix + "force_magnitude");
  }

  const ContactLaw& law() const { return potential_.law(); }
  double cutoff() const { return potential_.cutoff(); }
  const geometry::Domain& domain() const { return domain_; }
  // Below this many markers a parallel region costs more than it saves (a doublet of
  // 2 × 184 markers stays on one thread), and add_forces runs on one thread. Eight cells
  // (1 472 markers) already gain on two threads (docs/performance-coupled-step.md, "Threads from 512
  // markers").
  static constexpr std::size_t kParallelMarkers = 512;
  static bool threads_forces(std::size_t markers) { return markers >= kParallelMarkers; }
  // The pair lists (pair_lists.hpp): their skin, the bins per axis of the cell list that
  // builds them, how many times they were built (tests, the benchmark).
  double skin() const { return lists_.skin(); }
  int bins_x() const { return lists_.bins_x(); }
  int bins_y() const { return lists_.bins_y(); }
  std::size_t pair_list_builds() const { return lists_.builds(); }
  // The work of the pair sweep: the pairs of the lists, summed over the add_forces calls so far
  // (each pair once; on T threads the sweep evaluates the pairs between the threads' slabs twice,
  // sweep_owners.hpp). The benchmark's cost per pair (docs/performance-coupled-step.md, "The work
  // per cell behind the cost per cell").
  std::size_t listed_pairs_swept() const { return listed_pairs_swept_; }

 private:
  template <class E>
  void pair_sums_all(E& eng);

  geometry::Domain domain_;
  ContactPotential potential_;
  PairLists lists_;
  std::vector<double> magnitude_;
  detail::ContactWorkspace work_;
  std::size_t listed_pairs_swept_ = 0;
};

// Relative contact area of cell c (thesis §III.2, after Bagchi et al.): the fraction of
// its markers whose contact force (Morse, and repulsion when on) exceeds `fraction`
// (0.012) of the largest one over all markers. 0 when no marker feels a force.
double relative_contact_area(std::span<const double> force_magnitude, std::span<const std::size_t> offsets, int c,
                             double fraction = 0.012);

// The offsets array of an ImmersedCells (cells + 1 entries).
std::vector<std::size_t> cell_offsets(const membrane::ImmersedCells& cells);

// Brute-force O(N²) reference: every marker against every marker of the other cells,
// same arithmetic and summation order as CellContacts (bitwise the same result).
ContactStats add_forces_brute_force(const geometry::Domain& domain, const ContactLaw& law, const MarkerView& markers,
                                    std::span<double> fx, std::span<double> fy);
double energy_brute_force(const geometry::Domain& domain, const ContactLaw& law, const MarkerView& markers);

}  // namespace erythro::aggregation
