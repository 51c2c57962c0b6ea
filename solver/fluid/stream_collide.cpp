// Fused stream–collide, pull scheme (model.md §1): node n gathers f_i from
// n − c_i in the source lattice (post-collision values of the previous step),
// collides, and writes its own nine post-collision values to the destination.
// Rows are distributed over OpenMP threads; every node is independent, so the
// result is bitwise identical for any thread count.
//
// Performance (docs/performance.md): on large lattices the step is memory bound,
// 144 B per node update (9 doubles read, 9 written).
//  - Interior nodes take a branch-free loop over x that the compiler vectorises
//    (nine restrict source and nine destination streams). Not `omp simd`: GCC 12
//    privatises the node's f[9] per SIMD lane and then cannot vectorise the loop.
//    The outermost rows and columns take the general path with boundary handling.
//    Each span starts its vector loop at the first cache-line aligned output node (the
//    few nodes before it go through the loop's scalar remainder): +10–25 % in cache.
//    Both paths collide through the same node_update() → collide_node().
//  - When the two lattices do not fit in the last-level cache, each row is done in
//    chunks of kChunk nodes collided into a per-thread buffer and streamed out with
//    non-temporal stores: no write-allocate read of the destination (216 → 144 B per
//    node update). A single thread also prefetches its nine source streams into L2.
//  - Smaller lattices stay in cache: ordinary stores, whole rows.
//
// Rounding: floating-point contraction is off project-wide (-ffp-contract=off in
// cmake/CompilerSettings.cmake), so every path, store mode and thread count gives the
// same bits, and a reference that calls collide_node() reproduces them exactly
// (solver/tests/fluid/kernel_equivalence_test.cpp).

#include "fluid/stream_collide.hpp"

#include <algorithm>
#include <cstdint>

#include "fluid/collide_node.hpp"
#include "lattice/d2q9.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif
#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace erythro::fluid::detail {
namespace {

using namespace d2q9;

// Nodes per row chunk with streaming stores: the chunk's nine buffered output rows
// (9 × 64 × 8 B = 4.5 KiB) stay in L1 until streamed out.
constexpr int kChunk = 64;
// Software prefetch distance along each source stream, in nodes (6 KiB ahead; 512,
// 768, 1024 and 2048 measured, 768 best on the reference machine, docs/performance.md).
constexpr std::size_t kPrefetchDistance = 768;

// Value streamed into node (x, y) along direction i, following the boundary rules
// of fluid/boundary.hpp. A wall on the bottom/top takes precedence at corners.
[[gnu::always_inline]] inline double pull_general(const KernelArgs& a, int x, int y, int i) {
  const Grid& g = a.grid;
  const std::size_t N = g.size();
  int sx = x - cx[i], sy = y - cy[i];
  const Side* wall = nullptr;
  if (sy < 0 || sy >= g.ny) {
    const Side& side = sy < 0 ? a.boundaries.bottom : a.boundaries.top;
    if (side.type == SideType::periodic) {
      sy = (sy + g.ny) % g.ny;
    } else {
      wall = &side;
    }
  }
  if (!wall && (sx < 0 || sx >= g.nx)) {
    const Side& side = sx < 0 ? a.boundaries.left : a.boundaries.right;
    if (side.type == SideType::periodic) {
      sx = (sx + g.nx) % g.nx;
    } else {
      wall = &side;
    }
  }
  if (wall) {
    // Halfway bounce-back: f_i(x, t+1) = f*_ī(x, t) + 2 w_i ρ0 (c_i·u_w)/c_s².
    double value = a.src[opposite[i] * N + g.index(x, y)];
    if (wall->type == SideType::moving_wall) {
      value += 2.0 * w[i] * inv_cs2 * (cx[i] * wall->ux + cy[i] * wall->uy);
    }
    return value;
  }
  return a.src[i * N + g.index(sx, sy)];
}

// Per-node inputs of the collision other than the populations.
struct NodeInputs {
  const double* tau = nullptr;  // τ field or null
  const double* fx = nullptr;   // force field or null
  const double* fy = nullptr;
  double uniform_fx = 0.0, uniform_fy = 0.0, magic = 0.0;
  Rates uniform_rates{1.0, 1.0};
};

// The collision of node n (streamed populations in f). The one place where both
// the interior and the general path compute, so both round identically. `flatten`
// inlines collide_node() here: an out-of-line copy of that header function could be
// taken by the linker from another file compiled with contraction.
template <CollisionModel Model, bool TauField, bool HasForce, bool ForceField>
[[gnu::flatten]] inline void node_update(const double* tau, const double* fx, const double* fy, std::size_t n,
                                         double ufx, double ufy, double magic, Rates uniform_rates, double* f) {
  const Rates r = TauField ? rates_for(Model, tau[n], magic) : uniform_rates;
  double Fx = 0.0, Fy = 0.0;
  if constexpr (HasForce) {
    Fx = ufx;
    Fy = ufy;
    if constexpr (ForceField) {
      Fx += fx[n];
      Fy += fy[n];
    }
  }
  collide_node<Model, HasForce>(f, r, Fx, Fy);
}

// `len` interior nodes n0, n0+1, …: s_i[k] is the value streaming into node n0+k along
// i, o_i[k] receives its post-collision value. Nine restrict streams in, nine out,
// no branches: the loop vectorises along x.
template <CollisionModel Model, bool TauField, bool HasForce, bool ForceField>
void interior_span(const NodeInputs& in, const double* const* src, double* const* out, std::size_t n0, int len) {
  const double* __restrict s0 = src[0];
  const double* __restrict s1 = src[1];
  const double* __restrict s2 = src[2];
  const double* __restrict s3 = src[3];
  const double* __restrict s4 = src[4];
  const double* __restrict s5 = src[5];
  const double* __restrict s6 = src[6];
  const double* __restrict s7 = src[7];
  const double* __restrict s8 = src[8];
  double* __restrict o0 = out[0];
  double* __restrict o1 = out[1];
  double* __restrict o2 = out[2];
  double* __restrict o3 = out[3];
  double* __restrict o4 = out[4];
  double* __restrict o5 = out[5];
  double* __restrict o6 = out[6];
  double* __restrict o7 = out[7];
  double* __restrict o8 = out[8];
  const double* __restrict tau = TauField ? in.tau + n0 : nullptr;
  const double* __restrict fx = ForceField ? in.fx + n0 : nullptr;
  const double* __restrict fy = ForceField ? in.fy + n0 : nullptr;
  const double ufx = in.uniform_fx, ufy = in.uniform_fy, magic = in.magic;
  const Rates ur = in.uniform_rates;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
  for (int k = 0; k < len; ++k) {
    double f[Q] = {s0[k], s1[k], s2[k], s3[k], s4[k], s5[k], s6[k], s7[k], s8[k]};
    node_update<Model, TauField, HasForce, ForceField>(tau, fx, fy, static_cast<std::size_t>(k), ufx, ufy, magic,
                                                       ur, f);
    o0[k] = f[0];
    o1[k] = f[1];
    o2[k] = f[2];
    o3[k] = f[3];
    o4[k] = f[4];
    o5[k] = f[5];
    o6[k] = f[6];
    o7[k] = f[7];
    o8[k] = f[8];
  }
}

// dst[0..len) ← src[0..len) with non-temporal stores where dst is vector aligned
// (ordinary stores for the unaligned head and the tail). With AVX-512 one store
// writes a whole cache line.
inline void stream_out(double* __restrict dst, const double* __restrict src, int len) {
  int k = 0;
#if defined(__AVX512F__)
  constexpr int width = 8;
#elif defined(__AVX__)
  constexpr int width = 4;
#elif defined(__SSE2__)
  constexpr int width = 2;
#endif
#if defined(__SSE2__)
  for (; k < len && reinterpret_cast<std::uintptr_t>(dst + k) % (width * sizeof(double)) != 0; ++k) dst[k] = src[k];
  for (; k + width <= len; k += width) {
#if defined(__AVX512F__)
    _mm512_stream_pd(dst + k, _mm512_loadu_pd(src + k));
#elif defined(__AVX__)
    _mm256_stream_pd(dst + k, _mm256_loadu_pd(src + k));
#else
    _mm_stream_pd(dst + k, _mm_loadu_pd(src + k));
#endif
  }
#endif
  for (; k < len; ++k) dst[k] = src[k];
}

// Software prefetch into L2 (prefetcht1), used when a single thread streams a lattice
// that does not fit in cache: with nine source streams the hardware prefetcher alone
// leaves one core waiting on memory. Requesting each stream kPrefetchDistance nodes
// ahead into L2 gains 25–50 % at 1024² over no prefetch; the non-temporal hint
// (prefetchnta) gained less and prefetcht0 nothing: nine streams 6 KiB ahead do not
// fit in L1 beside the collision's working set (measured; docs/performance.md). With
// both cores streaming the memory bus is already saturated and the extra requests
// cost 20 %, so then it is off.
inline void prefetch_l2(const double* p) {
#if defined(__GNUC__)
  __builtin_prefetch(p, 0, 2);
#else
  (void)p;
#endif
}

// Number of threads of the enclosing parallel region.
inline int team_size() {
#if defined(_OPENMP)
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// Orders this thread's non-temporal stores before the barrier that ends the step.
inline void store_fence() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

template <CollisionModel Model, bool TauField, bool HasForce, bool ForceField>
void update_chunk(const KernelArgs& a, const NodeInputs& in, int y, int x0, int x1, double* const* out,
                  bool prefetch) {
  const Grid& g = a.grid;
  const std::size_t N = g.size();
  // A node next to the boundary: nine general pulls (unrolled, so c_i are constants).
  auto general = [&](int x) __attribute__((always_inline)) {
    double f[Q];
#pragma GCC unroll 9
    for (int i = 0; i < Q; ++i) f[i] = pull_general(a, x, y, i);
    node_update<Model, TauField, HasForce, ForceField>(in.tau, in.fx, in.fy, g.index(x, y), in.uniform_fx,
                                                       in.uniform_fy, in.magic, in.uniform_rates, f);
#pragma GCC unroll 9
    for (int i = 0; i < Q; ++i) out[i][x - x0] = f[i];
  };
  if (y == 0 || y == g.ny - 1 || g.nx < 3) {
    for (int x = x0; x < x1; ++x) general(x);
    return;
  }
  if (x0 == 0) general(0);
  const int begin = std::max(x0, 1), end = std::min(x1, g.nx - 1);
  if (end > begin) {
    const double* src[Q];
    double* dst[Q];
    for (int i = 0; i < Q; ++i) {
      const std::size_t from = g.index(begin - cx[i], y - cy[i]);
      src[i] = a.src + i * N + from;
      dst[i] = out[i] + (begin - x0);
      if (prefetch) {  // the same span kPrefetchDistance nodes further on, one request per line
        const std::size_t stop = std::min(N, from + kPrefetchDistance + static_cast<std::size_t>(end - begin));
        for (std::size_t k = from + kPrefetchDistance; k < stop; k += 8) prefetch_l2(a.src + i * N + k);
      }
    }
    // Split off the head up to the first node whose outputs are cache-line aligned, so
    // the vector loop's nine stores never straddle two lines (the same per-node arithmetic).
    const int len = end - begin;
    const auto misalign = reinterpret_cast<std::uintptr_t>(dst[0]) % 64;  // a multiple of 8 B
    const int head = std::min(len, static_cast<int>((64 - misalign) % 64 / sizeof(double)));
    const std::size_t n0 = g.index(begin, y);
    if (head > 0) interior_span<Model, TauField, HasForce, ForceField>(in, src, dst, n0, head);
    if (len > head) {
      for (int i = 0; i < Q; ++i) {
        src[i] += head;
        dst[i] += head;
      }
      interior_span<Model, TauField, HasForce, ForceField>(in, src, dst, n0 + head, len - head);
    }
  }
  if (x1 == g.nx) general(g.nx - 1);
}

template <CollisionModel Model, bool TauField, bool HasForce, bool ForceField>
void run_kernel(const KernelArgs& a) {
  const Grid g = a.grid;
  const std::size_t N = g.size();
  NodeInputs in;
  in.tau = a.tau_field;
  in.fx = a.force_x;
  in.fy = a.force_y;
  in.uniform_fx = a.uniform_fx;
  in.uniform_fy = a.uniform_fy;
  in.magic = a.collision.trt_magic;
  in.uniform_rates = rates_for(Model, a.collision.tau, a.collision.trt_magic);
  const bool streaming = uses_streaming_stores(g, a.stores);

#pragma omp parallel if (g.worth_threading())
  {
    alignas(64) double buffer[Q][kChunk];
    const bool prefetch = streaming && team_size() == 1;
#pragma omp for schedule(static)
    for (int y = 0; y < g.ny; ++y) {
      const std::size_t row = g.index(0, y);
      if (!streaming) {  // the whole row straight into the destination
        double* out[Q];
        for (int i = 0; i < Q; ++i) out[i] = a.dst + i * N + row;
        update_chunk<Model, TauField, HasForce, ForceField>(a, in, y, 0, g.nx, out, false);
        continue;
      }
      for (int x0 = 0; x0 < g.nx; x0 += kChunk) {
        const int x1 = std::min(g.nx, x0 + kChunk);
        double* out[Q];
        for (int i = 0; i < Q; ++i) out[i] = buffer[i];
        update_chunk<Model, TauField, HasForce, ForceField>(a, in, y, x0, x1, out, prefetch);
        for (int i = 0; i < Q; ++i) stream_out(a.dst + i * N + row + x0, buffer[i], x1 - x0);
      }
    }
    if (streaming) store_fence();
  }
}

template <CollisionModel Model>
void dispatch_fields(const KernelArgs& a) {
  const bool tau = a.tau_field != nullptr;
  const bool field = a.force_x != nullptr;
  const bool force = field || a.uniform_fx != 0.0 || a.uniform_fy != 0.0;
  if (tau) {
    if (field) return run_kernel<Model, true, true, true>(a);
    if (force) return run_kernel<Model, true, true, false>(a);
    return run_kernel<Model, true, false, false>(a);
  }
  if (field) return run_kernel<Model, false, true, true>(a);
  if (force) return run_kernel<Model, false, true, false>(a);
  return run_kernel<Model, false, false, false>(a);
}

}  // namespace

bool uses_streaming_stores(const Grid& grid, StoreMode mode) {
#if defined(__SSE2__)
  switch (mode) {
    case StoreMode::automatic: return 2 * Q * sizeof(double) * grid.size() > kStreamingFootprintBytes;
    case StoreMode::cached: return false;
    case StoreMode::streaming: return true;
  }
  return false;
#else
  (void)grid;
  (void)mode;
  return false;
#endif
}

void stream_collide(const KernelArgs& args) {
  switch (args.collision.model) {
    case CollisionModel::bgk: return dispatch_fields<CollisionModel::bgk>(args);
    case CollisionModel::trt: return dispatch_fields<CollisionModel::trt>(args);
    case CollisionModel::regularized: return dispatch_fields<CollisionModel::regularized>(args);
  }
}

}  // namespace erythro::fluid::detail
