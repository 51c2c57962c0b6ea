#pragma once
// Spreading and interpolation written out one marker at a time in the order the transfer
// promises (ib/transfer.hpp; docs/model.md eqs 2.2–2.4a), for tests that compare the code's
// result with them bit for bit.
#include <span>
#include <vector>

#include "common/portable_sincos.hpp"
#include "geometry/domain.hpp"
#include "ib/kernel.hpp"

namespace erythro::ib::reference {

// The 1D weight of support node b of a marker at X (origin i0): φ(X − (i0 + b + ½)), for the
// cosine kernel in the form the code evaluates it (model.md eq 2.4a, through sin and cos of πx/2).
inline double weight(KernelType t, double X, int i0, int b) {
  if (t != KernelType::cosine4) return phi(t, X - (i0 + b + 0.5));
  double s, c;
  numeric::sin_cos_half_pi(X - (i0 + 1.5), s, c);
  const double w[4] = {0.25 * (1.0 - s), 0.25 * (1.0 + c), 0.25 * (1.0 + s), 0.25 * (1.0 - c)};
  return w[b];
}

// Node column i or row j of a support, wrapped on a periodic axis; −1 beyond a wall.
inline int node_on_axis(int i, int n, bool periodic) {
  if (periodic) return (i % n + n) % n;
  return i >= 0 && i < n ? i : -1;
}

// Marker (X, Y)'s interpolated velocity from (ux, uy) (eq 2.3): each row's sum over b from +0,
// then the rows from +0, a node beyond a wall left out.
inline void interpolate_one(const geometry::Domain& d, KernelType t, std::span<const double> ux,
                            std::span<const double> uy, double X, double Y, double& Ux, double& Uy) {
  const int w = width(t), i0 = support_start(X, w), j0 = support_start(Y, w);
  double sx = 0.0, sy = 0.0;
  for (int a = 0; a < w; ++a) {
    const int j = node_on_axis(j0 + a, d.grid.ny, d.periodic_y);
    if (j < 0) continue;
    double rx = 0.0, ry = 0.0;
    for (int b = 0; b < w; ++b) {
      const int i = node_on_axis(i0 + b, d.grid.nx, d.periodic_x);
      if (i < 0) continue;
      const double wb = weight(t, X, i0, b);
      rx += ux[d.grid.index(i, j)] * wb;
      ry += uy[d.grid.index(i, j)] * wb;
    }
    const double wa = weight(t, Y, j0, a);
    sx += rx * wa;
    sy += ry * wa;
  }
  Ux = sx;
  Uy = sy;
}

// Spreading (eq 2.2) added to (fx, fy) in the promised order: each node takes its terms by
// support row a (a marker's first row first), then by marker index; the term of marker m at
// support node (a, b) is (F_m w_y[a]) w_x[b].
inline void spread_in_order(const geometry::Domain& d, KernelType t, std::span<const double> X,
                            std::span<const double> Y, std::span<const double> Fx, std::span<const double> Fy,
                            std::vector<double>& fx, std::vector<double>& fy) {
  const int w = width(t);
  for (int a = 0; a < w; ++a) {
    for (std::size_t m = 0; m < X.size(); ++m) {
      const int i0 = support_start(X[m], w), j0 = support_start(Y[m], w);
      const int j = node_on_axis(j0 + a, d.grid.ny, d.periodic_y);
      if (j < 0) continue;
      const double wa = weight(t, Y[m], j0, a), gx = Fx[m] * wa, gy = Fy[m] * wa;
      for (int b = 0; b < w; ++b) {
        const int i = node_on_axis(i0 + b, d.grid.nx, d.periodic_x);
        if (i < 0) continue;
        const double wb = weight(t, X[m], i0, b);
        fx[d.grid.index(i, j)] += gx * wb;
        fy[d.grid.index(i, j)] += gy * wb;
      }
    }
  }
}

}  // namespace erythro::ib::reference
