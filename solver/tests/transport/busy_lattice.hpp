#pragma once
// A transport lattice with every ingredient, for the unit tests of the mass balance and of
// the collision operators: non-periodic sides of each kind, a velocity field, sources and
// sinks, a random initial field; D uniform (d_field = false) or random per node.
#include <random>
#include <vector>

#include "transport/transport_lattice.hpp"

namespace erythro::transport::test_support {

inline TransportLattice busy_lattice(Stencil st, CollisionModel c, double D, bool d_field, Grid g = Grid{19, 13}) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  TransportBoundaries b{{SideKind::fixed_concentration, 0.3},
                        {SideKind::fixed_flux, -0.01},
                        {SideKind::zero_flux},
                        {SideKind::fixed_concentration, 1.2}};
  TransportLattice lat(g, st, b);
  lat.set_collision(c);
  lat.set_uniform_diffusivity(D);
  std::vector<double> C(g.size()), ux(g.size()), uy(g.size());
  for (std::size_t n = 0; n < g.size(); ++n) {
    C[n] = u01(rng);
    ux[n] = 0.05 * (u01(rng) - 0.5);
    uy[n] = 0.05 * (u01(rng) - 0.5);
  }
  lat.set_velocity(ux, uy);
  for (auto& q : lat.source()) q = 0.01 * (u01(rng) - 0.3);
  for (auto& k : lat.decay_rate()) k = 0.05 * u01(rng);
  if (d_field)
    for (auto& d : lat.diffusivity()) d = 0.02 + 0.3 * u01(rng);
  lat.initialize(C);
  return lat;
}

}  // namespace erythro::transport::test_support
