#pragma once
// Immersed-boundary transfer between Lagrangian markers and the lattice
// (docs/model.md §2, thesis eqs 23–25), over the full width × width support square of
// the kernel (4 × 4 nodes for the 4-point kernels), h = 1:
//
//   spreading      f(x) += Σ_m F_m δ_h(x − X_m)           (eq 23)
//   interpolation  U_m   = Σ_x u(x) δ_h(x − X_m) h²        (eq 25)
//
// F_m is a FORCE (force density × marker arc length), so Σ_x f = Σ_m F_m when the
// kernel sums to one. Periodic axes wrap, walls drop support nodes (geometry/domain.hpp).
// Marker coordinates may be unwrapped (outside [0, n) on a periodic axis).
//
// Threading: spreading gathers per grid row. Markers are bucketed (counting sort,
// stable) by the first row of their support; each row, owned by one thread, adds
// the contributions of the `width` buckets that reach it in a fixed order (bucket
// offset, then marker index). No two threads write the same node and every node
// sums its terms in the same order for ANY thread count: the result is bitwise
// independent of OMP_NUM_THREADS. Interpolation is parallel over markers (reads only).
// Both read the markers' data laid out in bucket order (copied once per spread), so that a
// row's markers are neighbours in memory and neighbouring markers read neighbouring rows
// of the grid (grids beyond the cache).
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/domain.hpp"
#include "ib/kernel.hpp"
#include "ib/row_buckets.hpp"

namespace erythro::ib {

class Transfer {
 public:
  Transfer(KernelType kernel, geometry::Domain domain) : kernel_(kernel), domain_(domain) {}

  KernelType kernel() const { return kernel_; }
  const geometry::Domain& domain() const { return domain_; }

  // Adds the spread marker forces (Fx, Fy) at (X, Y) to the node force density
  // (fx, fy), each of size grid.size(). If given (size ny), rows_written holds each row's
  // state (fluid/force_rows.hpp): a row it adds to is zeroed first if it is cleared, and
  // then marked as holding force; the other rows are left as they are. Throws
  // std::invalid_argument on size mismatch and std::domain_error naming the marker if a
  // position is not finite.
  void spread(std::span<const double> X, std::span<const double> Y, std::span<const double> Fx,
              std::span<const double> Fy, std::span<double> fx, std::span<double> fy,
              std::span<std::uint8_t> rows_written = {});

  // Writes the interpolated velocity (Ux, Uy) of every marker from node fields (ux, uy).
  // At the positions of the last spread() (the IB cycle's), its supports and weights are
  // reused (one sine and cosine per marker and axis fewer; the same numbers).
  void interpolate(std::span<const double> X, std::span<const double> Y, std::span<const double> ux,
                   std::span<const double> uy, std::span<double> Ux, std::span<double> Uy) const;

 private:
  KernelType kernel_;
  geometry::Domain domain_;
  // Scratch reused across calls: the markers sorted by their support's first row, and in that
  // order (index q) their position, force, support origin and weights.
  RowBuckets buckets_;
  std::vector<int> piece_rows_;  // the first row of each piece of the row pass (RowBuckets::split_rows)
  std::vector<int> i0_, j0_;
  std::vector<double> xs_, ys_, fxs_, fys_, wx_, wy_;
  std::vector<double> weights_x_, weights_y_;  // the marker positions (marker order) wx_, wy_ were computed at
};

// Explicit Euler marker update of the thesis: X ← X + U Δt (lattice Δt = 1 by default).
void advance_markers(std::span<double> X, std::span<double> Y, std::span<const double> Ux,
                     std::span<const double> Uy, double dt = 1.0);

}  // namespace erythro::ib
