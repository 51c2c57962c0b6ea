#pragma once
// The fused stream–collide kernel on one in-place lattice: the AA pattern
// (Bailey et al. 2009, ICPP; Wittmann et al. 2013, Comput Math Appl 65:924),
// internal to the fluid layer. docs/performance.md says why it replaced two lattices.
//
// Layouts. Slot s of the array F (nine population arrays `stride` ≥ N apart) holds one
// population; below, k·N stands for k·stride.
//  natural : F[k·N + n] = f*_k(n), the post-collision population k of node n (the layout
//            of FluidLattice::populations(), there with stride N).
//  streamed: the population pulled by node n along j sits in the slot it was pulled
//            from, source_slot(n, j), swapped: F[source_slot(n, j)] = f*_ĵ(n).
// A pull_swap step takes natural to streamed: node n pulls f_j from source_slot(n, j)
// (the pull scheme, docs/model.md §1, with the boundary rules of fluid/boundary.hpp),
// collides, and writes f*_ĵ(n) back into that slot. A local step takes streamed to
// natural: node n's incoming f_j(n) sits at F[ĵ·N + n] (plus the wall term for a
// direction that bounced off a moving wall); it collides and writes F[k·N + n].
// Every slot is read and written by exactly one node per step, so both are in place,
// race-free on any number of threads, and give the bits of a two-lattice pull kernel.
#include <cstddef>
#include <cstdint>

#include "fluid/boundary.hpp"
#include "fluid/collision.hpp"
#include "lattice/d2q9.hpp"
#include "lattice/grid.hpp"

namespace erythro::fluid::detail {

enum class AaStep { pull_swap, local };

// Distance between the nine population arrays in FluidLattice's storage: N rounded up to
// a cache line, plus 4168 doubles (32 KiB and 9 lines). When N is a power of two (1024²,
// 2048²) unpadded arrays start at the same offset modulo a large power of two, and their
// nine streams conflict in the memory system: measured 55–82 % of the copy bound
// unpadded against 88–107 % padded (stand-alone AA loop; docs/performance.md, Summary).
inline constexpr std::size_t kArrayPadding = 4168;
inline constexpr std::size_t padded_stride(std::size_t nodes) { return (nodes + 7) / 8 * 8 + kArrayPadding; }
static_assert(kArrayPadding % 8 == 0, "every population array must start on a cache line");

struct KernelArgs {
  Grid grid;
  double* f = nullptr;  // the lattice: natural before a pull_swap step, streamed before a local step
  std::size_t stride = 0;  // distance between population arrays (≥ N)
  AaStep step = AaStep::pull_swap;
  CollisionConfig collision;
  BoundaryConfig boundaries;
  const double* tau_field = nullptr;  // optional τ(x)
  const double* row_tau = nullptr;    // with τ(x): per row its one τ, or 0 where τ varies; null: per node
  const double* force_x = nullptr;    // optional F(x)
  const double* force_y = nullptr;
  const std::uint8_t* force_rows =
      nullptr;  // with F(x): per row its state (fluid/force_rows.hpp); null: all may hold force
  double uniform_fx = 0.0, uniform_fy = 0.0;
  // Optional (both or none): every node's velocity u, the one its collision relaxed towards
  // (docs/model.md eq 1.3b; the u of FluidLattice::compute_moments after the step up to
  // round-off), so that a caller who needs it everywhere makes no second pass.
  double* velocity_x = nullptr;
  double* velocity_y = nullptr;
};

void stream_collide(const KernelArgs& args);

// Where the pull scheme takes the population streaming into node (x, y) along c_j,
// in the natural layout: from (x, y) − c_j, wrapped across a periodic side; across a
// wall (halfway bounce-back) from the node's own opposite population F[ĵ·N + n], plus
// `wall_term` for a moving wall. A bottom/top wall is crossed first at a corner.
struct Source {
  std::size_t slot;
  const Side* wall;  // the wall crossed, or null
};

inline Source source_slot(const Grid& g, const BoundaryConfig& b, std::size_t stride, int x, int y, int j) {
  const std::size_t N = stride;
  int sx = x - d2q9::cx[j], sy = y - d2q9::cy[j];
  if (sy < 0 || sy >= g.ny) {
    const Side& side = sy < 0 ? b.bottom : b.top;
    if (side.type != SideType::periodic) return {d2q9::opposite[j] * N + g.index(x, y), &side};
    sy = (sy + g.ny) % g.ny;
  }
  if (sx < 0 || sx >= g.nx) {
    const Side& side = sx < 0 ? b.left : b.right;
    if (side.type != SideType::periodic) return {d2q9::opposite[j] * N + g.index(x, y), &side};
    sx = (sx + g.nx) % g.nx;
  }
  return {j * N + g.index(sx, sy), nullptr};
}

// Ladd's moving-wall term of a population bounced along c_j: 2 w_j ρ0 (c_j·u_w)/c_s².
inline double wall_term(const Side& wall, int j) {
  return 2.0 * d2q9::w[j] * d2q9::inv_cs2 * (d2q9::cx[j] * wall.ux + d2q9::cy[j] * wall.uy);
}

// Slot of f*_k(x, y) in the streamed layout: the slot node (x, y) pulled along k̄ from.
inline std::size_t streamed_slot(const Grid& g, const BoundaryConfig& b, std::size_t stride, int x, int y, int k) {
  return source_slot(g, b, stride, x, y, d2q9::opposite[k]).slot;
}

}  // namespace erythro::fluid::detail
