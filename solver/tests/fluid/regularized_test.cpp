// Unit checks of the regularised collision (Latt & Chopard 2006, Math Comput Simul
// 72:165; collide_node.hpp): exact mass conservation and momentum change equal to the
// force (Guo), equilibrium is a fixed point, the operator equals BGK where the
// regularisation removes nothing, and force-driven Poiseuille flow converges at
// second order.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fluid/collide_node.hpp"
#include "fluid/fluid_lattice.hpp"
#include "lattice/d2q9.hpp"

using namespace erythro;
using namespace erythro::fluid;

namespace {
constexpr auto kReg = CollisionModel::regularized;

void random_populations(double* f, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(0.9, 1.1);
  for (int i = 0; i < d2q9::Q; ++i) f[i] = d2q9::w[i] * (dist(gen) - 1.0);  // stored as f − w
}

struct Moments3 {
  double m, jx, jy, pxx, pyy, pxy;
};
Moments3 moments_of(const double* f) {
  Moments3 r{};
  for (int i = 0; i < d2q9::Q; ++i) {
    const double cx = d2q9::cx[i], cy = d2q9::cy[i];
    r.m += f[i];
    r.jx += cx * f[i];
    r.jy += cy * f[i];
    r.pxx += cx * cx * f[i];
    r.pyy += cy * cy * f[i];
    r.pxy += cx * cy * f[i];
  }
  return r;
}
}  // namespace

TEST(Regularized, NameRoundTrips) {
  CollisionModel m = CollisionModel::bgk;
  ASSERT_TRUE(parse_collision_model("regularized", m));
  EXPECT_EQ(m, kReg);
  EXPECT_EQ(to_string(kReg), "regularized");
}

TEST(Regularized, ConservesMassAndAddsExactlyTheForce) {
  for (double tau : {0.5001, 0.6, 0.8, 1.0, 2.5}) {
    for (unsigned seed : {1u, 7u, 42u}) {
      double f[9];
      random_populations(f, seed);
      const Moments3 before = moments_of(f);
      const double Fx = 1e-3, Fy = -2e-3;
      detail::collide_node<kReg, true>(f, detail::rates_for(kReg, tau, 3.0 / 16), Fx, Fy);
      const Moments3 after = moments_of(f);
      EXPECT_NEAR(after.m, before.m, 1e-15) << "tau " << tau;
      EXPECT_NEAR(after.jx - before.jx, Fx, 1e-15) << "tau " << tau;
      EXPECT_NEAR(after.jy - before.jy, Fy, 1e-15) << "tau " << tau;
    }
  }
}

TEST(Regularized, EquilibriumIsFixedPointWithoutForce) {
  double f[9], g[9];
  for (int i = 0; i < 9; ++i) f[i] = g[i] = d2q9::equilibrium_deviation(i, 1.02, 0.05, -0.03);
  detail::collide_node<kReg, false>(f, detail::rates_for(kReg, 0.7, 0), 0, 0);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(f[i], g[i], 1e-16);
}

TEST(Regularized, EqualsBgkAtTauOne) {
  // ω = 1: both give f' = f^eq + S/2, whatever f^neq was.
  double f[9], g[9];
  random_populations(f, 5);
  for (int i = 0; i < 9; ++i) g[i] = f[i];
  detail::collide_node<CollisionModel::bgk, true>(f, detail::rates_for(CollisionModel::bgk, 1.0, 0), 1e-3, 2e-3);
  detail::collide_node<kReg, true>(g, detail::rates_for(kReg, 1.0, 0), 1e-3, 2e-3);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(f[i], g[i], 1e-16);
}

TEST(Regularized, EqualsBgkWhenNonEquilibriumIsSecondOrderHermite) {
  // f = f^eq + w_i [Q_i:A/(2c_s⁴) − c_i·F/(2c_s²)] is its own projection (orders 0–2,
  // with the −F/2 first moment of Guo's pre-collision state): nothing is discarded.
  const double rho = 1.01, ux = 0.04, uy = -0.02, Fx = 3e-4, Fy = -1e-4;
  const double axx = 2e-3, ayy = -1e-3, axy = 5e-4;
  double f[9], g[9];
  for (int i = 0; i < 9; ++i) {
    const double cx = d2q9::cx[i], cy = d2q9::cy[i];
    const double q = (cx * cx - 1.0 / 3) * axx + (cy * cy - 1.0 / 3) * ayy + 2 * cx * cy * axy;
    f[i] = g[i] = d2q9::equilibrium_deviation(i, rho, ux, uy) + d2q9::w[i] * (4.5 * q - 1.5 * (cx * Fx + cy * Fy));
  }
  for (double tau : {0.55, 0.8, 1.7}) {
    double a[9], b[9];
    for (int i = 0; i < 9; ++i) a[i] = f[i], b[i] = g[i];
    detail::collide_node<CollisionModel::bgk, true>(a, detail::rates_for(CollisionModel::bgk, tau, 0), Fx, Fy);
    detail::collide_node<kReg, true>(b, detail::rates_for(kReg, tau, 0), Fx, Fy);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(a[i], b[i], 1e-16) << "tau " << tau << " i " << i;
  }
}

TEST(Regularized, SecondMomentAfterCollisionEqualsBgk) {
  // Regularisation only discards the 3rd/4th-order (ghost) moments.
  for (unsigned seed : {2u, 9u}) {
    double a[9], b[9];
    random_populations(a, seed);
    for (int i = 0; i < 9; ++i) b[i] = a[i];
    detail::collide_node<CollisionModel::bgk, true>(a, detail::rates_for(CollisionModel::bgk, 0.62, 0), 2e-4, 1e-4);
    detail::collide_node<kReg, true>(b, detail::rates_for(kReg, 0.62, 0), 2e-4, 1e-4);
    const Moments3 ma = moments_of(a), mb = moments_of(b);
    EXPECT_NEAR(ma.pxx, mb.pxx, 1e-15);
    EXPECT_NEAR(ma.pyy, mb.pyy, 1e-15);
    EXPECT_NEAR(ma.pxy, mb.pxy, 1e-15);
    double diff = 0.0;
    for (int i = 0; i < 9; ++i) diff = std::max(diff, std::abs(a[i] - b[i]));
    EXPECT_GT(diff, 1e-6) << "random populations carry ghost moments the two operators treat differently";
  }
}

TEST(Regularized, PoiseuilleConvergesAtSecondOrder) {
  // Force-driven channel, diffusive scaling (τ fixed, u_centre ∝ 1/N); exact profile
  // u = F y (N − y)/(2ν). Unidirectional flow: the model acts as TRT with τ− = 1,
  // so the bounce-back slip is O(h²) and τ-dependent (docs/stability.md).
  for (double tau : {0.8, 1.5}) {
    double previous = 0.0;
    for (int N : {8, 16, 32}) {
      BoundaryConfig walls;
      walls.bottom.type = walls.top.type = SideType::wall;
      FluidLattice lat(Grid{4, N}, {kReg, tau, 3.0 / 16}, walls);
      const double nu = d2q9::viscosity_of_tau(tau), u_centre = 0.02 * 16.0 / N;
      const double F = 8.0 * nu * u_centre / (double(N) * N);
      lat.set_uniform_force(F, 0.0);
      const long steps = static_cast<long>(std::ceil(std::log(1e15) * N * N / (nu * 9.8696)));
      for (long s = 0; s < steps; ++s) lat.step();
      const Moments m = lat.moments();
      double num = 0, den = 0;
      for (int j = 0; j < N; ++j) {
        const double y = j + 0.5, exact = F * y * (N - y) / (2 * nu);
        const double e = m.ux[lat.grid().index(1, j)] - exact;
        num += e * e;
        den += exact * exact;
      }
      const double error = std::sqrt(num / den);
      if (previous > 0.0) {
        EXPECT_NEAR(std::log2(previous / error), 2.0, 0.1) << "tau " << tau << " N " << N;
      }
      previous = error;
    }
  }
}

TEST(Regularized, PoiseuilleExactAtTauSevenEighths) {
  // For unidirectional shear flow the regularized model acts as TRT with τ− = 1, i.e.
  // Λ = (τ − ½)(1 − ½) = 3/16 at τ = 7/8, where bounce-back walls are exactly halfway
  // (Ginzburg & d'Humières 2003): the parabola is reproduced to round-off.
  const int N = 16;
  const double tau = 0.875, nu = d2q9::viscosity_of_tau(tau), F = 1e-5;
  BoundaryConfig walls;
  walls.bottom.type = walls.top.type = SideType::wall;
  FluidLattice lat(Grid{4, N}, {kReg, tau, 3.0 / 16}, walls);
  lat.set_uniform_force(F, 0.0);
  const long steps = static_cast<long>(std::ceil(std::log(1e15) * N * N / (nu * 9.8696)));
  for (long s = 0; s < steps; ++s) lat.step();
  const Moments m = lat.moments();
  for (int j = 0; j < N; ++j) {
    const double y = j + 0.5, exact = F * y * (N - y) / (2 * nu);
    EXPECT_NEAR(m.ux[lat.grid().index(1, j)], exact, 1e-12 * F * N * N / (8 * nu)) << "row " << j;
  }
}
