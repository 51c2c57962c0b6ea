// Transport units (transport_units.hpp) and compartments (compartments.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "transport/compartments.hpp"
#include "transport/reactions.hpp"
#include "transport/time_coupling.hpp"
#include "transport/transport_units.hpp"

using namespace erythro;
using namespace erythro::transport;

TEST(TransportUnits, Conversions) {
  const TransportUnits u{0.2, 1e-5};  // thesis ch. V: 0.2 µm, 10 µs
  EXPECT_NEAR(u.diffusivity(3300.0), 0.825, 1e-12);
  EXPECT_NEAR(u.tau(3300.0), 0.5 + 3 * 0.825, 1e-12);
  EXPECT_NEAR(u.rate(2842.0), 0.02842, 1e-15);
  EXPECT_NEAR(u.source(50.0), 5e-4, 1e-18);
  EXPECT_NEAR(u.flux(10.0), 5e-4, 1e-18);
  EXPECT_NEAR(u.velocity(1000.0), 0.05, 1e-15);
  EXPECT_NEAR(dt_for_tau(0.2, 3300.0, u.tau(3300.0)), 1e-5, 1e-18);
  EXPECT_TRUE(check_transport_units(u, 3300.0, 2842.0, 1000.0).empty());
}

TEST(TransportUnits, ChecksNameEachViolation) {
  const TransportUnits tiny_dt{0.2, 1e-8};  // τ − ½ = 0.0025
  const auto p = check_transport_units(tiny_dt, 3300.0, 0.0, 0.0);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("tau"), std::string::npos);
  const TransportUnits big_dt{0.2, 1e-3};  // τ = 247; k dt = 2.8; u = 5
  EXPECT_EQ(check_transport_units(big_dt, 3300.0, 2842.0, 1000.0).size(), 3u);
}

TEST(Compartments, DiffusivitiesAndReactionsPerNode) {
  const Grid g{5, 1};
  const std::vector<std::uint8_t> ids = {0, 1, 2, 3, 4};  // plasma, rbc, EC, SM, tissue
  const NoO2Model m = NoO2Model::arteriole_defaults();
  const TransportUnits u{0.2, 1e-5};
  TransportLattice no(g, Stencil::d2q5, {}), o2(g, Stencil::d2q5, {});
  no.initialize_uniform(0.027);  // µM = C_ref
  o2.initialize_uniform(1.3 * 4.7);  // P = K_m,eNOS = 4.7 Torr
  apply_diffusivities(m, ids, u, no, o2);
  EXPECT_NEAR(no.diffusivity()[0], 0.825, 1e-12);
  EXPECT_NEAR(o2.diffusivity()[4], 0.7, 1e-12);
  update_reactions(m, ids, u, no, o2);
  // Plasma: nothing.
  EXPECT_EQ(no.source()[0], 0.0);
  EXPECT_EQ(no.decay_rate()[0], 0.0);
  EXPECT_EQ(o2.decay_rate()[0], 0.0);
  // RBC: NO scavenging 2842 1/s.
  EXPECT_NEAR(no.decay_rate()[1], u.rate(no_scavenging_rate()), 1e-15);
  // EC: NO source R1 = 25 µM/s at P = K_m; the O2 sink k C equals it (1:1).
  EXPECT_NEAR(no.source()[2], u.source(25.0), 1e-15);
  EXPECT_NEAR(o2.decay_rate()[2] * o2.concentration()[2], u.source(25.0), 1e-15);
  // SM: NO 1 1/s; O2 Q = Q_max P/(P + 2 K_m) at C_NO = C_ref.
  EXPECT_NEAR(no.decay_rate()[3], u.rate(1.0), 1e-18);
  EXPECT_NEAR(o2.decay_rate()[3] * o2.concentration()[3], u.source(o2_consumption(4.7, 0.027, 5.0)), 1e-15);
  EXPECT_NEAR(o2.decay_rate()[4] * o2.concentration()[4], u.source(o2_consumption(4.7, 0.027, 50.0)), 1e-15);
}

TEST(TimeCoupling, SubcyclesTheFluidForThesisParameters) {
  // h = 0.15 µm, plasma ν = 1.2 cP / 1.025 g/cm³ ≈ 1.17e6 µm²/s at τ_f = 1.
  const double h = 0.15, nu = 1.2e-3 / 1025.0 * 1e12, dt_f = 0.5 / 3.0 * h * h / nu;
  const TimeCoupling c = plan_time_coupling(dt_f, h, 3300.0, 1.0);
  EXPECT_EQ(c.transport_per_fluid, 1);
  EXPECT_GT(c.fluid_per_transport, 300);  // ν/D ≈ 355
  EXPECT_LE(c.tau_max, 1.0);
  EXPECT_GT(c.tau_max, 0.99);
  EXPECT_NEAR(c.velocity_scale, c.fluid_per_transport, 1e-9);
  // D ≫ ν: several transport steps per fluid step.
  const TimeCoupling d = plan_time_coupling(1e-5, 0.2, 1e4, 1.0);
  EXPECT_GT(d.transport_per_fluid, 1);
  EXPECT_LE(d.tau_max, 1.0 + 1e-12);
  EXPECT_NEAR(d.velocity_scale, 1.0 / d.transport_per_fluid, 1e-15);
}

TEST(TimeCoupling, VelocityAveragerHandsTheScaledMean) {
  VelocityAverager avg(2);
  const std::vector<double> a = {0.01, 0.0}, b = {0.03, -0.02}, zero = {0.0, 0.0};
  avg.add(a, zero);
  avg.add(b, a);
  TransportLattice lat(Grid{2, 1}, Stencil::d2q5, {});
  avg.apply(lat, 3.0);
  EXPECT_NEAR(lat.velocity_x()[0], 3.0 * 0.02, 1e-15);
  EXPECT_NEAR(lat.velocity_x()[1], 3.0 * -0.01, 1e-15);
  EXPECT_NEAR(lat.velocity_y()[0], 3.0 * 0.005, 1e-15);
  EXPECT_EQ(avg.samples(), 0);
  EXPECT_THROW(avg.apply(lat, 1.0), std::logic_error);
}

TEST(Compartments, CoupledNoO2ColumnReachesSteadyStateWithOneToOneEcCoupling) {
  // 1D column (grid 1 × 60, h = 0.5 µm, Δt from τ = 1 for D_NO): an RBC-compartment
  // layer 10 µm (NO scavenging; O2 fed at 70 Torr from the bottom side), EC 2.5 µm,
  // SM 7.5 µm, tissue 10 µm, zero flux on top; NO zero flux at both ends;
  // update_reactions() every step, 4 s of physical time. At steady state the EC's NO
  // production equals its O2 use (1:1), NO production = NO consumption, concentrations
  // stay non-negative, and both lattices' mass balances close in every step.
  const Grid g{1, 60};
  std::vector<std::uint8_t> ids(g.size());
  for (int y = 0; y < g.ny; ++y) {
    const double yc = (y + 0.5) * 0.5;
    ids[std::size_t(y)] = yc < 10.0 ? 1 : yc < 12.5 ? 2 : yc < 20.0 ? 3 : 4;
  }
  const NoO2Model m = NoO2Model::arteriole_defaults();
  const TransportUnits u{0.5, dt_for_tau(0.5, 3300.0, 1.0)};
  TransportBoundaries bo2, bno;
  bo2.bottom = {SideKind::fixed_concentration, 70.0 * m.alpha};
  bo2.top = {SideKind::zero_flux, 0.0};
  bno.bottom = bno.top = {SideKind::zero_flux, 0.0};
  TransportLattice no(g, Stencil::d2q5, bno), o2(g, Stencil::d2q5, bo2);
  apply_diffusivities(m, ids, u, no, o2);
  no.initialize_uniform(0.0);
  o2.initialize_uniform(70.0 * m.alpha);
  double worst = 0.0;
  const long steps = std::lround(4.0 / u.dt_s);
  for (long s = 0; s < steps; ++s) {
    update_reactions(m, ids, u, no, o2);
    no.step();
    o2.step();
    worst = std::max({worst, no.mass_balance().relative_residual(), o2.mass_balance().relative_residual()});
  }
  EXPECT_LT(worst, 1e-13);
  // Steady: NO produced in the EC = NO consumed (RBC layer, SM, tissue).
  const auto& nb = no.mass_balance();
  // EC: NO production q_NO = O2 use k C (the same R1 at the same P).
  double produced = 0.0, used = 0.0;
  for (std::size_t n = 0; n < ids.size(); ++n) {
    if (ids[n] != 2) continue;
    produced += no.source()[n];
    used += o2.decay_rate()[n] * o2.concentration()[n];
  }
  EXPECT_GT(produced, 0.0);
  EXPECT_LT(std::fabs(nb.source), 1e-9 * produced);
  EXPECT_NEAR(produced, used, 1e-9 * produced);
  for (double c : o2.concentration()) EXPECT_GT(c, 0.0);
  for (double c : no.concentration()) EXPECT_GE(c, 0.0);
}
