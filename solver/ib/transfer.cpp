#include "ib/transfer.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "common/chunk_stealing.hpp"
#include "common/portable_sincos.hpp"
#include "fluid/force_rows.hpp"
#include "geometry/grid_polygon.hpp"
#include "ib/row_buckets.hpp"

namespace erythro::ib {

namespace {

// Before the first addition to a row: a row the fluid lattice cleared but did not zero
// (fluid/force_rows.hpp) is zeroed now, while its lines are fetched for the additions anyway;
// then the row is marked as holding force.
void mark_written(std::uint8_t& state, double* rowx, double* rowy, int nx) {
  if (state == fluid::force_row::kCleared) {
    std::fill_n(rowx, nx, 0.0);
    std::fill_n(rowy, nx, 0.0);
  }
  state = fluid::force_row::kForced;
}

// Markers from which the per-marker loops run on the threads (each marker its own result, so
// the bits do not depend on it): below it a parallel region costs more than it saves.
constexpr long kParallelMarkers = 512;
// Markers per chunk of interpolation that a thread takes at once (common/chunk_stealing.hpp):
// a few microseconds of work, against one compare-and-swap per chunk.
constexpr long kMarkerChunk = 128;
// Pieces of the rows per thread in spreading, each of about equal work: a thread's share is
// kRowPiecesPerThread of them, and a thread done first takes the last pieces of a slower one.
constexpr int kRowPiecesPerThread = 32;

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
  // Ints combined with & (no short cut) over raw pointers: a loop that vectorises with plain
  // loads, where bools with && did not vectorise and spans gave gathers. With no positions to
  // compare with, the positions are compared with themselves (no read beyond WX).
  const double* x = X.data();
  const double* y = Y.data();
  const double* wx = compare ? WX.data() : x;
  const double* wy = compare ? WY.data() : y;
  // Blocks over the threads, a vector loop within each: the combined `parallel for simd` stayed
  // scalar with GCC 12 on AVX2 hosts (docs/performance-coupled-step.md, "Per-step costs of small scenes").
  constexpr long kBlock = 1024;
  const long blocks = (markers + kBlock - 1) / kBlock;
  int finite = 1, same = 1;
#pragma omp parallel for schedule(static) if (markers >= kParallelMarkers) reduction(& : finite, same)
  for (long b = 0; b < blocks; ++b) {
    const long first = b * kBlock, last = std::min(markers, first + kBlock);
    int block_finite = 1, block_same = 1;
#pragma omp simd reduction(& : block_finite, block_same)
    for (long m = first; m < last; ++m) {
      block_finite &= (std::isfinite(x[m]) ? 1 : 0) & (std::isfinite(y[m]) ? 1 : 0);
      block_same &= (x[m] == wx[m] ? 1 : 0) & (y[m] == wy[m] ? 1 : 0);
    }
    finite &= block_finite;
    same &= block_same;
  }
  if (finite == 0) report_first_non_finite(X, Y);
  return compare && same != 0;
}

void check_finite(std::span<const double> X, std::span<const double> Y) { check_finite_and_same(X, Y, {}, {}); }

// Grids beyond the cache (a hundred cells and more): a marker's support rows are far apart in
// memory and miss the cache, so spreading and interpolation ask for the lines they will need a
// little ahead (docs/performance-coupled-step.md, "Support rows ahead of their use"). Prefetches are hints:
// no result depends on them. On grids that stay in the cache they only cost instructions
// (interpolation 4.0 → 5.0–5.7 µs per cell at 255²), so they are asked for from kPrefetchNodes
// nodes on: 2^17 nodes hold 14.7 MB of populations and fields at 112 B per node, half the
// 32 MiB last-level cache of the machines erythro is measured on (at 509² they take
// interpolation from 9.3–10.8 to 6.2–7.1 µs per cell).
constexpr std::size_t kPrefetchNodes = std::size_t{1} << 17;
constexpr long kPrefetchAhead = 16;  // markers ahead in interpolation (8 and 24 measured alike)

// The lines of one support of width W in (ux, uy): each row's first and last node, columns
// clamped into the grid, rows wrapped or left out as interpolation takes them. Inlined by
// force: out of line, GCC 12 took the function for one without effects and dropped its calls.
template <int W>
[[gnu::always_inline]] inline void prefetch_support(const geometry::Domain& d, const double* ux, const double* uy, int i0,
                                                    int j0) {
  const int lo = std::clamp(i0, 0, d.grid.nx - 1), hi = std::clamp(i0 + W - 1, 0, d.grid.nx - 1);
  for (int a = 0; a < W; ++a) {
    int j = j0 + a;
    if (d.periodic_y)
      j = geometry::wrap_periodic(j, d.grid.ny);
    else if (j < 0 || j >= d.grid.ny)
      continue;
    __builtin_prefetch(ux + d.grid.index(lo, j));
    __builtin_prefetch(uy + d.grid.index(lo, j));
    __builtin_prefetch(ux + d.grid.index(hi, j));
    __builtin_prefetch(uy + d.grid.index(hi, j));
  }
}

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

// The velocity of `count` markers: for k = 0 … count − 1, `weights(k, i0, wx, j0, wy)` gives the support
// origin and 1D weights of marker marker_of(k) (computed from (X, Y), or the ones spread()
// computed for the same positions), whose velocity is written; `support_of(k, i0, j0)` gives the
// support origin alone (for the prefetch ahead). Each marker's sum is its own, so the order of k
// (marker order, or spread()'s order by rows) and the thread count leave the bits.
template <class K, class Weights, class MarkerOf, class SupportOf>
void interpolate_impl(const geometry::Domain& d, long count, const Weights& weights, const MarkerOf& marker_of,
                      const SupportOf& support_of, std::span<const double> ux, std::span<const double> uy,
                      std::span<double> Ux, std::span<double> Uy) {
  constexpr int W = K::width;
  const int nx = d.grid.nx, ny = d.grid.ny;
  const bool ahead = d.grid.size() >= kPrefetchNodes;
  auto marker_velocity = [&](long k) {
    int i0, j0;
    if (ahead && k + kPrefetchAhead < count) {
      support_of(static_cast<std::size_t>(k + kPrefetchAhead), i0, j0);
      prefetch_support<W>(d, ux.data(), uy.data(), i0, j0);
    }
    double wx[W], wy[W];
    weights(static_cast<std::size_t>(k), i0, wx, j0, wy);
    const std::size_t m = marker_of(static_cast<std::size_t>(k));
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
        return;
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
          if (d.periodic_x)
            i = geometry::wrap_periodic(i, nx);
          else if (i < 0 || i >= nx)
            continue;
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
  };
  parallel::for_each_range(count, kMarkerChunk, count >= kParallelMarkers ? omp_get_max_threads() : 1,
                           [&](long first, long last) {
                             for (long k = first; k < last; ++k) marker_velocity(k);
                           });
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
    // 1. The markers sorted by the first row of their support (ib/row_buckets.hpp).
    const bool threads = d.grid.worth_threading() && M >= 64;
    buckets_.sort(Y, W, d, threads && static_cast<long>(M) >= kParallelMarkers);
    const int nb = buckets_.buckets();
    const std::vector<int>& order = buckets_.sorted();
    const std::size_t Q = order.size();
    // 2. The bucketed markers' positions and forces in that order, and their support origins
    //    and weights (the row pass and interpolation then read them in order, not scattered
    //    over the markers).
    i0_.resize(Q);
    j0_.resize(Q);
    wx_.resize(Q * W);
    wy_.resize(Q * W);
    xs_.resize(Q);
    ys_.resize(Q);
    fxs_.resize(Q);
    fys_.resize(Q);
    // Block b also copies markers b·kWeightBlock … of (X, Y), in marker order: the positions these
    // weights belong to (interpolate() compares them with its own).
    weights_x_.resize(M);
    weights_y_.resize(M);
    const long markers = static_cast<long>(M), sorted = static_cast<long>(Q);  // sorted ≤ markers
    // Blocks of markers over the threads; each marker its own: the same bits.
    const int weight_threads = markers >= kParallelMarkers ? omp_get_max_threads() : 1;
    parallel::for_each_range(markers, kWeightBlock, weight_threads, [&](long first, long last) {
      std::copy_n(X.data() + first, last - first, weights_x_.data() + first);
      std::copy_n(Y.data() + first, last - first, weights_y_.data() + first);
      if (first >= sorted) return;  // markers beyond a wall only
      const long n = std::min(sorted, last) - first;
      for (long q = first; q < first + n; ++q) {
        const std::size_t m = static_cast<std::size_t>(order[static_cast<std::size_t>(q)]);
        xs_[q] = X[m];
        ys_[q] = Y[m];
        fxs_[q] = Fx[m];
        fys_[q] = Fy[m];
      }
      weights_of_block<K>(xs_.data() + first, n, i0_.data() + first, wx_.data() + first * W);
      weights_of_block<K>(ys_.data() + first, n, j0_.data() + first, wy_.data() + first * W);
    });
    // 3. Gather per row: row y receives support row a of the markers whose first row is y − a.
    const bool ahead = d.grid.size() >= kPrefetchNodes;
    auto add_row = [&](int y) {
      double* rowx = fx.data() + d.grid.index(0, y);
      double* rowy = fy.data() + d.grid.index(0, y);
      for (int a = 0; a < W; ++a) {
        const int b = buckets_.bucket_of(y - a);
        if (b < 0 || b >= nb || buckets_.start(b) == buckets_.start(b + 1)) continue;
        if (!rows_written.empty()) mark_written(rows_written[static_cast<std::size_t>(y)], rowx, rowy, nx);
        for (int q = buckets_.start(b); q < buckets_.start(b + 1); ++q) {
          const std::size_t s = static_cast<std::size_t>(q);
          const double gx = fxs_[s] * wy_[s * W + a], gy = fys_[s] * wy_[s * W + a];
          const double* w = &wx_[s * W];
          const int i0 = i0_[s];
          if (ahead && a == 0 && y + W - 1 < ny) {  // this support's later rows (kPrefetchNodes)
            const int lo = std::clamp(i0, 0, nx - 1);
            for (int r = 1; r < W; ++r) {
              __builtin_prefetch(rowx + r * nx + lo, 1);
              __builtin_prefetch(rowy + r * nx + lo, 1);
            }
          }
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
            int i = i0 + c;
            if (d.periodic_x)
              i = geometry::wrap_periodic(i, nx);
            else if (i < 0 || i >= nx)
              continue;  // beyond a wall: dropped (geometry/domain.hpp)
            rowx[i] += gx * w[c];
            rowy[i] += gy * w[c];
          }
        }
      }
    };
    // Pieces of neighbouring rows with about equal work (the cells are not spread evenly over the
    // rows), each thread starting on its own run of pieces; which thread adds a row does not
    // change its sums.
    const int row_threads = threads ? omp_get_max_threads() : 1;
    const int pieces = row_threads > 1 ? row_threads * kRowPiecesPerThread : 1;
    buckets_.split_rows(pieces, piece_rows_);
    parallel::for_each_chunk(pieces, row_threads, [&](long piece) {
      const std::size_t p = static_cast<std::size_t>(piece);
      for (int y = piece_rows_[p]; y < piece_rows_[p + 1]; ++y) add_row(y);
    });
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
  dispatch(kernel_, [&](auto k) {
    using K = decltype(k);
    constexpr int W = K::width;
    auto weights_from_positions = [&](std::size_t m, int& i0, double* wx, int& j0, double* wy) {
      weights_1d<K>(X[m], i0, wx);
      weights_1d<K>(Y[m], j0, wy);
    };
    auto support_from_positions = [&](std::size_t m, int& i0, int& j0) {
      i0 = support_start(X[m], W);
      j0 = support_start(Y[m], W);
    };
    if (same_positions) {
      // spread()'s order by rows (neighbouring markers read neighbouring rows of the grid).
      auto spread_support = [&](std::size_t q, int& i0, int& j0) {
        i0 = i0_[q];
        j0 = j0_[q];
      };
      interpolate_impl<K>(
          domain_, static_cast<long>(buckets_.sorted().size()),
          [&](std::size_t q, int& i0, double* wx, int& j0, double* wy) {
            spread_support(q, i0, j0);
            std::copy_n(&wx_[q * W], W, wx);
            std::copy_n(&wy_[q * W], W, wy);
          },
          [&](std::size_t q) { return static_cast<std::size_t>(buckets_.sorted()[q]); }, spread_support, ux, uy, Ux,
          Uy);
      // The markers spread() left without a bucket have no row of their support on the grid:
      // eq 2.3's sum over no rows, +0 (what interpolate_impl gives when every row is absent).
      for (const int m : buckets_.outside()) {
        Ux[static_cast<std::size_t>(m)] = 0.0;
        Uy[static_cast<std::size_t>(m)] = 0.0;
      }
    } else {
      interpolate_impl<K>(
          domain_, static_cast<long>(M), weights_from_positions, [](std::size_t m) { return m; },
          support_from_positions, ux, uy, Ux, Uy);
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
