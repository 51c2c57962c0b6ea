// Fused stream–collide on one in-place lattice, the AA pattern (fluid/stream_collide.hpp):
// a pull_swap step (natural → streamed layout) and a local step (streamed → natural)
// alternate. Rows are distributed over OpenMP threads; every slot belongs to exactly one
// node per step, so the result is bitwise identical for any thread count, and equal to
// the two-lattice pull scheme's (solver/tests/fluid/kernel_equivalence_test.cpp).
//
// Performance (docs/performance.md): on large lattices the step is memory bound,
// 144 B per node update (9 doubles read and the same 9 written back). Each node writes
// the cache lines it has just read, so ordinary stores cost no write-allocate read and
// no second lattice is streamed through the cache; the nine arrays are padded apart
// (padded_stride). At 1024² on one thread this moves data at about the copy bandwidth
// (97–122 % of the paired bound) against 57–66 % for the two-lattice kernel with
// non-temporal stores it replaced.
//  - Interior nodes take a branch-free loop over x that the compiler vectorises
//    (nine source streams, each written back in place). Not `omp simd`: GCC 12
//    privatises the node's f[9] per SIMD lane and then cannot vectorise the loop.
//    Rows along a wall take it too, each bounced source being the node's own opposite
//    slot (a moving wall's term added to that slot first); only the first and last node
//    of a row in a pull_swap step (and in a local step beside a moving side wall) take
//    the general path with boundary handling.
//    Each span starts its vector loop at the first cache-line aligned node (the few
//    nodes before it go through the loop's scalar remainder).
//    Both paths collide through the same node_update() → collide_node().
//  - On request (KernelArgs::velocity_*) each node's velocity is written as well: the u its
//    collision relaxed towards (docs/model.md eq 1.3b), already in registers, so 16 B of
//    stores per node and no arithmetic (against summing the nine post-collision populations
//    again, or a separate pass that reads them and the force): the dense immersed cells
//    need the velocity at nearly every node after each step.
//
// Rounding: floating-point contraction is off project-wide (-ffp-contract=off in
// cmake/CompilerSettings.cmake), so every path and thread count gives the same bits, and
// a reference that calls collide_node() reproduces them exactly.

#include "fluid/stream_collide.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "fluid/collide_node.hpp"
#include "fluid/force_rows.hpp"
#include "lattice/d2q9.hpp"

namespace erythro::fluid::detail {
namespace {

using namespace d2q9;

// Per-node inputs of the collision other than the populations.
struct NodeInputs {
  const double* tau = nullptr;  // τ field or null
  const double* fx = nullptr;   // force field or null
  const double* fy = nullptr;
  double uniform_fx = 0.0, uniform_fy = 0.0, magic = 0.0;
  Rates uniform_rates{1.0, 1.0};
  double* ux = nullptr;  // the velocity after the step, or null (KernelArgs::velocity_*)
  double* uy = nullptr;
};

// The collision of node n (streamed populations in f) and, with Velocity, the velocity it
// relaxed towards into ux[n], uy[n] (eq 1.3b). The one place where both the interior and
// the general path compute, so both round identically.
// `flatten` inlines collide_node() here: an out-of-line copy of that header function could
// be taken by the linker from another file compiled with contraction.
template <CollisionModel Model, bool TauField, bool HasForce, bool ForceField, bool Velocity>
[[gnu::flatten]] inline void node_update(const double* tau, const double* fx, const double* fy, std::size_t n,
                                         double ufx, double ufy, double magic, Rates uniform_rates, double* f,
                                         double* ux, double* uy) {
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
  const CollisionVelocity u = collide_node<Model, HasForce>(f, r, Fx, Fy);
  if constexpr (Velocity) {
    ux[n] = u.ux;
    uy[n] = u.uy;
  }
}

// `len` interior nodes n0, n0+1, …: s_i[k] holds the value streaming into node n0+k
// along i, and receives the post-collision value of the opposite direction, s_i[k] ←
// f*_ī (in both AA steps the slot a population came from takes its opposite back; see
// stream_collide.hpp). Nine streams, each read and then written at the same index: no
// dependence between iterations (ivdep), no branches, so the loop vectorises along x.
// With Velocity, each node's collision velocity too (eq 1.3b).
template <CollisionModel Model, bool TauField, bool HasForce, bool ForceField, bool Velocity>
void interior_span(const NodeInputs& in, double* const* src, std::size_t n0, int len) {
  double* s0 = src[0];
  double* s1 = src[1];
  double* s2 = src[2];
  double* s3 = src[3];
  double* s4 = src[4];
  double* s5 = src[5];
  double* s6 = src[6];
  double* s7 = src[7];
  double* s8 = src[8];
  const double* __restrict tau = TauField ? in.tau + n0 : nullptr;
  const double* __restrict fx = ForceField ? in.fx + n0 : nullptr;
  const double* __restrict fy = ForceField ? in.fy + n0 : nullptr;
  double* __restrict ux = Velocity ? in.ux + n0 : nullptr;
  double* __restrict uy = Velocity ? in.uy + n0 : nullptr;
  const double ufx = in.uniform_fx, ufy = in.uniform_fy, magic = in.magic;
  const Rates ur = in.uniform_rates;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
  for (int k = 0; k < len; ++k) {
    double f[Q] = {s0[k], s1[k], s2[k], s3[k], s4[k], s5[k], s6[k], s7[k], s8[k]};
    node_update<Model, TauField, HasForce, ForceField, Velocity>(tau, fx, fy, static_cast<std::size_t>(k), ufx, ufy,
                                                                 magic, ur, f, ux, uy);
    // opposite = {0, 3, 4, 1, 2, 7, 8, 5, 6}
    s0[k] = f[0];
    s3[k] = f[1];
    s4[k] = f[2];
    s1[k] = f[3];
    s2[k] = f[4];
    s7[k] = f[5];
    s8[k] = f[6];
    s5[k] = f[7];
    s6[k] = f[8];
  }
}

template <AaStep Step, CollisionModel Model, bool TauField, bool HasForce, bool ForceField, bool Velocity>
void update_row(const KernelArgs& a, const NodeInputs& in, int y) {
  const Grid& g = a.grid;
  const std::size_t N = a.stride;  // distance between the population arrays
  double* const F = a.f;
  // A node next to the boundary: nine general pulls (unrolled, so c_i are constants).
  auto general = [&](int x) __attribute__((always_inline)) {
    const std::size_t n = g.index(x, y);
    double f[Q];
    std::size_t slot[Q];
#pragma GCC unroll 9
    for (int i = 0; i < Q; ++i) {
      const Source s = source_slot(g, a.boundaries, N, x, y, i);
      slot[i] = s.slot;
      // pull_swap reads the natural layout where the pull scheme would; the local step
      // finds every incoming population at F[ī·N + n] (stream_collide.hpp).
      double value = Step == AaStep::pull_swap ? F[s.slot] : F[opposite[i] * N + n];
      // Halfway bounce-back: f_i(x, t+1) = f*_ī(x, t) + 2 w_i ρ0 (c_i·u_w)/c_s².
      if (s.wall && s.wall->type == SideType::moving_wall) value += wall_term(*s.wall, i);
      f[i] = value;
    }
    node_update<Model, TauField, HasForce, ForceField, Velocity>(in.tau, in.fx, in.fy, n, in.uniform_fx,
                                                                 in.uniform_fy, in.magic, in.uniform_rates, f, in.ux,
                                                                 in.uy);
#pragma GCC unroll 9
    for (int i = 0; i < Q; ++i) {
      if constexpr (Step == AaStep::pull_swap) {
        F[slot[i]] = f[opposite[i]];
      } else {
        F[i * N + n] = f[i];
      }
    }
  };
  if (g.nx < 3) {
    for (int x = 0; x < g.nx; ++x) general(x);
    return;
  }
  // The row's run of nodes that the vector loop takes: every node whose nine sources are each
  // a contiguous stream along x (docs/performance-coupled-step.md, "Wall rows in the vector loop"). A
  // pull_swap step's first and last nodes wrap across a periodic side or bounce off a side
  // wall, so they take the general path; a local step reads every node's own slots, so only a
  // side with a wall term (moving) keeps its end node general.
  const bool ends_general = Step == AaStep::pull_swap || a.boundaries.left.type == SideType::moving_wall ||
                            a.boundaries.right.type == SideType::moving_wall;
  const int begin = ends_general ? 1 : 0, end = ends_general ? g.nx - 1 : g.nx;
  if (ends_general) general(0);
  double* src[Q];
  const std::size_t n0 = g.index(begin, y);
  for (int i = 0; i < Q; ++i) {
    // Across the bottom or top (only on rows 0 and ny − 1): wrapped when periodic, else the
    // halfway bounce-back's own opposite slot F[ī·N + n] (source_slot, stream_collide.hpp).
    const int sy = y - cy[i];
    const Side* crossed = sy < 0 ? &a.boundaries.bottom : sy >= g.ny ? &a.boundaries.top : nullptr;
    const bool bounced = crossed != nullptr && crossed->type != SideType::periodic;
    if (Step == AaStep::local || bounced) {
      src[i] = F + opposite[i] * N + n0;
    } else {
      src[i] = F + i * N + g.index(begin - cx[i], (sy + g.ny) % g.ny);
    }
    // A moving wall's term goes into the bounced value before the loop reads it: the slot
    // then holds F[ī·N + n] + wall_term, the general path's sum, which the collision
    // overwrites (the slot is node n's alone in both steps).
    if (bounced && crossed->type == SideType::moving_wall) {
      const double term = wall_term(*crossed, i);
      double* slot = src[i];
      for (int k = 0; k < end - begin; ++k) slot[k] += term;
    }
  }
  // Split off the head up to the first cache-line aligned node of s_0 (the same
  // per-node arithmetic), so the vector loop's aligned streams never straddle two lines.
  const int len = end - begin;
  const auto misalign = reinterpret_cast<std::uintptr_t>(src[0]) % 64;  // a multiple of 8 B
  const int head = std::min(len, static_cast<int>((64 - misalign) % 64 / sizeof(double)));
  if (head > 0) interior_span<Model, TauField, HasForce, ForceField, Velocity>(in, src, n0, head);
  if (len > head) {
    for (int i = 0; i < Q; ++i) src[i] += head;
    interior_span<Model, TauField, HasForce, ForceField, Velocity>(in, src, n0 + head, len - head);
  }
  if (ends_general) general(g.nx - 1);
}

// Row y with the kernel variant its inputs need: τ node by node only where the row's τ
// varies, the force field only on rows that may hold force (docs/performance-coupled-step.md,
// "Quiet rows"). A skipped zero force or a row's one τ gives the same values.
template <AaStep Step, CollisionModel Model, bool Velocity>
void update_row_variant(const KernelArgs& a, const NodeInputs& in, int y, bool tau, bool field, bool force) {
  if (tau) {
    if (field) return update_row<Step, Model, true, true, true, Velocity>(a, in, y);
    if (force) return update_row<Step, Model, true, true, false, Velocity>(a, in, y);
    return update_row<Step, Model, true, false, false, Velocity>(a, in, y);
  }
  if (field) return update_row<Step, Model, false, true, true, Velocity>(a, in, y);
  if (force) return update_row<Step, Model, false, true, false, Velocity>(a, in, y);
  return update_row<Step, Model, false, false, false, Velocity>(a, in, y);
}

template <AaStep Step, CollisionModel Model>
void run_kernel(const KernelArgs& a) {
  const Grid g = a.grid;
  NodeInputs base;
  base.tau = a.tau_field;
  base.fx = a.force_x;
  base.fy = a.force_y;
  base.uniform_fx = a.uniform_fx;
  base.uniform_fy = a.uniform_fy;
  base.magic = a.collision.trt_magic;
  base.uniform_rates = rates_for(Model, a.collision.tau, a.collision.trt_magic);
  base.ux = a.velocity_x;
  base.uy = a.velocity_y;
  const bool velocity = a.velocity_x != nullptr;
  const bool uniform_force = a.uniform_fx != 0.0 || a.uniform_fy != 0.0;
#pragma omp parallel for schedule(static) if (g.worth_threading())
  for (int y = 0; y < g.ny; ++y) {
    const bool field = a.force_x != nullptr && (a.force_rows == nullptr || a.force_rows[y] == force_row::kForced);
    const bool tau = a.tau_field != nullptr && (a.row_tau == nullptr || a.row_tau[y] == 0.0);
    NodeInputs in = base;
    if (a.tau_field != nullptr && !tau) in.uniform_rates = rates_for(Model, a.row_tau[y], a.collision.trt_magic);
    if (velocity) update_row_variant<Step, Model, true>(a, in, y, tau, field, field || uniform_force);
    else update_row_variant<Step, Model, false>(a, in, y, tau, field, field || uniform_force);
  }
}

template <AaStep Step>
void dispatch_model(const KernelArgs& a) {
  switch (a.collision.model) {
    case CollisionModel::bgk: return run_kernel<Step, CollisionModel::bgk>(a);
    case CollisionModel::trt: return run_kernel<Step, CollisionModel::trt>(a);
    case CollisionModel::regularized: return run_kernel<Step, CollisionModel::regularized>(a);
  }
}

}  // namespace

void stream_collide(const KernelArgs& args) {
  if (args.stride < args.grid.size()) throw std::invalid_argument("stream_collide: population arrays overlap");
  if ((args.velocity_x == nullptr) != (args.velocity_y == nullptr))
    throw std::invalid_argument("stream_collide: the velocity outputs are both or none");
  if (args.step == AaStep::pull_swap) return dispatch_model<AaStep::pull_swap>(args);
  return dispatch_model<AaStep::local>(args);
}

}  // namespace erythro::fluid::detail
