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

// The rows of one τ (refresh_tau_rows) collide as a plain row, the others node by node: a field
// whose rows differ only in their LAST node (and one uniform row at another τ) gives the same
// bits as the same field never classified (every row node by node). A row taken for uniform on
// its first nodes alone would collide its last node with the wrong τ.
TEST(FluidLattice, RowsOfOneTauAreFoundOverTheWholeRow) {
  BoundaryConfig b;
  b.bottom.type = b.top.type = SideType::wall;
  CollisionConfig c{CollisionModel::bgk, 0.8, 3.0 / 16};
  const Grid g{12, 9};
  FluidLattice classified(g, c, b), node_by_node(g, c, b);
  for (FluidLattice* l : {&classified, &node_by_node}) {
    l->set_uniform_force(1e-5, 0);
    l->enable_tau_field();
    const std::span<double> tau = l->tau_field();  // leaves the rows unclassified
    for (int y = 1; y < g.ny; y += 2) tau[g.index(g.nx - 1, y)] = 1.3;
    for (int x = 0; x < g.nx; ++x) tau[g.index(x, 4)] = 0.6;
  }
  classified.refresh_tau_rows();
  for (int s = 0; s < 40; ++s) {
    classified.step();
    node_by_node.step();
  }
  const auto pc = classified.populations(), pn = node_by_node.populations();
  for (std::size_t k = 0; k < pc.size(); ++k) ASSERT_EQ(pc[k], pn[k]) << "population entry " << k;
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

namespace {
// Eq 1.5 and 1.7 written direction by direction in long double, the source S_i (eq 1.4)
// apart from the equilibrium: the reference for the folded form of eq 1.5b.
template <CollisionModel M>
void guo_written_out(const double* f_in, double tau, double magic, double Fx, double Fy, long double* out) {
  using L = long double;
  L f[9], rho = 0, jx = 0, jy = 0;
  for (int i = 0; i < 9; ++i) {
    f[i] = L(d2q9::w[i]) + f_in[i];
    rho += f[i];
    jx += d2q9::cx[i] * f[i];
    jy += d2q9::cy[i] * f[i];
  }
  const L ux = (jx + L(0.5) * Fx) / rho, uy = (jy + L(0.5) * Fy) / rho;
  L feq[9], S[9];
  for (int i = 0; i < 9; ++i) {
    const L cu = d2q9::cx[i] * ux + d2q9::cy[i] * uy, cF = d2q9::cx[i] * Fx + d2q9::cy[i] * Fy;
    feq[i] = L(d2q9::w[i]) * rho * (1 + 3 * cu + L(4.5) * cu * cu - L(1.5) * (ux * ux + uy * uy));
    S[i] = L(d2q9::w[i]) * (3 * (cF - (ux * Fx + uy * Fy)) + 9 * cu * cF);
  }
  const L op = 1 / L(tau), om = M == CollisionModel::trt ? 1 / (L(0.5) + L(magic) / (L(tau) - L(0.5))) : op;
  for (int i = 0; i < 9; ++i) {
    const int j = d2q9::opposite[i];
    const L fp = (f[i] + f[j]) / 2, fm = (f[i] - f[j]) / 2, ep = (feq[i] + feq[j]) / 2, em = (feq[i] - feq[j]) / 2;
    const L sp = (S[i] + S[j]) / 2, sm = (S[i] - S[j]) / 2;
    out[i] = f[i] - op * (fp - ep) - om * (fm - em) + (1 - op / 2) * sp + (1 - om / 2) * sm - L(d2q9::w[i]);
  }
}

template <CollisionModel M>
double worst_difference_from_written_out(double tau, double force_scale) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    double f[9];
    random_populations(f, 100 + trial);
    const double Fx = force_scale * unit(gen), Fy = force_scale * unit(gen);
    long double ref[9];
    guo_written_out<M>(f, tau, 3.0 / 16, Fx, Fy, ref);
    detail::collide_node<M, true>(f, detail::rates_for(M, tau, 3.0 / 16), Fx, Fy);
    for (int i = 0; i < 9; ++i) worst = std::max(worst, static_cast<double>(std::fabs(f[i] - ref[i])));
  }
  return worst;
}
}  // namespace

// Eq 1.5b folds Guo's source into the equilibrium: the same values as eqs 1.5 and 1.7 written
// out, to round-off (populations are O(w_i); 1e-16 is a few units in the last place of them),
// for τ from near ½ to 3 and forces from 1e-7 to 1e-2 per node (the IB forces of the
// V&V scenes are ≤ 1e-3).
TEST(Collision, GuoSourceInsideTheEquilibriumEqualsTheSourceWrittenOut) {
  for (double tau : {0.51, 0.8, 1.0, 1.7, 3.0}) {
    for (double force : {1e-7, 1e-4, 1e-2}) {
      EXPECT_LT(worst_difference_from_written_out<CollisionModel::bgk>(tau, force), 1e-16) << tau << " " << force;
      EXPECT_LT(worst_difference_from_written_out<CollisionModel::trt>(tau, force), 1e-16) << tau << " " << force;
    }
  }
}
