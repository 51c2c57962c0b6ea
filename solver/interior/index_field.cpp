// The index field I(x) of the thesis (§II.4, eqs 26–27; model.md §5). One update:
//  (1) I = 1 everywhere (only the nodes the previous update changed are reset);
//  (2) per cell, a band pass over the nodes within w + 1 of each edge (the edge's
//      bounding box grown by w + 1: O(markers), not O(grid)): d = shortest signed
//      distance to the polygon's edges; |d| < w → band node, I = min(I, H(d)) (eq 26);
//      free nodes next to an inside band node (w ≤ −d < w + 1) → start candidates;
//  (3) per cell, the interior: flood_fill — a scan-line fill from each candidate that
//      lies in the 2w × 2w window of a marker and is still free, replacing I = 1 by 0
//      and stopping at band nodes, then from every candidate still free; ray_casting — the free nodes inside by the even–odd
//      rule. Then a leak check against the enclosed area.
#include "interior/index_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "interior/geometry.hpp"

namespace erythro::interior {

namespace {
constexpr std::uint8_t kFree = 0, kBand = 1, kFilled = 2;
constexpr int kChunk = 16;  // band-pass row chunk (nodes)

std::string cell_box(const membrane::Polygon& p) {
  const auto [x0, x1] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
  std::ostringstream s;
  s << "[" << *x0 << ", " << *x1 << "] x [" << *y0 << ", " << *y1 << "]";
  return s.str();
}
}  // namespace

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

IndexField::IndexField(const ib::Domain& domain, IndexFieldOptions options) : domain_(domain), options_(options) {
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
  sd_.assign(n, std::numeric_limits<double>::infinity());
}

const FillReport& IndexField::update(std::span<const membrane::Polygon> cells) {
  // (1) I = 1 everywhere: undo the previous update.
  for (std::size_t k : dirty_) {
    index_[k] = 1.0;
    mark_[k] = kFree;
    owner_[k] = -1;
    candidate_[k] = 0;
  }
  dirty_.clear();
  report_ = FillReport{};
  report_.cells = static_cast<int>(cells.size());
  if (options_.method == Method::indexless) return report_;

  for (int c = 0; c < report_.cells; ++c) check_polygon(cells[static_cast<std::size_t>(c)], c);
  stats_.assign(cells.size(), CellStats{});
  starts_.clear();
  starts_begin_.assign(1, 0);
  // (2) the bands of every cell first, so that each fill stops at every band.
  for (int c = 0; c < report_.cells; ++c) band_pass(cells[static_cast<std::size_t>(c)], c, stats_[static_cast<std::size_t>(c)]);
  if (options_.method == Method::band_only) return report_;
  // (3) the interiors, then the leak check.
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

void IndexField::check_polygon(const membrane::Polygon& p, int cell) const {
  if (p.size() < 3 || p.y.size() != p.x.size())
    throw InputError("interior: cell " + std::to_string(cell) + " has " + std::to_string(p.size()) +
                     " markers; a closed membrane polygon needs at least 3 (and as many y as x)");
  for (std::size_t m = 0; m < p.size(); ++m)
    if (!std::isfinite(p.x[m]) || !std::isfinite(p.y[m]))
      throw InputError("interior: cell " + std::to_string(cell) + " marker " + std::to_string(m) +
                       " has a non-finite position (" + std::to_string(p.x[m]) + ", " + std::to_string(p.y[m]) + ")");
}

void IndexField::band_pass(const membrane::Polygon& p, int cell, CellStats& stats) {
  const Grid& g = domain_.grid;
  const double w = options_.band_half_width;
  // Distances are needed below w (the band). Start candidates (w ≤ −d < w + 1) are the free
  // nodes 4-adjacent to an inside band node: |d| is 1-Lipschitz, so for w > 1 such a node
  // has d ≤ −w (an outside node next to d' < 0 would need d' ≥ w − 1 > 0). A thinner band
  // (w ≤ 1) records distances up to w + 1 and takes candidates from them directly.
  const bool adjacency = w > 1.0;
  const double margin = adjacency ? w : w + 1.0, margin2 = margin * margin;
  const std::size_t n = p.size();
  // Outward unit normals of the edges and (angle-weighted, in 2D: summed) pseudo-normals
  // of the vertices: the sign of (P − Q)·n at the nearest point Q is the inside/outside
  // sign of P for a simple polygon (Bærentzen & Aanæs 2005).
  const double orient = membrane::signed_area(p) >= 0.0 ? 1.0 : -1.0;
  enx_.resize(n);
  eny_.resize(n);
  len_.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = a + 1 == n ? 0 : a + 1;
    const double ex = p.x[b] - p.x[a], ey = p.y[b] - p.y[a], len = std::sqrt(ex * ex + ey * ey);
    len_[a] = len;
    enx_[a] = len > 0 ? orient * ey / len : 0.0;
    eny_[a] = len > 0 ? -orient * ex / len : 0.0;
  }
  // Wedges: the line through each vertex along its pseudo-normal (the bisector of the two
  // edge normals) splits the band between the vertex's two edges. A node whose nearest point
  // lies on edge e (or on one of its vertices) lies in e's wedge — between the lines at its
  // ends — provided the polygon turns little per vertex: then each edge evaluates only its
  // wedge (about 1.6 evaluations per band node instead of 4.4). The local conditions checked
  // (else every edge evaluates its whole capsule, the always-correct fallback):
  //  - turning angle |θ_v| ≤ 0.5 rad at every vertex (cos θ = n_in·n_out, sin θ = n_in × n_out);
  //  - both edges at v longer than (w + 1)|sin θ_v| + 0.1: the nearest point of a node in
  //    the neighbour's wedge then lies on the neighbour, not beyond it;
  //  - the wedge lines at an edge's two ends do not cross within w + 1 of it:
  //    |e| ≥ (w + 1)(|tan(θ_A/2)| + |tan(θ_B/2)|) + 0.1, tan(θ/2) = sin θ/(1 + cos θ).
  // A tolerance of 0.25 h widens every wedge against round-off (extra nodes are harmless:
  // the minimum over edges is kept). Verified node for node against the brute-force distance
  // in verification.interior_fill_agreement.
  vtx_.resize(n);
  vty_.resize(n);
  theta_.resize(n);  // |tan(θ_v/2)|
  bool wedges = true;
  const double cos_max = std::cos(0.5);
  for (std::size_t v = 0; v < n && wedges; ++v) {
    const std::size_t z = v == 0 ? n - 1 : v - 1;
    const double lin = len_[z], lout = len_[v];
    const double cr = enx_[z] * eny_[v] - eny_[z] * enx_[v], dt = enx_[z] * enx_[v] + eny_[z] * eny_[v];
    const double nx_ = enx_[z] + enx_[v], ny_ = eny_[z] + eny_[v], nl = std::sqrt(nx_ * nx_ + ny_ * ny_);
    if (lin == 0.0 || lout == 0.0 || dt < cos_max || nl == 0.0 || std::min(lin, lout) < margin * std::abs(cr) + 0.1) {
      wedges = false;
      break;
    }
    vtx_[v] = -orient * ny_ / nl;  // forward tangent of the bisector line (normal rotated by +90°·orient)
    vty_[v] = orient * nx_ / nl;
    theta_[v] = std::abs(cr) / (1.0 + dt);
  }
  for (std::size_t a = 0; a < n && wedges; ++a) {
    const std::size_t b = a + 1 == n ? 0 : a + 1;
    if (len_[a] < margin * (theta_[a] + theta_[b]) + 0.1) wedges = false;
  }
  if (wedges) ++report_.wedge_cells;
  constexpr double kWedgeTol = 0.25;
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = a + 1 == n ? 0 : a + 1;
    const double ax = p.x[a], ay = p.y[a];
    const double ex = p.x[b] - ax, ey = p.y[b] - ay, len2 = ex * ex + ey * ey;
    if (len2 == 0.0) continue;  // a repeated marker: its neighbours' edges cover it
    const double inv_len2 = 1.0 / len2;
    const std::size_t z = a == 0 ? n - 1 : a - 1;
    const double pax = enx_[z] + enx_[a], pay = eny_[z] + eny_[a];  // pseudo-normal at A
    const double pbx = enx_[a] + enx_[b], pby = eny_[a] + eny_[b];  // pseudo-normal at B
    const double nex = enx_[a], ney = eny_[a];                          // normal of the edge
    const double inv_ey = ey != 0.0 ? 1.0 / ey : 0.0, bx = p.x[b], by = p.y[b];
    // Bisector-line tangents at A and B (wedge mode) and their reciprocal x components.
    const double tax = wedges ? vtx_[a] : 0.0, tay = wedges ? vty_[a] : 0.0;
    const double tbx = wedges ? vtx_[b] : 0.0, tby = wedges ? vty_[b] : 0.0;
    const double inv_tax = tax != 0.0 ? 1.0 / tax : 0.0, inv_tbx = tbx != 0.0 ? 1.0 / tbx : 0.0;
    int j0, j1;
    if (wedges) {
      // Rows of the wedge ∩ {|distance to the edge's line| < margin}: the parallelogram with
      // corners V ± margin·N_V/(N_V·n_e) on the bisector lines (N_V the unit pseudo-normal).
      const double nax = vty_[a] * orient, nay = -vtx_[a] * orient;  // unit pseudo-normal at A
      const double nbx = vty_[b] * orient, nby = -vtx_[b] * orient;  // unit pseudo-normal at B
      const double sa = margin / (nax * nex + nay * ney), sb = margin / (nbx * nex + nby * ney);
      const double ylo = std::min(ay - std::abs(sa * nay), by - std::abs(sb * nby)) - kWedgeTol;
      const double yhi = std::max(ay + std::abs(sa * nay), by + std::abs(sb * nby)) + kWedgeTol;
      node_range(ylo, yhi, j0, j1);
    } else {
      node_range(std::min(ay, by) - margin, std::max(ay, by) + margin, j0, j1);
    }
    for (int j = j0; j <= j1; ++j) {
      const int jj = wrap_node(j, g.ny, domain_.periodic_y);
      if (jj < 0) continue;
      const double py = j + 0.5, qy = py - ay;
      // Nodes of this row within `margin` of the edge lie within `margin` in x of the part
      // of the edge with |y(t) − py| ≤ margin, t ∈ [tl, th]: a tight row interval.
      double tl = 0.0, th = 1.0;
      if (ey != 0.0) {
        const double t1 = (qy - margin) * inv_ey, t2 = (qy + margin) * inv_ey;
        tl = std::clamp(std::min(t1, t2), 0.0, 1.0);
        th = std::clamp(std::max(t1, t2), 0.0, 1.0);
      }
      double lo = ax + std::min(tl * ex, th * ex) - margin, hi = ax + std::max(tl * ex, th * ex) + margin;
      if (wedges) {  // (P − A)·T_A ≥ −tol and (P − B)·T_B ≤ tol on this row
        const double ra = -kWedgeTol - qy * tay, rb = kWedgeTol - (py - by) * tby;
        if (tax > 1e-12) lo = std::max(lo, ax + ra * inv_tax);
        else if (tax < -1e-12) hi = std::min(hi, ax + ra * inv_tax);
        else if (ra > 0.0) continue;
        if (tbx > 1e-12) hi = std::min(hi, bx + rb * inv_tbx);
        else if (tbx < -1e-12) lo = std::max(lo, bx + rb * inv_tbx);
        else if (rb < 0.0) continue;
      }
      int i0, i1;
      node_range(lo, hi, i0, i1);
      const std::size_t row = static_cast<std::size_t>(jj) * static_cast<std::size_t>(g.nx);
      for (int c0 = i0; c0 <= i1; c0 += kChunk) {
        // Phase 1 (branch-free): squared distance and signed side per node.
        const int cn = std::min(kChunk, i1 - c0 + 1);
        double d2v[kChunk], sv[kChunk];
        for (int q = 0; q < cn; ++q) {
          const double qx = static_cast<double>(c0 + q) + 0.5 - ax;
          const double t0 = (qx * ex + qy * ey) * inv_len2;
          const double t = std::min(1.0, std::max(0.0, t0));
          const double dx = qx - t * ex, dy = qy - t * ey;
          d2v[q] = dx * dx + dy * dy;
          const double sa = dx * pax + dy * pay, sb = dx * pbx + dy * pby, se = dx * nex + dy * ney;
          // Side at the nearest point: vertex A (t = 0), vertex B (t = 1) or the edge.
          const double at_a = t0 <= 0.0, at_b = t0 >= 1.0;
          sv[q] = se + at_a * (sa - se) + at_b * (sb - se);
        }
        // Phase 2: keep the nearest edge per node (signed squared distance).
        for (int q = 0; q < cn; ++q) {
          const double d2 = d2v[q];
          if (d2 >= margin2) continue;
          const int ii = wrap_node(c0 + q, g.nx, domain_.periodic_x);
          if (ii < 0) continue;
          const std::size_t k = row + static_cast<std::size_t>(ii);
          const double cur = sd_[k];  // +inf when untouched
          if (std::isinf(cur)) {
            touched_.push_back(k);
            touched_xy_.push_back({ii, jj});
          } else if (d2 >= std::abs(cur)) {
            continue;
          }
          sd_[k] = sv[q] >= 0.0 ? d2 : -d2;
        }
      }
    }
  }
  auto add_candidate = [&](std::size_t k) {
    if (candidate_[k] != 0) return;
    candidate_[k] = cell + 1;
    starts_.push_back(k);
    dirty_.push_back(k);
  };
  for (std::size_t k : touched_) {  // signed squared → signed distance
    const double d2 = sd_[k];
    sd_[k] = d2 >= 0.0 ? std::sqrt(d2) : -std::sqrt(-d2);
  }
  for (std::size_t k : touched_) {
    const double d = sd_[k];
    if (std::abs(d) < w) {  // eq 26 in the band; overlapping bands keep the minimum I
      const double h = eq26(d, w);
      stats.band_area += 1.0 - h;
      if (mark_[k] == kFree) {
        mark_[k] = kBand;
        ++report_.band_nodes;
        dirty_.push_back(k);
      } else if (owner_[k] >= 0 && owner_[k] != cell) {
        ++report_.overlap_nodes;
      }
      owner_[k] = cell;
      index_[k] = std::min(index_[k], h);
    } else if (!adjacency && d <= -w) {  // start candidate: w ≤ −d < w + 1
      add_candidate(k);
    }
  }
  if (adjacency) {
    for (std::size_t q0 = 0; q0 < touched_.size(); ++q0) {
      if (sd_[touched_[q0]] >= 0.0) continue;
      const int x = touched_xy_[q0][0], y = touched_xy_[q0][1];
      const int nbx[4] = {x - 1, x + 1, x, x}, nby[4] = {y, y, y - 1, y + 1};
      for (int q = 0; q < 4; ++q) {
        const int xx = wrap_node(nbx[q], g.nx, domain_.periodic_x), yy = wrap_node(nby[q], g.ny, domain_.periodic_y);
        if (xx < 0 || yy < 0) continue;
        const std::size_t kn = g.index(xx, yy);
        if (std::isinf(sd_[kn])) add_candidate(kn);  // not in this cell's band (|d| ≥ w)
      }
    }
  }
  for (std::size_t k : touched_) sd_[k] = std::numeric_limits<double>::infinity();
  touched_.clear();
  touched_xy_.clear();
  starts_begin_.push_back(starts_.size());
}

void IndexField::flood_fill_cell(const membrane::Polygon& p, int cell, CellStats& stats) {
  const Grid& g = domain_.grid;
  // No fill of a closed polygon reaches beyond the nodes of its bounding box.
  int i0, i1, j0, j1;
  const auto [x0, x1] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
  node_range(*x0, *x1, i0, i1);
  node_range(*y0, *y1, j0, j1);
  const long box = std::min(static_cast<long>(g.size()), long{std::max(0, i1 - i0 + 1)} * long{std::max(0, j1 - j0 + 1)});
  const std::size_t begin = starts_begin_[static_cast<std::size_t>(cell)], end = starts_begin_[static_cast<std::size_t>(cell) + 1];
  if (begin == end) {  // no node beyond the band inside: a cell (almost) all band
    ++report_.fallback_cells;
    ray_cast_cell(p, cell, stats);
    return;
  }
  window_starts(p, cell, stats, box);  // the thesis: a start node in a marker's 2w × 2w window
  // Completion: every start node still free (an interior part the window rule missed).
  for (std::size_t s = begin; s < end; ++s) {
    if (mark_[starts_[s]] != kFree) continue;
    ++report_.completion_starts;
    scan_line_fill(starts_[s], cell, stats, box, p);
  }
}

void IndexField::window_starts(const membrane::Polygon& p, int cell, CellStats& stats, long limit) {
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
                                const membrane::Polygon& p) {
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
    for (int s = 0, xi = xl; s < len; ++s, xi = xi + 1 == nx ? 0 : xi + 1) {
      const std::size_t kk = row + static_cast<std::size_t>(xi);
      mark_[kk] = kFilled;
      index_[kk] = 0.0;
      dirty_.push_back(kk);
    }
    stats.filled += len;
    if (stats.filled > limit) {
      std::ostringstream msg;
      msg << "interior: the flood fill of cell " << cell << " leaked: " << stats.filled
          << " nodes filled, more than the " << limit << " nodes of its bounding box " << cell_box(p)
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

void IndexField::ray_cast_cell(const membrane::Polygon& p, int /*cell*/, CellStats& stats) {
  const Grid& g = domain_.grid;
  const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
  int j0, j1;
  node_range(*y0, *y1, j0, j1);
  for (int j = j0; j <= j1; ++j) {
    const int jj = wrap_node(j, g.ny, domain_.periodic_y);
    if (jj < 0) continue;
    row_crossings(p, j + 0.5, crossings_);
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
        dirty_.push_back(k);
        ++stats.filled;
      }
    }
  }
}

void IndexField::check_area(const membrane::Polygon& p, int cell, const CellStats& stats) {
  // Σ(1 − I) of the cell against its enclosed area (clipped at walls). A valid fill agrees
  // to O(h²) (docs/verification-interior.md); the bound allows a band cut by a wall
  // (0.30 h per unit length, ∫₀^w (1 − H) = w(¼ − 1/π²)) and pinched bands with a margin.
  const double area = std::abs(clipped_area(p, domain_));
  const double mismatch = std::abs(stats.band_area + static_cast<double>(stats.filled) - area);
  const double allowed = 0.5 * membrane::perimeter(p) + 4.0;
  if (mismatch > report_.max_area_mismatch) {
    report_.max_area_mismatch = mismatch;
    report_.max_area_mismatch_allowed = allowed;
  }
  if (mismatch <= allowed) return;
  std::ostringstream msg;
  msg << "interior: cell " << cell << " (markers in " << cell_box(p) << "): the " << to_string(options_.method)
      << " interior plus band holds " << stats.band_area + static_cast<double>(stats.filled)
      << " h^2 but the polygon encloses " << area << " h^2 (mismatch " << mismatch << " > " << allowed
      << "): the membrane polygon self-intersects, overlaps itself or another cell, or the fill leaked";
  throw FillLeakError(msg.str());
}

void IndexField::write_relaxation_times(std::span<double> tau, double nu_in, double nu_ex) const {
  if (tau.size() != index_.size())
    throw std::invalid_argument("IndexField::write_relaxation_times: tau has " + std::to_string(tau.size()) +
                                " entries, the grid " + std::to_string(index_.size()));
  // Eq 27 with ν = μ/ρ0, ρ0 = 1: ν(x) = ν_in + (ν_ex − ν_in) I(x), τ = ½ + 3ν (c_s² = ⅓).
  for (std::size_t k = 0; k < tau.size(); ++k) tau[k] = 0.5 + 3.0 * (nu_in + (nu_ex - nu_in) * index_[k]);
}

}  // namespace erythro::interior
