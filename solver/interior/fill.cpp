// Step (3) of the index-field update (index_field.cpp): the interior of one cell — the
// thesis's scan-line flood fill (with the completion pass and the small-cell fallback)
// and even–odd ray casting. One cell after the other: a cell's fill stops at the nodes of
// the fills before it. (Filled in parallel into per-cell lists and written afterwards,
// the fills cost more than they do serially — a per-node "taken" stamp and the list —
// and are about 6 % of the update; they stay serial.)
#include "interior/index_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "interior/geometry.hpp"
#include "interior/marks.hpp"

namespace erythro::interior {

using detail::kFilled;
using detail::kFree;

void IndexField::flood_fill_cell(const geometry::Polygon& p, int cell, CellStats& stats) {
  const Grid& g = domain_.grid;
  // No fill of a closed polygon reaches beyond the nodes of its bounding box.
  int i0, i1, j0, j1;
  const auto [x0, x1] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
  node_range(*x0, *x1, i0, i1);
  node_range(*y0, *y1, j0, j1);
  const long box = std::min(static_cast<long>(g.size()), long{std::max(0, i1 - i0 + 1)} * long{std::max(0, j1 - j0 + 1)});
  const std::vector<std::size_t>& starts = work_[static_cast<std::size_t>(cell)].starts;
  if (starts.empty()) {  // no node beyond the band inside: a cell (almost) all band
    ++report_.fallback_cells;
    ray_cast_cell(p, cell, stats);
    return;
  }
  window_starts(p, cell, stats, box);  // the thesis: a start node in a marker's 2w × 2w window
  // Completion: every start node still free (an interior part the window rule missed).
  for (std::size_t k : starts) {
    if (mark_[k] != kFree) continue;
    ++report_.completion_starts;
    scan_line_fill(k, cell, stats, box, p);
  }
}

void IndexField::window_starts(const geometry::Polygon& p, int cell, CellStats& stats, long limit) {
  const Grid& g = domain_.grid;
  const double hw = options_.band_half_width;
  // The thesis: the first start node in the window of a marker (markers in order).
  for (std::size_t m = 0; m < p.size(); ++m) {
    int i0, i1, j0, j1;
    node_range(p.x[m] - hw, p.x[m] + hw, i0, i1);
    node_range(p.y[m] - hw, p.y[m] + hw, j0, j1);
    for (int j = j0; j <= j1; ++j) {
      const int jj = wrap_node(j, g.ny, domain_.periodic_y);
      if (jj < 0) continue;
      for (int i = i0; i <= i1; ++i) {
        const int ii = wrap_node(i, g.nx, domain_.periodic_x);
        if (ii < 0) continue;
        const std::size_t k = g.index(ii, jj);
        if (candidate_[k] != cell + 1 || mark_[k] != kFree) continue;
        ++report_.fill_starts;
        scan_line_fill(k, cell, stats, limit, p);
        return;
      }
    }
  }
}

void IndexField::scan_line_fill(std::size_t start, int cell, CellStats& stats, long limit,
                                const geometry::Polygon& p) {
  const Grid& g = domain_.grid;
  const int nx = g.nx, ny = g.ny;
  stack_.clear();
  stack_.push_back(start);
  while (!stack_.empty()) {
    const std::size_t k = stack_.back();
    stack_.pop_back();
    if (mark_[k] != kFree) continue;
    const int x = static_cast<int>(k % static_cast<std::size_t>(nx)), y = static_cast<int>(k / static_cast<std::size_t>(nx));
    const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(nx);
    // The span of free nodes through x on row y (a whole periodic row at most).
    int xl = x, xr = x, len = 1;
    while (len < nx) {
      int xn = xl - 1;
      if (xn < 0) {
        if (!domain_.periodic_x) break;
        xn = nx - 1;
      }
      if (mark_[row + static_cast<std::size_t>(xn)] != kFree) break;
      xl = xn;
      ++len;
    }
    while (len < nx) {
      int xn = xr + 1;
      if (xn == nx) {
        if (!domain_.periodic_x) break;
        xn = 0;
      }
      if (mark_[row + static_cast<std::size_t>(xn)] != kFree) break;
      xr = xn;
      ++len;
    }
    std::vector<std::size_t>& changed = changed_.lists[static_cast<std::size_t>(block_of_row_[static_cast<std::size_t>(y)])];
    for (int s = 0, xi = xl; s < len; ++s, xi = xi + 1 == nx ? 0 : xi + 1) {
      const std::size_t kk = row + static_cast<std::size_t>(xi);
      mark_[kk] = kFilled;
      index_[kk] = 0.0;
      changed.push_back(kk);
    }
    stats.filled += len;
    if (stats.filled > limit) {
      std::ostringstream msg;
      msg << "interior: the flood fill of cell " << cell << " leaked: " << stats.filled
          << " nodes filled, more than the " << limit << " nodes of its bounding box " << detail::marker_box(p)
          << " (reached row " << y << ", nodes " << xl << ".." << xr << ", from start node ("
          << start % static_cast<std::size_t>(nx) << ", " << start / static_cast<std::size_t>(nx)
          << ")): the membrane polygon is not a closed simple curve or its band (half-width "
          << options_.band_half_width << " h; >= 0.5 h is needed to be watertight) has a gap";
      throw FillLeakError(msg.str());
    }
    // Seeds: the first free node of each free run on the rows above and below.
    for (int dy : {-1, 1}) {
      int yn = y + dy;
      if (yn < 0 || yn >= ny) {
        if (!domain_.periodic_y) continue;
        yn = (yn + ny) % ny;
      }
      const std::size_t nrow = static_cast<std::size_t>(yn) * static_cast<std::size_t>(nx);
      bool prev_free = false;
      for (int s = 0, xi = xl; s < len; ++s, xi = xi + 1 == nx ? 0 : xi + 1) {
        const std::size_t kn = nrow + static_cast<std::size_t>(xi);
        const bool free = mark_[kn] == kFree;
        if (free && !prev_free) stack_.push_back(kn);
        prev_free = free;
      }
    }
  }
}

void IndexField::ray_cast_cell(const geometry::Polygon& p, int /*cell*/, CellStats& stats) {
  const Grid& g = domain_.grid;
  const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
  int j0, j1;
  node_range(*y0, *y1, j0, j1);
  for (int j = j0; j <= j1; ++j) {
    const int jj = wrap_node(j, g.ny, domain_.periodic_y);
    if (jj < 0) continue;
    row_crossings(p, j + 0.5, crossings_);
    std::vector<std::size_t>& changed = changed_.lists[static_cast<std::size_t>(block_of_row_[static_cast<std::size_t>(jj)])];
    for (std::size_t c = 0; c + 1 < crossings_.size(); c += 2) {
      // Even–odd: inside ⇔ x_c[2k] ≤ i + ½ < x_c[2k+1].
      const int i0 = static_cast<int>(std::ceil(crossings_[c] - 0.5));
      const int i1 = static_cast<int>(std::ceil(crossings_[c + 1] - 0.5)) - 1;
      for (int i = i0; i <= i1; ++i) {
        const int ii = wrap_node(i, g.nx, domain_.periodic_x);
        if (ii < 0) continue;
        const std::size_t k = g.index(ii, jj);
        if (mark_[k] != kFree) continue;
        mark_[k] = kFilled;
        index_[k] = 0.0;
        changed.push_back(k);
        ++stats.filled;
      }
    }
  }
}

}  // namespace erythro::interior
