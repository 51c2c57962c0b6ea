#pragma once
// The fused pull stream–collide kernel of the transport lattice (internal).
#include <cstddef>
#include <span>
#include <vector>

#include "lattice/grid.hpp"
#include "transport/stencils.hpp"
#include "transport/transport_lattice.hpp"

namespace erythro::transport::detail {

struct KernelArgs {
  Grid grid;
  Stencil stencil = Stencil::d2q5;
  TransportBoundaries boundaries;
  const double* src = nullptr;  // post-collision populations of step t, [i*N + n]
  double* dst = nullptr;        // post-collision populations of step t+1
  double* C = nullptr;          // concentration of the collision (out)
  double uniform_D = 0.0;
  bool trt = false;    // collision: BGK (T3) or TRT with magic parameter Λ (T3')
  double magic = 0.25;
  // optional per-node D, as the relaxation rates it sets (relaxation_rates below)
  const double* omega = nullptr;       // ω = ω⁻ (TRT)
  const double* omega_plus = nullptr;  // ω⁺ (TRT; = ω for BGK)
  // optional per-node diffusivity tensor (D2Q5 TRT only, eq T8); replaces D when set
  const double* Dxx = nullptr;
  const double* Dyy = nullptr;
  const double* Dxy = nullptr;
  const double* source = nullptr;  // optional q
  const double* decay = nullptr;   // optional k (only with q; null: k = 0)
  const double* ux = nullptr;  // optional velocity (both or neither)
  const double* uy = nullptr;
  // Axisymmetric lattice (docs/model.md eq 7.10): the radius of each row (size ny) and of the
  // bottom and top sides; null for a planar lattice. The kernel carries φ = r C and writes φ to C.
  const double* row_radius = nullptr;
  double bottom_radius = 0.0, top_radius = 0.0;
  // TRT with a source (eq 7.9): the antisymmetric source carries the velocity times Λ⁺/Λ⁻, per
  // node with a D field, else the uniform value.
  const double* source_velocity_scale = nullptr;
  double uniform_source_velocity_scale = 1.0;
  // Per-row accumulators (size ny): Σ q_tot, boundary inflow, Σ Σ_i g*_i, Σ |Σ_i g*_i|.
  double* row_source = nullptr;
  double* row_boundary = nullptr;
  double* row_amount = nullptr;
  double* row_scale = nullptr;
};

void stream_collide(const KernelArgs& args);

// The sides as a row at radius r of an axisymmetric lattice sees them (eq 7.10): a concentration
// or an inward flux on a side at radius R enters the φ = r C lattice as R times the value (the
// bottom and top sides at their radius, the left and right ones at the row's).
inline TransportBoundaries weighted_sides(TransportBoundaries b, double row_r, double bottom_r, double top_r) {
  b.left.value *= row_r;
  b.right.value *= row_r;
  b.bottom.value *= bottom_r;
  b.top.value *= top_r;
  return b;
}
inline TransportBoundaries row_sides(const KernelArgs& a, int y) {
  if (a.row_radius == nullptr) return a.boundaries;
  return weighted_sides(a.boundaries, a.row_radius[y], a.bottom_radius, a.top_radius);
}

// The relaxation rates of the collision at each node of a per-node D (resized to D's size).
void relaxation_rates(std::span<const double> D, bool trt, double magic, std::vector<double>& omega,
                      std::vector<double>& omega_plus);

// Value streamed into node (x, y) along direction i (boundary rules of
// transport_lattice.hpp; a bottom/top side takes precedence at corners, as in the
// fluid). `inflow` gains (value − g*_ī(x, y)) when the value comes from a side.
template <class S>
[[gnu::always_inline]] inline double pull(const Grid& g, const TransportBoundaries& b, const double* src, int x, int y,
                                          int i, double& inflow) {
  const std::size_t N = g.size();
  int sx = x - S::cx[i], sy = y - S::cy[i];
  const Side* side = nullptr;
  if (sy < 0 || sy >= g.ny) {
    const Side& s = sy < 0 ? b.bottom : b.top;
    if (s.kind == SideKind::periodic) {
      sy = (sy + g.ny) % g.ny;
    } else {
      side = &s;
    }
  }
  if (!side && (sx < 0 || sx >= g.nx)) {
    const Side& s = sx < 0 ? b.left : b.right;
    if (s.kind == SideKind::periodic) {
      sx = (sx + g.nx) % g.nx;
    } else {
      side = &s;
    }
  }
  if (!side) return src[i * N + g.index(sx, sy)];
  const double out = src[S::opposite[i] * N + g.index(x, y)];  // g*_ī leaving through the side
  double in = out;                                               // zero_flux: bounce-back
  switch (side->kind) {
    case SideKind::fixed_concentration: in = -out + 2.0 * S::w[i] * side->value; break;  // anti-bounce-back
    // The crossing weights sum to 1/6 on both stencils: Σ_crossing (6 w_i J) = J.
    case SideKind::fixed_flux: in = out + 6.0 * S::w[i] * side->value; break;
    default: break;
  }
  inflow += in - out;
  return in;
}

}  // namespace erythro::transport::detail
