#include "ib/transfer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "common/portable_sincos.hpp"
#include "geometry/grid_polygon.hpp"

namespace erythro::ib {

namespace {

// Markers from which the per-marker loops run on the threads (each marker its own result, so
// the bits do not depend on it): below it a parallel region costs more than it saves.
constexpr long kParallelMarkers = 512;

// Throws for the first marker with a non-finite position (looked for only once the
// parallel pass has found one).
void report_first_non_finite(std::span<const double> X, std::span<const double> Y) {
  for (std::size_t m = 0; m < X.size(); ++m) {
    if (!std::isfinite(X[m]) || !std::isfinite(Y[m])) {
      throw std::domain_error("immersed boundary: marker " + std::to_string(m) + " has a non-finite position (" +
                              std::to_string(X[m]) + ", " + std::to_string(Y[m]) + ")");
    }
  }
}

// Throws for a non-finite position (naming the first such marker) and returns whether (X, Y)
// equal (WX, WY) element by element; arrays of another size are not compared (false). One
// pass over the threads.
bool check_finite_and_same(std::span<const double> X, std::span<const double> Y, std::span<const double> WX,
                           std::span<const double> WY) {
  const bool compare = WX.size() == X.size() && WY.size() == Y.size();
  const long markers = static_cast<long>(X.size());
  bool finite = true, same = true;
#pragma omp parallel for schedule(static) if (markers >= kParallelMarkers) reduction(&& : finite, same)
  for (long m = 0; m < markers; ++m) {
    finite = finite && std::isfinite(X[m]) && std::isfinite(Y[m]);
    same = same && compare && X[m] == WX[m] && Y[m] == WY[m];  // `compare` first: no read beyond WX
  }
  if (!finite) report_first_non_finite(X, Y);
  return compare && same;
}

void check_finite(std::span<const double> X, std::span<const double> Y) { check_finite_and_same(X, Y, {}, {}); }

// Support origin and the 1D weights φ(X − (i0 + b + ½)), b = 0 … W − 1.
template <class K>
inline void weights_1d(double X, int& i0, double* w) {
  i0 = support_start(X, K::width);
  if constexpr (std::is_same_v<K, Cosine4>) {
    // φ(r) = ¼[1 + cos(πr/2)] (kernel.hpp) at r_b = r₀ − b, r₀ = X − (i0 + ½) ∈ [1, 2):
    // with x = r₀ − 1 ∈ [0, 1) the four weights need only sin(πx/2) and cos(πx/2) (model.md
    // eq 2.4a), computed inline (common/portable_sincos.hpp) instead of by the C library.
    double s, c;
    numeric::sin_cos_half_pi(X - (i0 + 1.5), s, c);
    w[0] = 0.25 * (1.0 - s);
    w[1] = 0.25 * (1.0 + c);
    w[2] = 0.25 * (1.0 + s);
    w[3] = 0.25 * (1.0 - c);
  } else {
    for (int b = 0; b < K::width; ++b) w[b] = K::phi(X - (i0 + b + 0.5));
  }
}

// weights_1d for n coordinates at once (origins i0[k], weights w[k W … k W + W − 1]): a loop
// of its own, outside the threads' region, so that the compiler vectorises it; each lane does
// what one call does, the same bits.
constexpr long kWeightBlock = 256;  // markers per block handed to a thread
template <class K>
void weights_of_block(const double* __restrict X, long n, int* __restrict i0, double* __restrict w) {
#pragma omp simd
  for (long k = 0; k < n; ++k) weights_1d<K>(X[k], i0[k], w + k * K::width);
}

// One marker's interpolation (model.md eq 2.3) on a four-wide support that lies wholly inside
// its rows, with the four rows side by side in the lanes of a vector: lane a takes
// r_a = Σ_b v(i0 + b, j_a) w_x[b] in the order b = 0 … 3, starting from +0, as the scalar loop's
// rx does (the same operations in the same order on the same operands: the same bits); the rows
// are then summed one by one in the order a = 0 … 3, a row beyond a wall (present[a] false) left
// out, as the scalar loop's `continue`. rows_x[a], rows_y[a]: the first support node of row a
// (any valid row where the row is absent; its lane is computed and not used).
using Lanes4 = double __attribute__((vector_size(32)));
inline void interpolate_rows_of_four(const double* const* rows_x, const double* const* rows_y, const bool* present,
                                     const double* wx, const double* wy, double& Ux, double& Uy) {
  Lanes4 rx = {0.0, 0.0, 0.0, 0.0}, ry = {0.0, 0.0, 0.0, 0.0};
  for (int b = 0; b < 4; ++b) {
    const Lanes4 column_x = {rows_x[0][b], rows_x[1][b], rows_x[2][b], rows_x[3][b]};
    const Lanes4 column_y = {rows_y[0][b], rows_y[1][b], rows_y[2][b], rows_y[3][b]};
    rx = rx + column_x * wx[b];
    ry = ry + column_y * wx[b];
  }
  double sx = 0.0, sy = 0.0;
  for (int a = 0; a < 4; ++a) {
    if (!present[a]) continue;
    sx += rx[a] * wy[a];
    sy += ry[a] * wy[a];
  }
  Ux = sx;
  Uy = sy;
}

// `weights(m, i0, wx, j0, wy)` gives marker m's support origin and 1D weights: computed
// from (X, Y), or the ones spread() computed for the same positions.
template <class K, class Weights>
void interpolate_impl(const geometry::Domain& d, long M, const Weights& weights, std::span<const double> ux,
                      std::span<const double> uy, std::span<double> Ux, std::span<double> Uy) {
  constexpr int W = K::width;
  const int nx = d.grid.nx, ny = d.grid.ny;
#pragma omp parallel for schedule(static) if (M >= kParallelMarkers)
  for (long m = 0; m < M; ++m) {
    int i0, j0;
    double wx[W], wy[W];
    weights(static_cast<std::size_t>(m), i0, wx, j0, wy);
    // The support's rows: wrapped across a periodic side, absent beyond a wall (no node there,
    // geometry/domain.hpp; an absent row is left out of the sum).
    int row[W];
    bool present[W];
    for (int a = 0; a < W; ++a) {
      row[a] = d.periodic_y ? geometry::wrap_periodic(j0 + a, ny) : j0 + a;
      present[a] = row[a] >= 0 && row[a] < ny;
    }
    if constexpr (W == 4) {
      if (i0 >= 0 && i0 <= nx - W) {  // the whole support inside its rows: the rows in vector lanes
        const double* rows_x[W];
        const double* rows_y[W];
        for (int a = 0; a < W; ++a) {
          const std::size_t n = d.grid.index(i0, present[a] ? row[a] : 0);
          rows_x[a] = ux.data() + n;
          rows_y[a] = uy.data() + n;
        }
        interpolate_rows_of_four(rows_x, rows_y, present, wx, wy, Ux[m], Uy[m]);
        continue;
      }
    }
    double sx = 0.0, sy = 0.0;
    for (int a = 0; a < W; ++a) {
      if (!present[a]) continue;
      const int j = row[a];
      double rx = 0.0, ry = 0.0;
      if (i0 >= 0 && i0 <= nx - W) {  // the whole support inside the row: no wrap, no drop
        const double* __restrict vx = ux.data() + d.grid.index(i0, j);
        const double* __restrict vy = uy.data() + d.grid.index(i0, j);
        for (int b = 0; b < W; ++b) {
          rx += vx[b] * wx[b];
          ry += vy[b] * wx[b];
        }
      } else {
        for (int b = 0; b < W; ++b) {
          int i = i0 + b;
          if (d.periodic_x) i = geometry::wrap_periodic(i, nx);
          else if (i < 0 || i >= nx) continue;
          const std::size_t n = d.grid.index(i, j);
          rx += ux[n] * wx[b];
          ry += uy[n] * wx[b];
        }
      }
      sx += rx * wy[a];
      sy += ry * wy[a];
    }
    Ux[m] = sx;
    Uy[m] = sy;
  }
}

}  // namespace

void Transfer::spread(std::span<const double> X, std::span<const double> Y, std::span<const double> Fx,
                      std::span<const double> Fy, std::span<double> fx, std::span<double> fy,
                      std::span<std::uint8_t> rows_written) {
  const std::size_t M = X.size();
  if (Y.size() != M || Fx.size() != M || Fy.size() != M) {
    throw std::invalid_argument("ib::Transfer::spread: marker arrays differ in size");
  }
  if (fx.size() != domain_.grid.size() || fy.size() != domain_.grid.size()) {
    throw std::invalid_argument("ib::Transfer::spread: force field size does not match the grid");
  }
  if (!rows_written.empty() && rows_written.size() != static_cast<std::size_t>(domain_.grid.ny)) {
    throw std::invalid_argument("ib::Transfer::spread: row flags do not match the grid");
  }
  check_finite(X, Y);
  dispatch(kernel_, [&](auto k) {
    using K = decltype(k);
    constexpr int W = K::width;
    const geometry::Domain& d = domain_;
    const int nx = d.grid.nx, ny = d.grid.ny;
    // 1. Support origins and weights of every marker.
    i0_.resize(M);
    j0_.resize(M);
    wx_.resize(M * W);
    wy_.resize(M * W);
    weights_x_.resize(M);  // the positions these weights belong to
    weights_y_.resize(M);
    const long markers = static_cast<long>(M);  // each marker its own: any thread count, the same bits
    const long blocks = (markers + kWeightBlock - 1) / kWeightBlock;
#pragma omp parallel for schedule(static) if (markers >= kParallelMarkers)
    for (long b = 0; b < blocks; ++b) {
      const long first = b * kWeightBlock, n = std::min(markers - first, kWeightBlock);
      weights_of_block<K>(X.data() + first, n, i0_.data() + first, wx_.data() + first * W);
      weights_of_block<K>(Y.data() + first, n, j0_.data() + first, wy_.data() + first * W);
      std::copy_n(X.data() + first, n, weights_x_.data() + first);
      std::copy_n(Y.data() + first, n, weights_y_.data() + first);
    }
    // 2. Stable counting sort of markers by the bucket of their first support row.
    //    Periodic y: bucket = j0 mod ny. Walls: bucket = j0 + W − 1 ∈ [0, ny + W − 1);
    //    a marker whose whole support lies beyond a wall gets no bucket.
    const int nb = d.periodic_y ? ny : ny + W - 1;
    auto bucket_of = [&](int j0) { return d.periodic_y ? geometry::wrap_periodic(j0, ny) : j0 + W - 1; };
    bucket_start_.assign(static_cast<std::size_t>(nb) + 1, 0);
    for (std::size_t m = 0; m < M; ++m) {
      const int b = bucket_of(j0_[m]);
      if (b >= 0 && b < nb) ++bucket_start_[static_cast<std::size_t>(b) + 1];
    }
    for (int b = 0; b < nb; ++b) bucket_start_[b + 1] += bucket_start_[b];
    order_.resize(static_cast<std::size_t>(bucket_start_[nb]));
    next_.assign(bucket_start_.begin(), bucket_start_.end() - 1);
    for (std::size_t m = 0; m < M; ++m) {
      const int b = bucket_of(j0_[m]);
      if (b >= 0 && b < nb) order_[static_cast<std::size_t>(next_[b]++)] = static_cast<int>(m);
    }
    // 3. Gather per row: row y receives support row a of markers whose first row is y − a.
    const bool threads = d.grid.worth_threading() && M >= 64;
#pragma omp parallel for schedule(static) if (threads)
    for (int y = 0; y < ny; ++y) {
      double* rowx = fx.data() + d.grid.index(0, y);
      double* rowy = fy.data() + d.grid.index(0, y);
      for (int a = 0; a < W; ++a) {
        const int b = bucket_of(y - a);
        if (b < 0 || b >= nb || bucket_start_[b] == bucket_start_[b + 1]) continue;
        if (!rows_written.empty()) rows_written[static_cast<std::size_t>(y)] = 1;
        for (int q = bucket_start_[b]; q < bucket_start_[b + 1]; ++q) {
          const std::size_t m = static_cast<std::size_t>(order_[q]);
          const double gx = Fx[m] * wy_[m * W + a], gy = Fy[m] * wy_[m * W + a];
          const double* w = &wx_[m * W];
          const int i0 = i0_[m];
          if (i0 >= 0 && i0 <= nx - W) {  // the whole support inside the row: no wrap, no drop
            double* __restrict sx = rowx + i0;
            double* __restrict sy = rowy + i0;
            for (int c = 0; c < W; ++c) {
              sx[c] += gx * w[c];
              sy[c] += gy * w[c];
            }
            continue;
          }
          for (int c = 0; c < W; ++c) {
            int i = i0_[m] + c;
            if (d.periodic_x) i = geometry::wrap_periodic(i, nx);
            else if (i < 0 || i >= nx) continue;  // beyond a wall: dropped (geometry/domain.hpp)
            rowx[i] += gx * w[c];
            rowy[i] += gy * w[c];
          }
        }
      }
    }
  });
}

void Transfer::interpolate(std::span<const double> X, std::span<const double> Y, std::span<const double> ux,
                           std::span<const double> uy, std::span<double> Ux, std::span<double> Uy) const {
  const std::size_t M = X.size();
  if (Y.size() != M || Ux.size() != M || Uy.size() != M) {
    throw std::invalid_argument("ib::Transfer::interpolate: marker arrays differ in size");
  }
  if (ux.size() != domain_.grid.size() || uy.size() != domain_.grid.size()) {
    throw std::invalid_argument("ib::Transfer::interpolate: velocity field size does not match the grid");
  }
  // The positions spread() last saw (the usual IB cycle: spread at X^n, fluid step,
  // interpolate at X^n): its supports and weights serve again, the same numbers.
  const bool same_positions = check_finite_and_same(X, Y, weights_x_, weights_y_);
  const long markers = static_cast<long>(M);
  dispatch(kernel_, [&](auto k) {
    using K = decltype(k);
    constexpr int W = K::width;
    if (same_positions) {
      interpolate_impl<K>(domain_, markers, [&](std::size_t m, int& i0, double* wx, int& j0, double* wy) {
        i0 = i0_[m];
        j0 = j0_[m];
        std::copy_n(&wx_[m * W], W, wx);
        std::copy_n(&wy_[m * W], W, wy);
      }, ux, uy, Ux, Uy);
    } else {
      interpolate_impl<K>(domain_, markers, [&](std::size_t m, int& i0, double* wx, int& j0, double* wy) {
        weights_1d<K>(X[m], i0, wx);
        weights_1d<K>(Y[m], j0, wy);
      }, ux, uy, Ux, Uy);
    }
  });
}

void advance_markers(std::span<double> X, std::span<double> Y, std::span<const double> Ux,
                     std::span<const double> Uy, double dt) {
  const long markers = static_cast<long>(X.size());  // each marker its own: any thread count, the same bits
#pragma omp parallel for schedule(static) if (markers >= kParallelMarkers)
  for (long q = 0; q < markers; ++q) {
    const std::size_t m = static_cast<std::size_t>(q);
    X[m] += Ux[m] * dt;
    Y[m] += Uy[m] * dt;
  }
}

}  // namespace erythro::ib
