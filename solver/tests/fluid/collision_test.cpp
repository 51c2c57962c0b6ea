// Unit checks of the collision operators: mass conservation, momentum change equal
// to the force (Guo), equilibrium is a fixed point, and fluid-lattice plumbing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "fluid/collide_node.hpp"
#include "fluid/fluid_lattice.hpp"

using namespace erythro;
using namespace erythro::fluid;

namespace {
void random_populations(double* f, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(0.9, 1.1);
  for (int i = 0; i < d2q9::Q; ++i) f[i] = d2q9::w[i] * (dist(gen) - 1.0);  // stored as f - w
}

template <CollisionModel M>
void check_conservation(double tau) {
  double f[9];
  random_populations(f, 7);
  double m0 = 0, jx0 = 0, jy0 = 0;
  for (int i = 0; i < 9; ++i) {
    m0 += f[i];
    jx0 += d2q9::cx[i] * f[i];
    jy0 += d2q9::cy[i] * f[i];
  }
  const double Fx = 1e-3, Fy = -2e-3;
  detail::collide_node<M, true>(f, detail::rates_for(M, tau, 3.0 / 16), Fx, Fy);
  double m1 = 0, jx1 = 0, jy1 = 0;
  for (int i = 0; i < 9; ++i) {
    m1 += f[i];
    jx1 += d2q9::cx[i] * f[i];
    jy1 += d2q9::cy[i] * f[i];
  }
  EXPECT_NEAR(m1, m0, 1e-15);
  // Guo forcing: the collision adds exactly F to the momentum.
  EXPECT_NEAR(jx1 - jx0, Fx, 1e-15);
  EXPECT_NEAR(jy1 - jy0, Fy, 1e-15);
}
}  // namespace

TEST(Collision, BgkConservesMassAndAddsForce) { check_conservation<CollisionModel::bgk>(0.8); }
TEST(Collision, TrtConservesMassAndAddsForce) { check_conservation<CollisionModel::trt>(0.8); }

TEST(Collision, EquilibriumIsFixedPointWithoutForce) {
  for (auto model : {CollisionModel::bgk, CollisionModel::trt}) {
    double f[9], g[9];
    for (int i = 0; i < 9; ++i) f[i] = g[i] = d2q9::equilibrium_deviation(i, 1.02, 0.05, -0.03);
    const auto r = detail::rates_for(model, 0.7, 3.0 / 16);
    if (model == CollisionModel::bgk) detail::collide_node<CollisionModel::bgk, false>(f, r, 0, 0);
    else detail::collide_node<CollisionModel::trt, false>(f, r, 0, 0);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(f[i], g[i], 1e-16);
  }
}

TEST(Collision, TrtWithMagicEqualToBgkValueMatchesBgk) {
  // TRT with τ− = τ+ (Λ = (τ − ½)²) is BGK.
  const double tau = 0.9;
  double f[9], g[9];
  random_populations(f, 3);
  for (int i = 0; i < 9; ++i) g[i] = f[i];
  detail::collide_node<CollisionModel::bgk, true>(f, detail::rates_for(CollisionModel::bgk, tau, 0), 1e-3, 2e-3);
  detail::collide_node<CollisionModel::trt, true>(g, detail::rates_for(CollisionModel::trt, tau, (tau - 0.5) * (tau - 0.5)), 1e-3, 2e-3);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(f[i], g[i], 1e-15);
}

TEST(FluidLattice, RejectsInconsistentBoundaries) {
  BoundaryConfig b;
  b.bottom.type = SideType::wall;  // top stays periodic
  EXPECT_THROW(FluidLattice(Grid{8, 8}, CollisionConfig{}, b), std::invalid_argument);
}

TEST(FluidLattice, TauFieldEqualToUniformGivesIdenticalResult) {
  BoundaryConfig b;
  b.bottom.type = b.top.type = SideType::wall;
  CollisionConfig c{CollisionModel::trt, 0.8, 3.0 / 16};
  FluidLattice a(Grid{12, 9}, c, b), t(Grid{12, 9}, c, b);
  a.set_uniform_force(1e-5, 0);
  t.set_uniform_force(1e-5, 0);
  t.enable_tau_field();
  for (int s = 0; s < 50; ++s) {
    a.step();
    t.step();
  }
  const auto pa = a.populations(), pt = t.populations();
  for (std::size_t k = 0; k < pa.size(); ++k) ASSERT_EQ(pa[k], pt[k]);
}

TEST(FluidLattice, ForceFieldEqualToUniformForceGivesIdenticalResult) {
  CollisionConfig c{CollisionModel::bgk, 0.7, 3.0 / 16};
  FluidLattice a(Grid{10, 10}, c, BoundaryConfig{}), t(Grid{10, 10}, c, BoundaryConfig{});
  a.set_uniform_force(2e-5, -1e-5);
  t.enable_force_field();
  for (auto& v : t.force_x()) v = 2e-5;
  for (auto& v : t.force_y()) v = -1e-5;
  for (int s = 0; s < 20; ++s) {
    a.step();
    t.step();
  }
  const auto pa = a.populations(), pt = t.populations();
  for (std::size_t k = 0; k < pa.size(); ++k) ASSERT_EQ(pa[k], pt[k]);
}

// The healthy scan reports max |u| over all nodes (the steady-state check reuses it);
// a node above the Mach limit is reported as unhealthy instead.
TEST(FluidLattice, HealthScanReportsMaxSpeed) {
  const Grid g{4, 3};
  Moments m;
  m.rho.assign(g.size(), 1.0);
  m.ux.assign(g.size(), 0.01);
  m.uy.assign(g.size(), 0.0);
  m.ux[g.index(2, 1)] = 0.03;
  m.uy[g.index(2, 1)] = 0.04;
  const HealthReport ok = check_health(g, m, 0.3);
  ASSERT_TRUE(ok.healthy);
  EXPECT_EQ(ok.max_speed, std::hypot(0.03, 0.04));
  m.ux[g.index(1, 2)] = 0.5;  // |u|/c_s ≈ 0.87 > 0.3
  const HealthReport bad = check_health(g, m, 0.3);
  EXPECT_FALSE(bad.healthy);
  EXPECT_EQ(bad.quantity, "mach");
  EXPECT_EQ(bad.node_x, 1);
  EXPECT_EQ(bad.node_y, 2);
}

// The fast health check gives the exact scan's report: max |u| is the largest hypot over
// every node (bit for bit), also when many nodes tie within round-off of the largest |u|²,
// and a state with one bad node reports the first one in row-major order.
TEST(FluidLattice, HealthCheckEqualsTheExactScan) {
  const Grid g{37, 23};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.05, 0.05), angle(0.0, 6.283185307179586);
  for (int trial = 0; trial < 50; ++trial) {
    Moments m;
    m.rho.assign(g.size(), 1.0);
    m.ux.resize(g.size());
    m.uy.resize(g.size());
    const double speed = 0.04;
    for (std::size_t n = 0; n < g.size(); ++n) {
      if (trial % 2 == 0) {  // random velocities
        m.ux[n] = u(rng);
        m.uy[n] = u(rng);
      } else {  // every node at the same |u| in another direction: ties within round-off
        const double a = angle(rng);
        m.ux[n] = speed * std::cos(a);
        m.uy[n] = speed * std::sin(a);
      }
    }
    double expected = 0.0;
    for (std::size_t n = 0; n < g.size(); ++n) expected = std::max(expected, std::hypot(m.ux[n], m.uy[n]));
    const HealthReport r = check_health(g, m, 0.3);
    ASSERT_TRUE(r.healthy);
    ASSERT_EQ(r.max_speed, expected) << "trial " << trial;
  }
  Moments m;
  m.rho.assign(g.size(), 1.0);
  m.ux.assign(g.size(), 0.0);
  m.uy.assign(g.size(), 0.0);
  m.uy[g.index(5, 9)] = std::numeric_limits<double>::quiet_NaN();
  m.rho[g.index(30, 4)] = -1.0;
  const HealthReport bad = check_health(g, m, 0.3);
  EXPECT_FALSE(bad.healthy);
  EXPECT_EQ(bad.quantity, "density");
  EXPECT_EQ(bad.node_x, 30);
  EXPECT_EQ(bad.node_y, 4);
}
