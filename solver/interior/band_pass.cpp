// Step (2) of the index-field update (band_pass.hpp): the band of one cell, eq 26.
// (a) the cell's edge table (edge_table.hpp); (b) per edge, the rows of its wedge (or
// capsule) and in each row the nodes within reach, keeping the nearest signed squared
// distance per node in a per-cell box (BoxAxis, geometry.hpp) — no index wrapping, no
// touched-node list; (c) classify_box: eq 26 for every band node of the box, and the
// start candidates of the fill, listed in CellBand for the merge into the shared field.
// Bitwise the same field as the former per-node version (checked on ≈ 7 500 updates of
// random, folded, walled and periodic cells when it was introduced).
#include "interior/band_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "interior/geometry.hpp"
#include "interior/marks.hpp"

namespace erythro::interior {

namespace {
// One edge A + t(B − A) of the band pass: what a node visit needs.
struct Segment {
  double ax, ex, ey, inv_len2;
  double pax, pay, pbx, pby;  // pseudo-normals at A and B
  double nex, ney;            // normal of the edge
  double margin2;
};

// Visits node i of a row at height qy above A: the squared distance to the segment, kept
// in `best` (a signed squared distance, +inf when no edge reached the node) when nearer,
// signed by the side at the nearest point (vertex A at t = 0, B at t = 1, or the edge).
// Branch-free (which node is kept is unpredictable); d2 = margin2 and d2 = |best| keep
// the old value, as the strict comparisons require; live = false visits nothing.
inline void visit_node(const Segment& g, double qy, int i, double& best, bool live = true) {
  const double qx = static_cast<double>(i) + 0.5 - g.ax;
  const double t0 = (qx * g.ex + qy * g.ey) * g.inv_len2;
  const double t = std::min(1.0, std::max(0.0, t0));
  const double dx = qx - t * g.ex, dy = qy - t * g.ey, d2 = dx * dx + dy * dy;
  const double s = t0 <= 0.0 ? dx * g.pax + dy * g.pay : t0 >= 1.0 ? dx * g.pbx + dy * g.pby : dx * g.nex + dy * g.ney;
  const bool keep = !live || d2 >= g.margin2 || d2 >= std::abs(best);
  best = keep ? best : s >= 0.0 ? d2 : -d2;
}
template <class Out>
void classify_box(const geometry::Domain& domain, double w, const BoxAxis& bx, const BoxAxis& by,
                  detail::BandScratch& s, detail::BandStats& stats, Out& out);

// The distances of the band pass into the box; returns its axes.
std::array<BoxAxis, 2> distances(const geometry::Polygon& p, const geometry::Domain& domain, double w,
                                 detail::BandScratch& s, detail::BandStats& out) {
  const Grid& g = domain.grid;
  out.band_area = 0.0;
  // Distances are needed below w (the band). Start candidates (w ≤ −d < w + 1) are the free
  // nodes 4-adjacent to an inside band node: |d| is 1-Lipschitz, so for w > 1 such a node
  // has d ≤ −w (an outside node next to d' < 0 would need d' ≥ w − 1 > 0). A thinner band
  // (w ≤ 1) records distances up to w + 1 and takes candidates from them directly.
  const bool adjacency = w > 1.0;
  const double margin = adjacency ? w : w + 1.0, margin2 = margin * margin;
  const std::size_t n = p.size();
  // Normals, pseudo-normals and the wedge lines of every edge (edge_table.hpp). The wedges
  // are widened by 0.05 h against round-off (≈ 1e-13 h at lattice coordinates): nodes a
  // wedge takes in error only cost a visit, the minimum over edges is kept.
  constexpr double kWedgeTol = 0.05;
  out.signed_area = geometry::signed_area(p);
  const double orient = out.signed_area >= 0.0 ? 1.0 : -1.0;
  EdgeTable& e = s.edges;
  e.build(p, orient, margin, kWedgeTol);
  const bool wedges = e.wedges;
  out.perimeter = e.perimeter;
  out.wedges = wedges;
  // The cell's node box: every node within `margin` of an edge and its four neighbours
  // (BoxAxis; clipped at walls, folded on a periodic axis the cell spans). s.box holds the
  // best signed squared distance per box node, +inf where no edge reached.
  const auto [xmin, xmax] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [ymin, ymax] = std::minmax_element(p.y.begin(), p.y.end());
  out.within_walls = within_walls(domain, *xmin, *xmax, *ymin, *ymax);
  const BoxAxis bx = BoxAxis::covering(*xmin - margin - 1.0, *xmax + margin + 1.0, g.nx, domain.periodic_x);
  const BoxAxis by = BoxAxis::covering(*ymin - margin - 1.0, *ymax + margin + 1.0, g.ny, domain.periodic_y);
  const std::size_t stride = static_cast<std::size_t>(bx.size);
  s.box.assign(stride * static_cast<std::size_t>(by.size), std::numeric_limits<double>::infinity());
  s.span.assign(static_cast<std::size_t>(by.size), {bx.size, -1});  // per box row: columns an edge visited
  for (std::size_t a = 0; a < n; ++a) {
    if (e.len[a] == 0.0) continue;  // a repeated marker: its neighbours' edges cover it
    const std::size_t b = a + 1 == n ? 0 : a + 1, z = a == 0 ? n - 1 : a - 1;
    const double ax = p.x[a], ay = p.y[a], bxp = p.x[b], byp = p.y[b];
    const double ex = e.ex[a], ey = e.ey[a], inv_len2 = e.inv_len2[a], inv_ey = e.inv_ey[a];
    const double pax = e.nx[z] + e.nx[a], pay = e.ny[z] + e.ny[a];  // pseudo-normal at A
    const double pbx = e.nx[a] + e.nx[b], pby = e.ny[a] + e.ny[b];  // pseudo-normal at B
    const double nex = e.nx[a], ney = e.ny[a];                       // normal of the edge
    // Bisector-line tangents at A and B (wedge mode) and their reciprocal x components.
    const double tax = wedges ? e.tx[a] : 0.0, tay = wedges ? e.ty[a] : 0.0;
    const double tbx = wedges ? e.tx[b] : 0.0, tby = wedges ? e.ty[b] : 0.0;
    const double inv_tax = wedges ? e.inv_tx[a] : 0.0, inv_tbx = wedges ? e.inv_tx[b] : 0.0;
    int j0, j1;
    if (wedges)  // rows of the wedge ∩ {|distance to the edge's line| < margin}
      node_range(e.ylo[a], e.yhi[a], j0, j1);
    else
      node_range(std::min(ay, byp) - margin, std::max(ay, byp) + margin, j0, j1);
    const Segment seg{ax, ex, ey, inv_len2, pax, pay, pbx, pby, nex, ney, margin2};
    s.rows.clear();
    int widest = 0;
    for (int j = j0; j <= j1; ++j) {
      const int row_in_box = by.index(j);
      if (row_in_box < 0) continue;  // beyond a wall
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
        const double ra = -kWedgeTol - qy * tay, rb = kWedgeTol - (py - byp) * tby;
        if (tax > 1e-12) lo = std::max(lo, ax + ra * inv_tax);
        else if (tax < -1e-12) hi = std::min(hi, ax + ra * inv_tax);
        else if (ra > 0.0) continue;
        if (tbx > 1e-12) hi = std::min(hi, bxp + rb * inv_tbx);
        else if (tbx < -1e-12) lo = std::max(lo, bxp + rb * inv_tbx);
        else if (rb < 0.0) continue;
      }
      int i0, i1;
      node_range(lo, hi, i0, i1);
      if (bx.folded) {  // the box is the whole (periodic) axis: wrap every node
        double* row = s.box.data() + static_cast<std::size_t>(row_in_box) * stride;
        if (i0 <= i1) s.span[static_cast<std::size_t>(row_in_box)] = {0, bx.size - 1};
        for (int i = i0; i <= i1; ++i) visit_node(seg, qy, i, row[bx.index(i)]);
        continue;
      }
      // The box holds every node of the range, unwrapped (clipped at walls).
      i0 = std::max(i0, bx.origin);
      i1 = std::min(i1, bx.origin + bx.size - 1);
      if (i0 > i1) continue;
      s.rows.push_back({row_in_box, i0 - bx.origin, i1 - bx.origin, qy});
      widest = std::max(widest, i1 - i0 + 1);
    }
    // The edge's rows, each over the same number of nodes (its widest row): a constant trip
    // count the branch predictor follows, where each row's own count would be mispredicted.
    // Nodes past a row's end are visited masked (they store back what they read).
    for (const detail::BandScratch::EdgeRow& r : s.rows) {
      double* row = s.box.data() + static_cast<std::size_t>(r.row) * stride;
      auto& span = s.span[static_cast<std::size_t>(r.row)];
      span = {std::min(span[0], r.first), std::max(span[1], r.last)};
      if (r.first + widest > bx.size) {  // would run past the box: the row's own count
        for (int i = r.first; i <= r.last; ++i) visit_node(seg, r.qy, i + bx.origin, row[i]);
        continue;
      }
      for (int k = 0; k < widest; ++k)
        visit_node(seg, r.qy, r.first + k + bx.origin, row[r.first + k], r.first + k <= r.last);
    }
  }
  return {bx, by};
}

// Eq 26 for every band node of the box and the start candidates of the fill, to `out` in
// box order (FieldWriter or CellBand). A candidate is a box node no edge reached (|d| ≥ w)
// next to an inside band node; its box entry is set from +inf to −inf when passed on, so
// that it is passed on once.
template <class Out>
void classify_box(const geometry::Domain& domain, double w, const BoxAxis& bx, const BoxAxis& by,
                  detail::BandScratch& s, detail::BandStats& stats, Out& out) {
  const Grid& g = domain.grid;
  const bool adjacency = w > 1.0;  // as in distances()
  const std::size_t stride = static_cast<std::size_t>(bx.size);
  s.box_d.resize(static_cast<std::size_t>(bx.size));  // by box column; only the row's span is used
  s.box_h.resize(static_cast<std::size_t>(bx.size));
  // Per box column: its grid column and its left / right box neighbours (−1: beyond a wall).
  s.col_node.resize(static_cast<std::size_t>(bx.size));
  s.col_left.resize(static_cast<std::size_t>(bx.size));
  s.col_right.resize(static_cast<std::size_t>(bx.size));
  for (int bi = 0; bi < bx.size; ++bi) {
    const auto c = static_cast<std::size_t>(bi);
    s.col_node[c] = bx.node(bi);
    s.col_left[c] = bx.neighbour(bi, -1);
    s.col_right[c] = bx.neighbour(bi, 1);
  }
  double* box = s.box.data();
  double* box_d = s.box_d.data();
  double* box_h = s.box_h.data();
  const int* col_node = s.col_node.data();
  // Only band nodes with d ≤ 1 − w can have a free neighbour (|d| is 1-Lipschitz);
  // the box holds signed squared distances: d ≤ −(w − 1) ⇔ value ≤ −(w − 1)².
  const double limit = -(w - 1.0) * (w - 1.0);
  for (int bj = 0; bj < by.size; ++bj) {
    const double* row = box + static_cast<std::size_t>(bj) * stride;
    const auto [first, last] = s.span[static_cast<std::size_t>(bj)];
    if (first > last) continue;  // no edge reached this row
    const std::size_t b0 = static_cast<std::size_t>(first), b1 = static_cast<std::size_t>(last) + 1;
    // Signed distances and eq 26 for the row's span, branch-free (vectorised: this file is
    // compiled without errno for sqrt); only the entries an edge reached are read below.
    for (std::size_t bi = b0; bi < b1; ++bi) {
      const double d2 = row[bi], r = std::sqrt(std::abs(d2)), d = d2 >= 0.0 ? r : -r;
      box_d[bi] = d;
      box_h[bi] = eq26_in_band(d, w);
    }
    const std::size_t grid_row = static_cast<std::size_t>(by.node(bj)) * static_cast<std::size_t>(g.nx);
    const int up = by.neighbour(bj, 1), down = by.neighbour(bj, -1);  // box rows (−1: beyond a wall)
    for (std::size_t bi = b0; bi < b1; ++bi) {
      const double d2 = row[bi];  // signed squared distance
      if (std::isinf(d2)) continue;
      const std::size_t k = grid_row + static_cast<std::size_t>(col_node[bi]);
      const double d = box_d[bi];
      if (std::abs(d) < w) {  // eq 26 in the band (overlapping bands keep the minimum I)
        const double h = box_h[bi];
        stats.band_area += 1.0 - h;
        out.band_node(k, h);
      } else if (!adjacency && d <= -w) {  // start candidate: w ≤ −d < w + 1 (each box node once)
        out.candidate_node(k);
      }
      if (!adjacency || d2 > limit) continue;
      // A start candidate next to an inside band node: a neighbour no edge reached (|d| ≥ w).
      const int bi_ = static_cast<int>(bi);
      const int nb[4][2] = {{s.col_left[bi], bj}, {s.col_right[bi], bj}, {bi_, down}, {bi_, up}};
      for (const auto& q : nb) {
        if (q[0] < 0 || q[1] < 0) continue;  // beyond a wall
        double& entry = box[static_cast<std::size_t>(q[1]) * stride + static_cast<std::size_t>(q[0])];
        if (entry != std::numeric_limits<double>::infinity()) continue;  // reached by an edge, or listed
        entry = -std::numeric_limits<double>::infinity();
        out.candidate_node(static_cast<std::size_t>(by.node(q[1])) * static_cast<std::size_t>(g.nx) +
                           static_cast<std::size_t>(col_node[static_cast<std::size_t>(q[0])]));
      }
    }
  }
}

}  // namespace

void detail::find_band(const geometry::Polygon& p, const geometry::Domain& domain, double w, BandScratch& s,
                       BandStats& stats, FieldWriter& out) {
  const auto [bx, by] = distances(p, domain, w, s, stats);
  classify_box(domain, w, bx, by, s, stats, out);
}

void detail::find_band(const geometry::Polygon& p, const geometry::Domain& domain, double w, BandScratch& s,
                       BandStats& stats, CellBand& out) {
  out.clear();
  const auto [bx, by] = distances(p, domain, w, s, stats);
  classify_box(domain, w, bx, by, s, stats, out);
}

}  // namespace erythro::interior
