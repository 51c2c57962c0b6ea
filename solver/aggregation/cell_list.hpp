#pragma once
// The cell list (bins) through which the pair lists find each marker's neighbours
// (pair_lists.hpp; docs/model.md §4, "Neighbour search"): bins of side ≥ r_c + skin, each
// marker in one bin, the markers of a bin ascending. Its arrays are kept by the pair lists and
// reused from build to build.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "aggregation/marker_view.hpp"
#include "geometry/domain.hpp"

namespace erythro::aggregation::detail {

// Cell list over the domain: nb bins per axis of side n/nb ≥ r_c + skin (at least 1 bin).
struct CellList {
  static constexpr std::size_t kMixed = SIZE_MAX;
  int nbx = 1, nby = 1;
  std::vector<std::size_t> start, items;  // markers of bin b: items[start[b] … start[b+1]), ascending
  std::vector<std::size_t> owner;         // per bin: the one cell of its markers, kMixed, or none (empty)
  std::vector<std::size_t> fill;          // per bin: the next free place in items while building

  static int bins(int n, double rc) {
    // floor(n / r_c), with a 1e-9 margin so round-off in the bin index can never put two
    // markers closer than r_c two bins apart.
    return std::max(1, static_cast<int>(std::floor(double(n) / (rc * (1.0 + 1e-9)))));
  }

  static int bin_of(double x, int n, int nb, bool periodic) {
    double t = x / n;
    if (periodic) t -= std::floor(t);
    // Clamped before the conversion (no overflow): on a non-periodic axis markers beyond a
    // wall join the edge bin; on a periodic one it only catches t·nb rounding up to nb.
    return static_cast<int>(std::clamp(std::floor(t * nb), 0.0, double(nb - 1)));
  }

  void build(const geometry::Domain& d, const MarkerView& v, std::vector<int>& bin) {
    const std::size_t N = v.x.size();
    bin.resize(N);
    start.assign(static_cast<std::size_t>(nbx * nby) + 1, 0);
    for (std::size_t m = 0; m < N; ++m) {
      bin[m] = bin_of(v.y[m], d.grid.ny, nby, d.periodic_y) * nbx + bin_of(v.x[m], d.grid.nx, nbx, d.periodic_x);
      ++start[static_cast<std::size_t>(bin[m]) + 1];
    }
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    items.resize(N);
    fill.assign(start.begin(), start.end() - 1);
    for (std::size_t m = 0; m < N; ++m) items[fill[static_cast<std::size_t>(bin[m])]++] = m;  // ascending per bin
  }

  // owner[b] for every bin: markers are ascending per bin and a cell's markers are one
  // index range, so the bin holds one cell iff its first and last marker share it.
  void find_owners(std::span<const std::size_t> cell_of) {
    const std::size_t bins = start.size() - 1;
    owner.assign(bins, 0);
    for (std::size_t b = 0; b < bins; ++b) {
      if (start[b] == start[b + 1]) continue;
      const std::size_t first = cell_of[items[start[b]]], last = cell_of[items[start[b + 1] - 1]];
      owner[b] = first == last ? first : kMixed;
    }
  }

  // Whether every marker of the (non-empty) bins `nb` belongs to one cell: then no marker
  // of them has a partner of another cell, and their pair sums stay zero.
  bool one_cell(const std::vector<int>& nb) const {
    std::size_t cell = kMixed;
    for (const int q : nb) {
      const std::size_t b = static_cast<std::size_t>(q);
      if (start[b] == start[b + 1]) continue;
      if (owner[b] == kMixed || (cell != kMixed && owner[b] != cell)) return false;
      cell = owner[b];
    }
    return true;
  }

  // The distinct bins within ±1 of (bx, by), wrapped on periodic axes, ascending.
  void neighbours(const geometry::Domain& d, int bx, int by, std::vector<int>& out) const {
    out.clear();
    if (bx >= 1 && bx + 1 < nbx && by >= 1 && by + 1 < nby) {  // inside: nine distinct bins, row by row
      for (int j = by - 1; j <= by + 1; ++j)
        for (int i = bx - 1; i <= bx + 1; ++i) out.push_back(j * nbx + i);
      return;
    }
    for (int oy = -1; oy <= 1; ++oy) {
      int j = by + oy;
      if (d.periodic_y)
        j = (j + nby) % nby;
      else if (j < 0 || j >= nby)
        continue;
      for (int ox = -1; ox <= 1; ++ox) {
        int i = bx + ox;
        if (d.periodic_x)
          i = (i + nbx) % nbx;
        else if (i < 0 || i >= nbx)
          continue;
        out.push_back(j * nbx + i);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
};

}  // namespace erythro::aggregation::detail
