// Hb–O2 kinetics (hb_kinetics.hpp, eqs H1–H2): equilibrium, exactness, stiffness,
// mass closure alone and coupled to a closed transport lattice.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "transport/hb_kinetics.hpp"
#include "transport/transport_lattice.hpp"

using namespace erythro;
using namespace erythro::transport;

TEST(HbKinetics, EquilibriumIsStationary) {
  HbParameters p;
  for (double P : {5.0, 26.8, 70.0}) {
    const double S = hill_saturation(P);
    const HbStep s = advance_saturation(p, S, P, 1e-3);
    EXPECT_NEAR(s.saturation, S, 1e-15);
    EXPECT_NEAR(s.released, 0.0, 1e-15 * p.C_heme);
  }
}

TEST(HbKinetics, MatchesExactExponentialAtFixedP) {
  HbParameters p;
  p.M = 3.0;
  const double P = 20.0, S0 = 0.98, dt = 1e-3;
  const double lambda = p.k_off * (1.0 + std::pow(P / p.P50, p.n)) / p.M;
  EXPECT_NEAR(hb_relaxation_rate(p, P), lambda, 1e-12);
  double S = S0, released = 0.0;
  for (int k = 0; k < 50; ++k) {
    const HbStep s = advance_saturation(p, S, P, dt);
    released += s.released;
    S = s.saturation;
  }
  const double Seq = hill_saturation(P);
  const double exact = Seq + (S0 - Seq) * std::exp(-lambda * 50 * dt);
  EXPECT_NEAR(S, exact, 1e-13);
  EXPECT_NEAR(released, p.C_heme * (S0 - S), 1e-9);  // µM, round-off of 50 steps
  EXPECT_GT(released, 0.0);                        // de-oxygenation releases O2
}

TEST(HbKinetics, StiffStepLandsOnEquilibriumWithoutOvershoot) {
  HbParameters p;
  const double P = 10.0, Seq = hill_saturation(P);
  for (double dt : {0.1, 1.0, 1e3}) {  // λ dt from ~5 to ~5e4
    const HbStep s = advance_saturation(p, 0.97, P, dt);
    EXPECT_GE(s.saturation, Seq - 1e-15);
    EXPECT_LE(s.saturation, 0.97);
    if (dt >= 1.0) {
      EXPECT_NEAR(s.saturation, Seq, 1e-15);
    }
  }
  // From below (uptake): S rises to S_eq, released < 0.
  const HbStep up = advance_saturation(p, 0.01, 70.0, 10.0);
  EXPECT_NEAR(up.saturation, hill_saturation(70.0), 1e-15);
  EXPECT_LT(up.released, 0.0);
  // Modifier and stress coefficient scale the rate.
  HbParameters slow = p;
  slow.M = 4.0;
  HbParameters fast = p;
  fast.sigma = 4.0;
  EXPECT_NEAR(hb_relaxation_rate(slow, P) * 16.0, hb_relaxation_rate(fast, P), 1e-9);
  // M must be positive (M < 1 is allowed: a faster release than plain kinetics).
  EXPECT_THROW(advance_saturation(HbParameters{.M = 0.0}, 0.5, 10.0, 1.0), std::invalid_argument);
  EXPECT_NO_THROW(advance_saturation(HbParameters{.M = 0.5}, 0.5, 10.0, 1.0));
}

TEST(HbKinetics, CoupledReleaseClosesMassInAClosedBox) {
  // One 'cell' of 16 nodes in a closed box (zero flux): free O2 (lattice amount M)
  // plus bound O2 (C_heme S × cell nodes) is conserved to round-off, step by step.
  // Lattice units: concentration µM, dt = 1e-5 s per step.
  const Grid g{12, 12};
  TransportBoundaries closed{{SideKind::zero_flux}, {SideKind::zero_flux}, {SideKind::zero_flux}, {SideKind::zero_flux}};
  TransportLattice o2(g, Stencil::d2q5, closed);
  o2.set_uniform_diffusivity(0.3);
  o2.initialize_uniform(20.0);  // µM, the thesis' calibration medium
  std::vector<std::size_t> cell;
  for (int y = 4; y < 8; ++y)
    for (int x = 4; x < 8; ++x) cell.push_back(g.index(x, y));
  HbParameters p;
  const double dt = 1e-5;
  double S = 0.97;
  const double total0 = o2.stored_amount() + p.C_heme * S * double(cell.size());
  double worst = 0.0;
  for (int k = 0; k < 300; ++k) {
    auto q = o2.source();
    std::fill(q.begin(), q.end(), 0.0);
    const double P = mean_partial_pressure(cell, o2.concentration(), p.alpha);
    const HbStep s = advance_saturation(p, S, P, dt);
    distribute_release(cell, s.released, q);
    S = s.saturation;
    o2.step();
    EXPECT_NEAR(o2.mass_balance().source, s.released * double(cell.size()), 1e-12 * total0);
    const double total = o2.stored_amount() + p.C_heme * S * double(cell.size());
    worst = std::max(worst, std::fabs(total - total0) / total0);
  }
  EXPECT_LT(worst, 1e-14);
  EXPECT_LT(S, 0.97);  // the cell did release
}

TEST(HbKinetics, CellImplicitSolvesItsEquation) {
  // S_new = H2(S, P + C_heme (S − S_new)/α): the returned value satisfies it to
  // round-off, releases C_heme (S − S_new), and keeps an equilibrium stationary.
  HbParameters p;
  for (double dt : {1e-6, 1e-4, 1e-2}) {
    const double S = 0.97, P = 10.0;
    const HbStep r = advance_saturation_cell_implicit(p, S, P, dt);
    const double P_end = P + p.C_heme * (S - r.saturation) / p.alpha;
    EXPECT_NEAR(r.saturation, advance_saturation(p, S, P_end, dt).saturation, 1e-13) << dt;
    EXPECT_NEAR(r.released, p.C_heme * (S - r.saturation), 1e-9);
    EXPECT_LE(r.saturation, S);
    EXPECT_GE(r.saturation, hill_saturation(P));
  }
  const double Seq = hill_saturation(40.0);
  EXPECT_NEAR(advance_saturation_cell_implicit(p, Seq, 40.0, 1e-3).saturation, Seq, 1e-15);
}
