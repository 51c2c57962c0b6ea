// Boundary conditions of the transport lattice (transport_lattice.hpp): steady linear
// profiles that the halfway rules reproduce exactly, conservation with zero flux, the
// face fluxes (eq T6), periodic wrap.
#include <gtest/gtest.h>

#include <cmath>

#include "transport/transport_lattice.hpp"

using namespace erythro;
using namespace erythro::transport;

namespace {
// Node row y sits at y + ½; sides at 0 and H = ny.
void run_to_steady(TransportLattice& lat, int max_steps) {
  for (int s = 0; s < max_steps; ++s) lat.step();
}
TransportBoundaries channel(Side bottom, Side top) {
  TransportBoundaries b;
  b.bottom = bottom;
  b.top = top;
  return b;
}
}  // namespace

TEST(TransportBoundary, FixedConcentrationGivesExactLinearProfile) {
  // C(0) = 1, C(H) = 3: C = 1 + 2 y/H at y = j + ½, for several τ and both stencils.
  for (auto st : {Stencil::d2q5, Stencil::d2q9}) {
    for (double D : {0.05, 1.0 / 6.0, 0.6}) {
      const int H = 10;
      TransportLattice lat(Grid{3, H}, st,
                           channel({SideKind::fixed_concentration, 1.0}, {SideKind::fixed_concentration, 3.0}));
      lat.set_uniform_diffusivity(D);
      lat.initialize_uniform(0.0);
      run_to_steady(lat, 40000);
      for (int j = 0; j < H; ++j) {
        EXPECT_NEAR(lat.concentration()[lat.grid().index(1, j)], 1.0 + 2.0 * (j + 0.5) / H, 1e-11) << "D=" << D;
      }
      // Face flux: −D dC/dy = −2D/H through every north face, the sides included.
      std::vector<double> e(lat.grid().size()), n(lat.grid().size());
      lat.face_flux(e, n);
      for (int j = 0; j < H; ++j) EXPECT_NEAR(n[lat.grid().index(1, j)], -2.0 * D / H, 1e-12);
      EXPECT_NEAR(e[0], 0.0, 1e-14);
    }
  }
}

TEST(TransportBoundary, FixedFluxGivesPrescribedGradient) {
  // Inward flux J at the bottom, C = 0 at the top: C = J (H − y)/D; every face carries J.
  for (auto st : {Stencil::d2q5, Stencil::d2q9}) {
    const int H = 12;
    const double J = 0.01, D = 0.1;
    TransportLattice lat(Grid{4, H}, st, channel({SideKind::fixed_flux, J}, {SideKind::fixed_concentration, 0.0}));
    lat.set_uniform_diffusivity(D);
    lat.initialize_uniform(0.0);
    run_to_steady(lat, 40000);
    for (int j = 0; j < H; ++j) {
      EXPECT_NEAR(lat.concentration()[lat.grid().index(2, j)], J * (H - (j + 0.5)) / D, 1e-11);
    }
    std::vector<double> e(lat.grid().size()), n(lat.grid().size());
    lat.face_flux(e, n);
    for (int j = 0; j < H; ++j) EXPECT_NEAR(n[lat.grid().index(2, j)], J, 1e-13);
    EXPECT_NEAR(lat.mass_balance().boundary_in, 0.0, 1e-12);  // steady: in = out
  }
}

TEST(TransportBoundary, ZeroFluxConservesAmountExactly) {
  TransportBoundaries b{{SideKind::zero_flux}, {SideKind::zero_flux}, {SideKind::zero_flux}, {SideKind::zero_flux}};
  for (auto st : {Stencil::d2q5, Stencil::d2q9}) {
    const Grid g{9, 11};
    TransportLattice lat(g, st, b);
    std::vector<double> C(g.size());
    for (std::size_t n = 0; n < g.size(); ++n) C[n] = (n % 5 == 0) ? 4.0 : 0.5;
    lat.initialize(C);
    const double M0 = lat.stored_amount();
    for (int s = 0; s < 2000; ++s) {
      lat.step();
      EXPECT_EQ(lat.mass_balance().boundary_in, 0.0);
    }
    EXPECT_NEAR(lat.stored_amount(), M0, 1e-13 * M0);
    // Diffused to the mean.
    for (double c : lat.concentration()) EXPECT_NEAR(c, M0 / double(g.size()), 1e-3);
  }
}

TEST(TransportBoundary, PeriodicAdvectionMovesAPulse) {
  // u = 1 lattice speed... at u = 0.1 for 100 steps a pulse moves 10 nodes.
  const Grid g{40, 1};
  TransportLattice lat(g, Stencil::d2q5, {});
  lat.set_uniform_diffusivity(0.01);
  lat.set_uniform_velocity(0.1, 0.0);
  std::vector<double> C(g.size(), 0.0);
  for (int x = 0; x < 40; ++x) C[x] = std::exp(-0.5 * std::pow((x - 5.0) / 2.0, 2));
  lat.initialize(C);
  for (int s = 0; s < 100; ++s) lat.step();
  double mx = 0, m = 0;
  for (int x = 0; x < 40; ++x) {
    mx += x * lat.concentration()[x];
    m += lat.concentration()[x];
  }
  EXPECT_NEAR(mx / m, 15.0, 0.05);
}
