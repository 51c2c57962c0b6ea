#pragma once
// Pair (Verlet) lists of the contact forces (docs/model.md §4, "Neighbour search";
// docs/verification-aggregation.md §4): for each marker, the markers of OTHER cells that were
// within r_c + skin when the lists were built, in ascending index order. Kept between steps
// and rebuilt once some marker has moved skin/2 (so that every pair now within r_c is in
// them) or the cells changed; built through a cell list of bins of side ≥ r_c + skin, O(N) in
// markers, in parallel over bins, the same lists for any thread count.
#include <cstddef>
#include <span>
#include <vector>

#include "aggregation/cell_list.hpp"
#include "aggregation/marker_view.hpp"
#include "aggregation/pair_terms.hpp"
#include "geometry/domain.hpp"

namespace erythro::aggregation {

class PairLists {
 public:
  // The skin: kSkin, at most a quarter of the cut-off, and small enough that r_c + skin
  // stays below half of every periodic side (the minimum image stays the only image). The skin
  // changes the work, never the sums (pairs beyond r_c add nothing). Half a lattice unit: with
  // the Morse cut-off (about 12 h) the lists' builds and their pairs beyond r_c then cost about
  // the same (docs/performance-coupled-step.md, "A thinner skin for the pair lists").
  static constexpr double kSkin = 0.5;
  PairLists(const geometry::Domain& domain, double cutoff);

  // Whether the lists still hold every pair within the cut-off for these markers.
  bool valid(const MarkerView& v) const;
  // Builds them for these markers (cell_of[m]: marker m's cell); `parallel`: over the threads.
  void build(const MarkerView& v, std::span<const std::size_t> cell_of, bool parallel);

  // CSR: the partners of marker m are list()[start()[m] … start()[m+1]).
  std::span<const std::size_t> start() const { return start_; }
  std::span<const std::size_t> list() const { return list_; }
  // upper()[m]: the first entry of marker m whose partner has a higher index (start()[m + 1]
  // if none): the entries upper()[m] … start()[m+1] hold the pairs (m, n > m), each pair once.
  std::span<const std::size_t> upper() const { return upper_; }
  // The same pairs (m, n > m) as runs of consecutive partners of one cell: marker m's runs are
  // run_start()[m] … run_start()[m+1] − 1, run r the partners run_first()[r] …
  // run_first()[r] + run_length()[r] − 1, in the order of the entries (pair_sweep.hpp reads
  // a run's partners as one contiguous stretch of the marker arrays).
  std::span<const std::size_t> run_start() const { return run_start_; }
  std::span<const std::size_t> run_first() const { return run_first_; }
  std::span<const std::size_t> run_length() const { return run_length_; }
  double skin() const { return skin_; }
  int bins_x() const { return nbx_; }
  int bins_y() const { return nby_; }
  std::size_t builds() const { return builds_; }
  // The pairs (m, n) the lists hold, each once (each pair is in both markers' lists).
  std::size_t pairs() const { return list_.size() / 2; }

 private:
  void build_runs(std::span<const std::size_t> cell_of);

  // A thread's buffers while building: the neighbouring bins, the bin's candidates (and their
  // merge), the separations.
  struct ThreadBuffers {
    std::vector<int> neighbours;
    std::vector<std::size_t> candidates, merged, found;  // found: its markers' partners, in build order
    PairScratch separations;
    std::size_t most_candidates = 0;  // the most candidates of one bin it met
  };
  // Kept from build to build, so that a rebuild allocates nothing once they have grown.
  detail::CellList bins_;
  std::vector<int> bin_of_, thread_of_;         // per marker: its bin, the thread that listed it
  std::vector<std::size_t> found_at_, length_;  // per marker: where its partners start in its thread's found, how many
  std::vector<ThreadBuffers> per_thread_;
  // The most candidates of one bin and the most entries of the lists in any build so far: each
  // thread's buffers get that room before a build (the bins go to the threads as they come).
  std::size_t most_candidates_ = 0, most_entries_ = 0;

  geometry::Domain domain_;
  double cutoff_ = 0.0, skin_ = 0.0;
  int nbx_ = 1, nby_ = 1;
  std::vector<std::size_t> start_, list_, upper_;
  std::vector<std::size_t> run_start_, run_first_, run_length_;
  std::vector<double> x_, y_;           // the positions they were built at
  std::vector<std::size_t> offsets_;    // the cells they were built for
  std::size_t builds_ = 0;
};

}  // namespace erythro::aggregation
