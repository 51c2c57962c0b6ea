#pragma once
// ρ and u of one node from its nine post-collision populations (docs/model.md eq 1.3),
// the one place this is computed: FluidLattice::compute_moments and node_moments after a
// step, so that both give the same bits. (The stream–collide kernel's velocity output is
// the collision's own u, eq 1.3b: the same value up to round-off.) Internal to the fluid
// layer.
#include <cstddef>
#include <type_traits>
#include <utility>

#include "lattice/d2q9.hpp"

namespace erythro::fluid::detail {

// pop(i): the post-collision population f̃*_i (a deviation from w_i); F the force of that
// collision. ρ = 1 + Σ f̃*, ρu = Σ c f* − F/2 (Guo forcing: Σ c f* = ρu + F/2). The sums run
// over i = 0 … 8 in order, unrolled at compile time (no loop over an array, so that a loop
// over nodes around it vectorises).
template <class Population>
[[gnu::always_inline]] inline void moments_of(const Population& pop, double Fx, double Fy, double& rho, double& ux,
                                              double& uy) {
  double dr = 0.0, jx = 0.0, jy = 0.0;
  // A term with c = 0 is left out: the sums start at +0, and a sum is −0 only when both its
  // terms are, so jx and jy are never −0 and adding 0·f (±0) never changes them: the same bits.
  auto add = [&]<std::size_t I>(std::integral_constant<std::size_t, I>) {
    dr += pop(I);
    if constexpr (d2q9::cx[I] != 0) jx += d2q9::cx[I] * pop(I);
    if constexpr (d2q9::cy[I] != 0) jy += d2q9::cy[I] * pop(I);
  };
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (add(std::integral_constant<std::size_t, I>{}), ...);
  }(std::make_index_sequence<d2q9::Q>{});
  const double r = 1.0 + dr;
  const double inv_r = 1.0 / r;  // one division for both components
  rho = r;
  ux = (jx - 0.5 * Fx) * inv_r;
  uy = (jy - 0.5 * Fy) * inv_r;
}

}  // namespace erythro::fluid::detail
