#pragma once
// The interior index field of the thesis (§II.4, eqs 26–27; docs/model.md §5): I = 1 outside
// every cell, 0 inside, and the smoothed step H(d) of eq 26 in a band |d| < 2h around each
// membrane, d the shortest signed distance to the membrane polygon (negative inside).
// The local viscosity follows eq 27: ν(x) = ν_in + (ν_ex − ν_in) I(x).
//
// Rules (docs/verification-interior.md, "How the index field works"):
//  - overlap: where bands/interiors of several cells overlap, the node keeps the MINIMUM I
//    (cytoplasm wins; a node inside any cell is interior);
//  - periodic wrap: polygons may be unwrapped past a periodic side; node indices wrap mod n.
//    Across a wall (non-periodic side) band nodes beyond the wall are dropped;
//  - start nodes: free nodes next to an inside band node, hence w ≤ −d < w + 1 (thesis:
//    2h < −d < 3h). The thesis's rule (the first start node in the 4h × 4h window of a
//    marker) is applied first; then every start node still free starts a further fill
//    (completion_starts): an interior pinched into several parts by the band, or one whose
//    start nodes all lie outside the windows (a flat membrane), is filled completely;
//  - small cells: when a cell has no start node at all (all of it within the band) its
//    interior is set by ray casting instead (which then finds nothing unless the interior
//    touches walls only) and the cell is counted in FillReport::fallback_cells;
//  - leaks: a fill that sets more nodes than the nodes of the cell's marker bounding box, or
//    an interior whose Σ(1 − I) differs from the enclosed (wall-clipped) area by more than
//    0.5·perimeter + 4 h², throws interior::FillLeakError naming the cell, its marker box
//    and where the fill was.
#include <array>
#include <cstdint>
#include <exception>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/error.hpp"
#include "common/state_record.hpp"
#include "geometry/domain.hpp"
#include "geometry/polygon.hpp"
#include "interior/band_pass.hpp"

namespace erythro::interior {

enum class Method { indexless, band_only, flood_fill, ray_casting };

// "indexless", "band_only", "flood_fill", "ray_casting".
std::string_view to_string(Method m);
// Inverse of to_string; throws std::invalid_argument listing the allowed names.
Method parse_method(std::string_view name);

struct IndexFieldOptions {
  Method method = Method::flood_fill;
  double band_half_width = 2.0;  // lattice units: band |d| < 2h, total width 4h (eq 26)
};

struct FillReport {
  int cells = 0;
  long interior_nodes = 0;  // nodes set to I = 0 by the fill (or ray casting)
  long band_nodes = 0;      // nodes within the band |d| < w of at least one cell (I = H(d), eq 26)
  int fallback_cells = 0;   // flood_fill: cells with no start node at all, filled by ray casting
  int fill_starts = 0;      // flood_fill: fills started from a start node in a marker's 2w × 2w window
  int completion_starts = 0;  // flood_fill: fills started by the completion pass (start nodes still
                              // free after the thesis fill: pinched-off parts, flat membranes)
  long overlap_nodes = 0;   // band nodes of more than one cell (the minimum I is kept)
  int wedge_cells = 0;      // cells whose band pass used per-edge wedges (smooth polygons; the
                            // others, e.g. few markers or sharp corners, use whole capsules)
  double max_area_mismatch = 0.0;  // max over cells of |Σ(1 − H) + interior − area| (lattice units²)
  double max_area_mismatch_allowed = 0.0;  // the leak bound at that cell (0.5·perimeter + 4)
};

// A flood fill escaped its cell (open or self-intersecting polygon, marker spacing
// above the band width, ...). An InputError: the cell configuration is invalid.
class FillLeakError : public InputError {
 public:
  using InputError::InputError;
};

// Eq 26: H(d) = ½[1 + d/w + (1/π) sin(π d/w)] for |d| < w (w = band half-width = 2h),
// 0 for d ≤ −w, 1 for d ≥ w.
double smoothed_heaviside(double d, double half_width = 2.0);

class IndexField {
 public:
  // From this many cells on, the cells' band passes run in parallel (OpenMP threads).
  static constexpr int kParallelCells = 2;

  IndexField(const geometry::Domain& domain, IndexFieldOptions options);

  // Rebuilds I from the cells' polygons in lattice units (counter-clockwise; coordinates
  // may be unwrapped past a periodic side). Throws FillLeakError naming the cell and
  // where when a fill leaks (never silently accepted), std::domain_error for a non-finite
  // marker (a diverged membrane) and InputError for a polygon of fewer than 3 markers.
  // From kParallelCells cells on, and when not called inside an OpenMP parallel region, the
  // band passes, their merge, the reset and the τ rewrite use the OpenMP threads (the fills
  // stay serial): the same bits, report and checkpoint record for any number of threads.
  const FillReport& update(std::span<const geometry::Polygon> cells);
  std::span<const double> values() const { return index_; }  // I per node, index y*nx + x
  const FillReport& report() const { return report_; }
  const IndexFieldOptions& options() const { return options_; }
  const geometry::Domain& domain() const { return domain_; }

  // Eq 27 with ν ∝ μ at ρ0 = 1: τ = ½ + 3[ν_in + (ν_ex − ν_in) I] per node (lattice units).
  void write_relaxation_times(std::span<double> tau, double nu_in, double nu_ex) const;
  // The same, but only on the nodes this update or the previous one changed: bitwise equal
  // to write_relaxation_times when `tau` holds what write_relaxation_times (or this) wrote
  // after the previous update (write the full field once, after the first update).
  // O(band + interior) instead of O(grid).
  void write_changed_relaxation_times(std::span<double> tau, double nu_in, double nu_ex) const;

  // Checkpoint (common/state_record.hpp), under `prefix`: I, the node marks and the nodes
  // the last update changed, which the next update resets and rewrites τ on (the rest is
  // scratch, rebuilt by every update).
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  struct CellStats {
    detail::BandStats band;  // band pass: Σ(1 − H), perimeter, signed area, walls (band_pass.hpp)
    long filled = 0;         // nodes set to 0 for this cell
  };
  // Per cell, kept between updates (no allocation once grown).
  struct CellWork {
    detail::CellBand band;               // band nodes and start candidates, when found in parallel
    std::vector<std::uint8_t> accepted;  // … per entry: a candidate no earlier cell had
    std::vector<std::size_t> starts;     // the cell's start candidates, in band order
    std::exception_ptr error;            // what its band pass threw
  };
  // Nodes one update changed, one list per block of rows (block_begin; `used` blocks).
  struct ChangedNodes {
    std::vector<std::vector<std::size_t>> lists;
    int used = 0;
  };

  void check_polygon(const geometry::Polygon& p, int cell) const;
  void set_blocks(int blocks);  // the blocks of rows of this update
  std::size_t block_begin(int block, int blocks) const;  // first node of a block of rows
  template <class F> void for_each_changed(const ChangedNodes& changed, int block, int blocks, F&& f) const;
  void reset_changed(int threads);
  detail::FieldWriter writer(int cell, int block);
  void bands_one_after_another(std::span<const geometry::Polygon> cells);
  void find_bands(std::span<const geometry::Polygon> cells, int threads);
  void merge_bands(int threads);
  void flood_fill_cell(const geometry::Polygon& p, int cell, CellStats& stats);
  void ray_cast_cell(const geometry::Polygon& p, int cell, CellStats& stats);
  void window_starts(const geometry::Polygon& p, int cell, CellStats& stats, long limit);
  void scan_line_fill(std::size_t start, int cell, CellStats& stats, long limit, const geometry::Polygon& p);
  void check_area(const geometry::Polygon& p, int cell, const CellStats& stats);

  geometry::Domain domain_;
  IndexFieldOptions options_;
  std::vector<double> index_;           // I per node
  std::vector<std::uint8_t> mark_;      // 0 free, 1 band (any cell), 2 filled
  std::vector<int> owner_;              // cell whose band last touched a node (−1: none)
  std::vector<int> candidate_;          // cell + 1 for which the node is a start candidate (0: none)
  std::vector<CellWork> work_;          // per cell
  std::vector<detail::BandScratch> band_scratch_;  // per thread
  int blocks_ = 0;                      // blocks of rows of this update (one per thread)
  std::vector<int> block_of_row_;       // … the block of each row
  ChangedNodes changed_;                // nodes changed by the last update (reset by the next)
  ChangedNodes previous_changed_;       // those of the update before
  std::vector<std::size_t> stack_;      // scan-line seeds
  std::vector<double> crossings_;       // ray-casting scratch
  std::vector<CellStats> stats_;
  FillReport report_;
};

}  // namespace erythro::interior
