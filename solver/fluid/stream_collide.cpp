// Fused stream–collide, pull scheme (model.md §1): node n gathers f_i from
// n − c_i in the source lattice (post-collision values of the previous step),
// collides, and writes its own nine post-collision values to the destination.
// Rows are distributed over OpenMP threads; every node is independent, so the
// result is bitwise identical for any thread count.
//
// Interior nodes take a branch-free path the compiler vectorises along x; the
// outermost rows and columns take the general path with boundary handling.
#include "fluid/stream_collide.hpp"

#include "fluid/collide_node.hpp"
#include "lattice/d2q9.hpp"

namespace erythro::fluid::detail {
namespace {

using namespace d2q9;

// Value streamed into node (x, y) along direction i, following the boundary rules
// of fluid/boundary.hpp. A wall on the bottom/top takes precedence at corners.
inline double pull_general(const KernelArgs& a, int x, int y, int i) {
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

template <CollisionModel Model, bool TauField, bool HasForce, bool ForceField>
inline void finish_node(const KernelArgs& a, std::size_t n, double* f, Rates uniform_rates) {
  const Rates r = TauField ? rates_for(Model, a.tau_field[n], a.collision.trt_magic) : uniform_rates;
  double Fx = 0.0, Fy = 0.0;
  if constexpr (HasForce) {
    Fx = a.uniform_fx;
    Fy = a.uniform_fy;
    if constexpr (ForceField) {
      Fx += a.force_x[n];
      Fy += a.force_y[n];
    }
  }
  collide_node<Model, HasForce>(f, r, Fx, Fy);
  const std::size_t N = a.grid.size();
#pragma GCC unroll 9
  for (int i = 0; i < Q; ++i) a.dst[i * N + n] = f[i];
}

template <CollisionModel Model, bool TauField, bool HasForce, bool ForceField>
void run_kernel(const KernelArgs& a) {
  const Grid g = a.grid;
  const std::size_t N = g.size();
  const Rates uniform_rates = rates_for(Model, a.collision.tau, a.collision.trt_magic);

#pragma omp parallel for schedule(static) if (g.worth_threading())
  for (int y = 0; y < g.ny; ++y) {
    const bool edge_row = (y == 0 || y == g.ny - 1);
    if (edge_row || g.nx < 3) {
      for (int x = 0; x < g.nx; ++x) {
        double f[Q];
        for (int i = 0; i < Q; ++i) f[i] = pull_general(a, x, y, i);
        finish_node<Model, TauField, HasForce, ForceField>(a, g.index(x, y), f, uniform_rates);
      }
      continue;
    }
    // Row pointers shifted so that src_row[i][x] is the value streaming into (x, y).
    const double* src_row[Q];
    for (int i = 0; i < Q; ++i) {
      src_row[i] = a.src + i * N + g.index(0, y - cy[i]) - cx[i];
    }
    for (int x : {0, g.nx - 1}) {
      double f[Q];
      for (int i = 0; i < Q; ++i) f[i] = pull_general(a, x, y, i);
      finish_node<Model, TauField, HasForce, ForceField>(a, g.index(x, y), f, uniform_rates);
    }
    const std::size_t row = g.index(0, y);
#pragma omp simd
    for (int x = 1; x < g.nx - 1; ++x) {
      double f[Q];
#pragma GCC unroll 9
      for (int i = 0; i < Q; ++i) f[i] = src_row[i][x];
      finish_node<Model, TauField, HasForce, ForceField>(a, row + x, f, uniform_rates);
    }
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

void stream_collide(const KernelArgs& args) {
  switch (args.collision.model) {
    case CollisionModel::bgk: return dispatch_fields<CollisionModel::bgk>(args);
    case CollisionModel::trt: return dispatch_fields<CollisionModel::trt>(args);
  }
}

}  // namespace erythro::fluid::detail
