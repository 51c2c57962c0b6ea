// EdgeTable::build (edge_table.hpp). The marker coordinates are copied with marker 0
// repeated at the end, and the per-edge arrays carry edge 0 again at index n, so that every
// phase is one plain loop whose neighbour is index + 1: with restrict-qualified arrays the
// loops vectorise (this file is compiled without errno for sqrt). Every expression is the
// one the band pass used per edge before, so the index field is bitwise unchanged.
#include "interior/edge_table.hpp"

#include <algorithm>
#include <cmath>

namespace erythro::interior {

namespace {

// Edge a = (a, a + 1), a < n: edge vectors, outward unit normals (the sign of (P − Q)·n at
// the nearest point Q is the inside/outside sign of P; Bærentzen & Aanæs 2005) and the
// reciprocals of the row loops.
void edge_pass(std::size_t n, double orient, const double* __restrict x, const double* __restrict y,
               double* __restrict ex, double* __restrict ey, double* __restrict len, double* __restrict nx,
               double* __restrict ny, double* __restrict inv_len2, double* __restrict inv_ey) {
  for (std::size_t a = 0; a < n; ++a) {
    const double dx = x[a + 1] - x[a], dy = y[a + 1] - y[a], l2 = dx * dx + dy * dy, l = std::sqrt(l2);
    ex[a] = dx;
    ey[a] = dy;
    len[a] = l;
    nx[a] = l > 0 ? orient * dy / l : 0.0;
    ny[a] = l > 0 ? -orient * dx / l : 0.0;
    inv_len2[a] = 1.0 / l2;  // unused for a zero-length edge (the band pass skips it)
    inv_ey[a] = dy != 0.0 ? 1.0 / dy : 0.0;
  }
}

// Vertex v = 1 … n (v = n is vertex 0) between edges v − 1 and v: bisector-line tangent,
// |tan(θ/2)|, and whether the vertex breaks a wedge condition (edge_table.hpp).
int vertex_pass(std::size_t n, double orient, double margin, const double* __restrict len,
                const double* __restrict nx, const double* __restrict ny, double* __restrict tx,
                double* __restrict ty, double* __restrict inv_tx, double* __restrict tan_half) {
  const double cos_max = std::cos(0.5);
  int bad = 0;
  for (std::size_t v = 1; v <= n; ++v) {
    const std::size_t z = v - 1;
    const double lin = len[z], lout = len[v];
    const double cr = nx[z] * ny[v] - ny[z] * nx[v], dt = nx[z] * nx[v] + ny[z] * ny[v];
    const double sx = nx[z] + nx[v], sy = ny[z] + ny[v], nl = std::sqrt(sx * sx + sy * sy);
    bad |= static_cast<int>(lin == 0.0) | static_cast<int>(lout == 0.0) | static_cast<int>(dt < cos_max) |
           static_cast<int>(nl == 0.0) | static_cast<int>(std::min(lin, lout) < margin * std::abs(cr) + 0.1);
    const double t_x = -orient * sy / nl;  // normal rotated by +90°·orient (meaningless where bad)
    tx[v] = t_x;
    ty[v] = orient * sx / nl;
    inv_tx[v] = t_x != 0.0 ? 1.0 / t_x : 0.0;
    tan_half[v] = std::abs(cr) / (1.0 + dt);
  }
  return bad;
}

// Edge a < n: the y range of its wedge parallelogram, the corners V ± margin·N_V/(N_V·n_e)
// on the bisector lines at its ends (N_V the unit pseudo-normal), widened by wedge_tol;
// and whether the wedge lines at its ends cross within the margin.
int wedge_row_pass(std::size_t n, double orient, double margin, double wedge_tol, const double* __restrict y,
                   const double* __restrict len, const double* __restrict nx, const double* __restrict ny,
                   const double* __restrict tx, const double* __restrict ty, const double* __restrict tan_half,
                   double* __restrict ylo, double* __restrict yhi) {
  int bad = 0;
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = a + 1;
    bad |= static_cast<int>(len[a] < margin * (tan_half[a] + tan_half[b]) + 0.1);
    const double nax = ty[a] * orient, nay = -tx[a] * orient;  // unit pseudo-normal at A
    const double nbx = ty[b] * orient, nby = -tx[b] * orient;  // unit pseudo-normal at B
    const double sa = margin / (nax * nx[a] + nay * ny[a]), sb = margin / (nbx * nx[a] + nby * ny[a]);
    ylo[a] = std::min(y[a] - std::abs(sa * nay), y[b] - std::abs(sb * nby)) - wedge_tol;
    yhi[a] = std::max(y[a] + std::abs(sa * nay), y[b] + std::abs(sb * nby)) + wedge_tol;
  }
  return bad;
}

}  // namespace

void EdgeTable::build(const geometry::Polygon& p, double orient, double margin, double wedge_tol) {
  const std::size_t n = p.size();
  x_.assign(p.x.begin(), p.x.end());
  y_.assign(p.y.begin(), p.y.end());
  x_.push_back(p.x[0]);
  y_.push_back(p.y[0]);
  for (auto* v : {&ex, &ey, &len, &nx, &ny, &inv_len2, &inv_ey, &ylo, &yhi, &tx, &ty, &inv_tx, &tan_half})
    v->resize(n + 1);
  edge_pass(n, orient, x_.data(), y_.data(), ex.data(), ey.data(), len.data(), nx.data(), ny.data(),
            inv_len2.data(), inv_ey.data());
  for (auto* v : {&ex, &ey, &len, &nx, &ny, &inv_len2, &inv_ey}) (*v)[n] = (*v)[0];
  perimeter = 0.0;
  for (std::size_t a = 0; a < n; ++a) perimeter += len[a];

  // Wedges: the line through each vertex along its pseudo-normal (the bisector of the two
  // edge normals) splits the band between the vertex's two edges. A node whose nearest point
  // lies on edge e (or on one of its vertices) lies in e's wedge — between the lines at its
  // ends — provided the polygon turns little per vertex: then each edge evaluates only its
  // wedge (about 1.6 evaluations per band node instead of 4.4). The local conditions checked
  // (else every edge evaluates its whole capsule, the always-correct fallback):
  //  - turning angle |θ_v| ≤ 0.5 rad at every vertex (cos θ = n_in·n_out, sin θ = n_in × n_out);
  //  - both edges at v longer than margin·|sin θ_v| + 0.1: the nearest point of a node in
  //    the neighbour's wedge then lies on the neighbour, not beyond it;
  //  - the wedge lines at an edge's two ends do not cross within the margin of it:
  //    |e| ≥ margin (|tan(θ_A/2)| + |tan(θ_B/2)|) + 0.1, tan(θ/2) = sin θ/(1 + cos θ).
  // The band pass widens every wedge by wedge_tol against round-off (extra nodes are
  // harmless: the minimum over edges is kept). Verified node for node against the
  // brute-force distance (solver/tests/interior/randomized_test.cpp,
  // verification.interior_fill_agreement).
  int bad = vertex_pass(n, orient, margin, len.data(), nx.data(), ny.data(), tx.data(), ty.data(), inv_tx.data(),
                        tan_half.data());
  for (auto* v : {&tx, &ty, &inv_tx, &tan_half}) (*v)[0] = (*v)[n];  // vertex 0 was computed as vertex n
  bad |= wedge_row_pass(n, orient, margin, wedge_tol, y_.data(), len.data(), nx.data(), ny.data(), tx.data(),
                        ty.data(), tan_half.data(), ylo.data(), yhi.data());
  wedges = bad == 0;
}

}  // namespace erythro::interior
