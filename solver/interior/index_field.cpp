// The index field I(x) of the thesis (§II.4, eqs 26–27; docs/model.md §5). One update:
//  (1) I = 1 everywhere (only the nodes the previous update changed are reset);
//  (2) per cell, a band pass (band_pass.hpp): each edge visits the nodes of its capsule
//      |d| < w (or, for a smooth polygon, of its wedge between the bisector lines at its
//      ends), so the cost is O(markers), not O(grid); d = shortest signed distance to the
//      polygon's edges; |d| < w → band node, I = min(I, H(d)) (eq 26); free nodes next to
//      an inside band node (w ≤ −d < w + 1) → start candidates. The cells' band passes run
//      in parallel into per-cell lists (they read only their own polygon), then the lists
//      are merged into the field (merge_bands), each thread taking a block of rows and in
//      it the cells in order: the same bits and the same report as one cell after the
//      other, for any number of threads;
//  (3) per cell, the interior: flood_fill — a scan-line fill from the first candidate in
//      the 2w × 2w window of a marker (the thesis), replacing I = 1 by 0 and stopping at
//      band nodes, then from every candidate still free (completion); ray_casting — the
//      free nodes inside by the even–odd rule (fill.cpp, one cell after the other). Then a
//      leak check against the area.
// On one thread (or below kParallelCells cells) the band passes write into the field
// directly, one cell after the other. The nodes changed are kept per block of rows, so
// that the next update's reset and the τ rewrite run over the blocks in parallel.
#include "interior/index_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "interior/geometry.hpp"
#include "interior/marks.hpp"
#include "lattice/d2q9.hpp"

namespace erythro::interior {

using detail::kBand;
using detail::kFree;

std::string detail::marker_box(const geometry::Polygon& p) {
  const auto [x0, x1] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
  std::ostringstream s;
  s << "[" << *x0 << ", " << *x1 << "] x [" << *y0 << ", " << *y1 << "]";
  return s.str();
}

std::string_view to_string(Method m) {
  switch (m) {
    case Method::indexless: return "indexless";
    case Method::band_only: return "band_only";
    case Method::flood_fill: return "flood_fill";
    case Method::ray_casting: return "ray_casting";
  }
  return "?";
}

Method parse_method(std::string_view name) {
  for (Method m : {Method::indexless, Method::band_only, Method::flood_fill, Method::ray_casting})
    if (name == to_string(m)) return m;
  throw std::invalid_argument("unknown index-field method '" + std::string(name) +
                              "' (allowed: indexless, band_only, flood_fill, ray_casting)");
}

IndexField::IndexField(const geometry::Domain& domain, IndexFieldOptions options) : domain_(domain), options_(options) {
  if (domain.grid.nx <= 0 || domain.grid.ny <= 0)
    throw std::invalid_argument("IndexField: the grid must have at least one node per axis");
  if (!std::isfinite(options.band_half_width) || options.band_half_width <= 0.0)
    throw std::invalid_argument("IndexField: band_half_width must be positive and finite (lattice units), got " +
                                std::to_string(options.band_half_width));
  const std::size_t n = domain.grid.size();
  index_.assign(n, 1.0);
  mark_.assign(n, kFree);
  owner_.assign(n, -1);
  candidate_.assign(n, 0);
}

namespace {
// Threads for an update of n cells: across cells from kParallelCells cells on, unless
// already inside a parallel region (CellPhysics may run the update beside the force stage
// in a two-section region).
int threads_for(std::size_t n) {
#if defined(_OPENMP)
  if (static_cast<int>(n) >= IndexField::kParallelCells && !omp_in_parallel()) return std::max(1, omp_get_max_threads());
#endif
  (void)n;
  return 1;
}
int thread_id() {
#if defined(_OPENMP)
  return omp_get_thread_num();
#else
  return 0;
#endif
}
}  // namespace

const FillReport& IndexField::update(std::span<const geometry::Polygon> cells) {
  const std::size_t n = cells.size();
  const int threads = threads_for(n);
  // (1) I = 1 everywhere: undo the previous update (its nodes are kept in previous_changed_
  // for write_changed_relaxation_times).
  reset_changed(threads);
  std::swap(previous_changed_, changed_);
  set_blocks(threads);
  report_ = FillReport{};
  report_.cells = static_cast<int>(n);
  if (options_.method == Method::indexless) return report_;

  for (int c = 0; c < report_.cells; ++c) check_polygon(cells[static_cast<std::size_t>(c)], c);
  stats_.assign(n, CellStats{});
  if (work_.size() < n) work_.resize(n);  // kept between updates: no allocation once grown
  // (2) the bands of every cell first, so that each fill stops at every band.
  if (threads == 1) {
    bands_one_after_another(cells);
  } else {
    find_bands(cells, threads);
    merge_bands(threads);
  }
  for (int c = 0; c < report_.cells; ++c)
    if (stats_[static_cast<std::size_t>(c)].band.wedges) ++report_.wedge_cells;
  if (options_.method == Method::band_only) return report_;
  // (3) the interiors, one cell after the other, then the leak check.
  for (int c = 0; c < report_.cells; ++c) {
    const auto& p = cells[static_cast<std::size_t>(c)];
    auto& s = stats_[static_cast<std::size_t>(c)];
    if (options_.method == Method::flood_fill)
      flood_fill_cell(p, c, s);
    else
      ray_cast_cell(p, c, s);
    report_.interior_nodes += s.filled;
  }
  for (int c = 0; c < report_.cells; ++c)
    check_area(cells[static_cast<std::size_t>(c)], c, stats_[static_cast<std::size_t>(c)]);
  return report_;
}

void IndexField::set_blocks(int blocks) {
  if (changed_.lists.size() < static_cast<std::size_t>(blocks)) changed_.lists.resize(static_cast<std::size_t>(blocks));
  for (auto& l : changed_.lists) l.clear();
  changed_.used = blocks;
  if (blocks_ == blocks) return;
  blocks_ = blocks;
  block_of_row_.resize(static_cast<std::size_t>(domain_.grid.ny));
  for (int b = 0; b < blocks; ++b)
    for (std::size_t k = block_begin(b, blocks); k < block_begin(b + 1, blocks); k += static_cast<std::size_t>(domain_.grid.nx))
      block_of_row_[k / static_cast<std::size_t>(domain_.grid.nx)] = b;
}

std::size_t IndexField::block_begin(int block, int blocks) const {
  // Blocks of whole rows: block b of B holds rows [b·ny/B, (b + 1)·ny/B).
  const long rows = static_cast<long>(domain_.grid.ny) * block / blocks;
  return static_cast<std::size_t>(rows) * static_cast<std::size_t>(domain_.grid.nx);
}

template <class F>
void IndexField::for_each_changed(const ChangedNodes& changed, int block, int blocks, F&& f) const {
  if (changed.used == blocks) {  // list `block` holds exactly the block's nodes
    for (std::size_t k : changed.lists[static_cast<std::size_t>(block)]) f(k);
    return;
  }
  const std::size_t lo = block_begin(block, blocks), hi = block_begin(block + 1, blocks);
  for (int l = 0; l < changed.used; ++l)
    for (std::size_t k : changed.lists[static_cast<std::size_t>(l)])
      if (k >= lo && k < hi) f(k);
}

void IndexField::reset_changed(int threads) {
  std::uint8_t* mark = mark_.data();
  double* index = index_.data();
  int* owner = owner_.data();
  int* candidate = candidate_.data();
  // Each thread resets the nodes of its own block of rows.
#pragma omp parallel for schedule(static, 1) num_threads(threads) if (threads > 1)
  for (int t = 0; t < threads; ++t)
    for_each_changed(changed_, t, threads, [=](std::size_t k) {
      index[k] = 1.0;
      mark[k] = kFree;
      owner[k] = -1;
      candidate[k] = 0;
    });
}

detail::FieldWriter IndexField::writer(int cell, int block) {
  return detail::FieldWriter{index_.data(), mark_.data(), owner_.data(), candidate_.data(),
                             &changed_.lists[static_cast<std::size_t>(block)], nullptr, cell};
}

void IndexField::bands_one_after_another(std::span<const geometry::Polygon> cells) {
  if (band_scratch_.empty()) band_scratch_.resize(1);
  for (int c = 0; c < report_.cells; ++c) {
    CellWork& work = work_[static_cast<std::size_t>(c)];
    work.starts.clear();
    detail::FieldWriter out = writer(c, 0);
    out.starts = &work.starts;
    detail::find_band(cells[static_cast<std::size_t>(c)], domain_, options_.band_half_width, band_scratch_[0],
                      stats_[static_cast<std::size_t>(c)].band, out);
    report_.band_nodes += out.band_nodes;
    report_.overlap_nodes += out.overlap_nodes;
  }
}

void IndexField::find_bands(std::span<const geometry::Polygon> cells, int threads) {
  const std::size_t n = cells.size();
  if (band_scratch_.size() < static_cast<std::size_t>(threads)) band_scratch_.resize(static_cast<std::size_t>(threads));
  const double w = options_.band_half_width;
  // Each cell reads its polygon and writes its own lists with its thread's scratch; an
  // exception cannot leave the loop and is rethrown below for the first cell that threw.
#pragma omp parallel for schedule(dynamic) num_threads(threads)
  for (std::size_t c = 0; c < n; ++c) {
    CellWork& work = work_[c];
    work.error = nullptr;
    try {
      detail::find_band(cells[c], domain_, w, band_scratch_[static_cast<std::size_t>(thread_id())], stats_[c].band,
                        work.band);
      work.accepted.resize(work.band.node.size());
    } catch (...) {
      work.error = std::current_exception();
    }
  }
  for (std::size_t c = 0; c < n; ++c)
    if (work_[c].error) std::rethrow_exception(work_[c].error);
}

void IndexField::merge_bands(int threads) {
  const int n = report_.cells;
  // Each thread writes the nodes of its own block of rows, taking the cells in order: every
  // node sees the cells in the same order as one cell after the other, so the field, the
  // counts and each cell's candidates are those of the serial update.
  long band_nodes = 0, overlap_nodes = 0;
#pragma omp parallel num_threads(threads)
  {
#pragma omp for schedule(static, 1) reduction(+ : band_nodes, overlap_nodes)
    for (int t = 0; t < threads; ++t) {
      const std::size_t lo = block_begin(t, threads), hi = block_begin(t + 1, threads);
      for (int c = 0; c < n; ++c) {
        CellWork& work = work_[static_cast<std::size_t>(c)];
        const detail::CellBand& band = work.band;
        if (band.node.empty() || band.node_max < lo || band.node_min >= hi) continue;  // not in the block
        detail::FieldWriter out = writer(c, t);
        for (std::size_t v = 0; v < band.node.size(); ++v) {
          const std::size_t k = band.node[v];
          if (k < lo || k >= hi) continue;
          if (band.h[v] == detail::CellBand::kCandidate)
            work.accepted[v] = out.candidate_node(k);
          else
            out.band_node(k, band.h[v]);
        }
        band_nodes += out.band_nodes;
        overlap_nodes += out.overlap_nodes;
      }
    }
    // Each cell's start candidates, in band order.
#pragma omp for schedule(dynamic)
    for (int c = 0; c < n; ++c) {
      CellWork& work = work_[static_cast<std::size_t>(c)];
      work.starts.clear();
      for (std::size_t v = 0; v < work.band.node.size(); ++v)
        if (work.band.h[v] == detail::CellBand::kCandidate && work.accepted[v]) work.starts.push_back(work.band.node[v]);
    }
  }
  report_.band_nodes = band_nodes;
  report_.overlap_nodes = overlap_nodes;
}

void IndexField::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "index", index_);
  r.put(prefix + "mark", mark_);
  r.put(prefix + "owner", owner_);
  r.put(prefix + "candidate", candidate_);
  // The changed nodes in ascending order, once each: the same record for any number of threads.
  std::vector<std::size_t> changed;
  for (int l = 0; l < changed_.used; ++l)
    changed.insert(changed.end(), changed_.lists[static_cast<std::size_t>(l)].begin(),
                   changed_.lists[static_cast<std::size_t>(l)].end());
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  r.put(prefix + "dirty", changed);
}

void IndexField::restore_state(const StateRecord& r, const std::string& prefix) {
  const std::size_t n = index_.size();
  r.copy_to(prefix + "index", index_);
  auto ints = [&](const char* name, auto& out) {
    const std::vector<double>& v = r.get(prefix + name, n);
    std::transform(v.begin(), v.end(), out.begin(), [](double d) { return static_cast<std::decay_t<decltype(out[0])>>(d); });
  };
  ints("mark", mark_);
  ints("owner", owner_);
  ints("candidate", candidate_);
  changed_.lists.resize(std::max<std::size_t>(1, changed_.lists.size()));
  changed_.lists[0] = r.get_as<std::size_t>(prefix + "dirty");
  changed_.used = 1;  // of any rows: every block filters it (for_each_changed)
  blocks_ = 0;
  previous_changed_.used = 0;
}

void IndexField::check_polygon(const geometry::Polygon& p, int cell) const {
  if (p.size() < 3 || p.y.size() != p.x.size())
    throw InputError("interior: cell " + std::to_string(cell) + " has " + std::to_string(p.size()) +
                     " markers; a closed membrane polygon needs at least 3 (and as many y as x)");
  for (std::size_t m = 0; m < p.size(); ++m)
    if (!std::isfinite(p.x[m]) || !std::isfinite(p.y[m]))
      // A diverged membrane, not bad input: std::domain_error, as ImmersedCells reports it
      // (the simulation layer turns it into a divergence diagnosis).
      throw std::domain_error("interior: cell " + std::to_string(cell) + " marker " + std::to_string(m) +
                              " has a non-finite position (" + std::to_string(p.x[m]) + ", " +
                              std::to_string(p.y[m]) + ")");
}

void IndexField::check_area(const geometry::Polygon& p, int cell, const CellStats& stats) {
  // Σ(1 − I) of the cell against its enclosed area (clipped at walls). A valid fill agrees
  // to O(h²) (docs/verification-interior.md); the bound allows a band cut by a wall
  // (0.30 h per unit length, ∫₀^w (1 − H) = w(¼ − 1/π²)) and pinched bands with a margin.
  const double area = std::abs(stats.band.within_walls ? stats.band.signed_area : clipped_area(p, domain_));
  const double mismatch = std::abs(stats.band.band_area + static_cast<double>(stats.filled) - area);
  const double allowed = 0.5 * stats.band.perimeter + 4.0;
  if (mismatch > report_.max_area_mismatch) {
    report_.max_area_mismatch = mismatch;
    report_.max_area_mismatch_allowed = allowed;
  }
  if (mismatch <= allowed) return;
  std::ostringstream msg;
  msg << "interior: cell " << cell << " (markers in " << detail::marker_box(p) << "): the " << to_string(options_.method)
      << " interior plus band holds " << stats.band.band_area + static_cast<double>(stats.filled)
      << " h^2 but the polygon encloses " << area << " h^2 (mismatch " << mismatch << " > " << allowed
      << "): the membrane polygon self-intersects, overlaps itself or another cell, or the fill leaked";
  throw FillLeakError(msg.str());
}

void IndexField::write_relaxation_times(std::span<double> tau, double nu_in, double nu_ex) const {
  if (tau.size() != index_.size())
    throw std::invalid_argument("IndexField::write_relaxation_times: tau has " + std::to_string(tau.size()) +
                                " entries, the grid " + std::to_string(index_.size()));
  // Eq 27 with ν = μ/ρ0, ρ0 = 1: ν(x) = ν_in + (ν_ex − ν_in) I(x), τ = ½ + 3ν (c_s² = ⅓).
  for (std::size_t k = 0; k < tau.size(); ++k) tau[k] = d2q9::tau_of_viscosity(nu_in + (nu_ex - nu_in) * index_[k]);
}

void IndexField::write_changed_relaxation_times(std::span<double> tau, double nu_in, double nu_ex) const {
  if (tau.size() != index_.size())
    throw std::invalid_argument("IndexField::write_changed_relaxation_times: tau has " + std::to_string(tau.size()) +
                                " entries, the grid " + std::to_string(index_.size()));
  // Every node whose I differs from 1 now, or did after the previous update, is in one of
  // the two lists; every other node has I = 1 in both, so its τ is already ½ + 3ν_ex. Each
  // thread writes the nodes of its own block of rows (the blocks of the last update).
  const int threads = std::max(1, blocks_);
  double* t = tau.data();
  const double* index = index_.data();
#pragma omp parallel for schedule(static, 1) num_threads(threads) if (threads > 1)
  for (int b = 0; b < threads; ++b)
    for (const ChangedNodes* nodes : {&previous_changed_, &changed_})
      for_each_changed(*nodes, b, threads,
                       [&](std::size_t k) { t[k] = d2q9::tau_of_viscosity(nu_in + (nu_ex - nu_in) * index[k]); });
}

}  // namespace erythro::interior
