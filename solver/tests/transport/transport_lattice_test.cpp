// Unit checks of the transport lattice: stencil moments, equilibrium moments (eq T2),
// uniform states, the implicit sink (eq T4) and the mass balance (eq T5).
#include <gtest/gtest.h>

#include <cmath>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "busy_lattice.hpp"
#include "transport/stencils.hpp"
#include "transport/transport_lattice.hpp"

using namespace erythro;
using namespace erythro::transport;

namespace {
template <class S>
void check_moments() {
  double sum = 0, sx = 0, sxx = 0, syy = 0, sxy = 0;
  for (int i = 0; i < S::Q; ++i) {
    sum += S::w[i];
    sx += S::w[i] * S::cx[i];
    sxx += S::w[i] * S::cx[i] * S::cx[i];
    syy += S::w[i] * S::cy[i] * S::cy[i];
    sxy += S::w[i] * S::cx[i] * S::cy[i];
    EXPECT_EQ(S::cx[S::opposite[i]], -S::cx[i]);
    EXPECT_EQ(S::cy[S::opposite[i]], -S::cy[i]);
  }
  EXPECT_DOUBLE_EQ(sum, 1.0);
  EXPECT_DOUBLE_EQ(sx, 0.0);
  EXPECT_DOUBLE_EQ(sxx, kCs2);
  EXPECT_DOUBLE_EQ(syy, kCs2);
  EXPECT_DOUBLE_EQ(sxy, 0.0);
  // Equilibrium moments: Σ g = C, Σ c g = C u, Σ c c g = c_s² C I.
  const double C = 1.7, ux = 0.03, uy = -0.02;
  double m0 = 0, mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
  for (int i = 0; i < S::Q; ++i) {
    const double g = equilibrium<S>(i, C, ux, uy);
    m0 += g;
    mx += S::cx[i] * g;
    my += S::cy[i] * g;
    mxx += S::cx[i] * S::cx[i] * g;
    myy += S::cy[i] * S::cy[i] * g;
    mxy += S::cx[i] * S::cy[i] * g;
  }
  EXPECT_NEAR(m0, C, 1e-15);
  EXPECT_NEAR(mx, C * ux, 1e-15);
  EXPECT_NEAR(my, C * uy, 1e-15);
  EXPECT_NEAR(mxx, kCs2 * C, 1e-15);
  EXPECT_NEAR(myy, kCs2 * C, 1e-15);
  EXPECT_NEAR(mxy, 0.0, 1e-15);
}

TransportBoundaries all_periodic() { return {}; }
}  // namespace

TEST(TransportStencil, D2Q5Moments) { check_moments<D2Q5>(); }
TEST(TransportStencil, D2Q9Moments) { check_moments<D2Q9>(); }

TEST(TransportLattice, TauOfDiffusivity) {
  EXPECT_DOUBLE_EQ(tau_for_diffusivity(1.0 / 6.0), 1.0);
  EXPECT_DOUBLE_EQ(tau_for_diffusivity(0.5), 2.0);
}

TEST(TransportLattice, UniformStateStaysUniform) {
  for (auto st : {Stencil::d2q5, Stencil::d2q9}) {
    TransportBoundaries zero{{SideKind::zero_flux}, {SideKind::zero_flux}, {SideKind::zero_flux}, {SideKind::zero_flux}};
    TransportLattice lat(Grid{7, 5}, st, zero);
    lat.set_uniform_diffusivity(0.1);
    lat.set_uniform_velocity(0.0, 0.0);
    lat.initialize_uniform(2.5);
    for (int s = 0; s < 20; ++s) lat.step();
    for (double c : lat.concentration()) EXPECT_NEAR(c, 2.5, 1e-14);
  }
}

TEST(TransportLattice, ImplicitDecayIsCrankNicolson) {
  // Uniform C, periodic, q = 0, sink k: M(t+1) = M(t) (1 − k/2)/(1 + k/2) (eq T4).
  TransportLattice lat(Grid{4, 4}, Stencil::d2q5, all_periodic());
  lat.initialize_uniform(1.0);
  const double k = 0.3;
  for (auto& v : lat.decay_rate()) v = k;
  double M = lat.stored_amount();
  for (int s = 0; s < 5; ++s) {
    lat.step();
    const double expected = M * (1.0 - 0.5 * k) / (1.0 + 0.5 * k);
    EXPECT_NEAR(lat.stored_amount(), expected, 1e-14 * M);
    // C = Σ g/(1 + k/2) at every node.
    EXPECT_NEAR(lat.concentration()[0], (M / 16.0) / (1.0 + 0.5 * k), 1e-15);
    M = lat.stored_amount();
  }
}

TEST(TransportLattice, SourceIsTimeCentredFromTheFirstStep) {
  // Uniform C0, q and k set before initialize(): C_n = q/k + (C0 − q/k) r^n exactly,
  // r = (1 − k/2)/(1 + k/2) (eq T4), within O(k³) per step of the ODE's e^{−kn}.
  TransportLattice lat(Grid{3, 3}, Stencil::d2q5, {});
  const double C0 = 1.0, q = 0.01, k = 0.02, r = (1.0 - 0.5 * k) / (1.0 + 0.5 * k);
  for (auto& v : lat.source()) v = q;
  for (auto& v : lat.decay_rate()) v = k;
  lat.initialize_uniform(C0);
  EXPECT_DOUBLE_EQ(lat.concentration()[4], C0);
  for (int n = 1; n <= 50; ++n) {
    lat.step();
    EXPECT_NEAR(lat.concentration()[4], q / k + (C0 - q / k) * std::pow(r, n), 1e-14);
    EXPECT_NEAR(lat.concentration()[4], q / k + (C0 - q / k) * std::exp(-k * n), 2e-5);
  }
}

TEST(TransportLattice, MassBalanceClosesToRoundOff) {
  // Random field, random sources and sinks, a velocity field, every kind of side, per-node
  // D; BGK (T3) and TRT (T3') at three magic parameters.
  const CollisionModel models[] = {{}, {Collision::trt, 0.25}, {Collision::trt, 1.0 / 6.0}, {Collision::trt, 1.0 / 12.0}};
  for (auto st : {Stencil::d2q5, Stencil::d2q9})
    for (const CollisionModel& c : models) {
      auto lat = test_support::busy_lattice(st, c, 0.1, true, Grid{23, 17});
      double worst = 0.0, boundary = 0.0;
      for (int s = 0; s < 50; ++s) {
        const double before = lat.stored_amount();
        lat.step();
        const auto& mb = lat.mass_balance();
        worst = std::max(worst, mb.relative_residual());
        boundary += std::fabs(mb.boundary_in);
        EXPECT_NEAR(mb.storage_change, lat.stored_amount() - before, 1e-12);
        // M = Σ C + ½ Σ q_tot.
        EXPECT_NEAR(mb.amount, lat.total_amount() + 0.5 * mb.source, 1e-12 * mb.scale);
      }
      EXPECT_LT(worst, 1e-14) << (c.kind == Collision::trt ? "trt " : "bgk ") << c.magic;
      EXPECT_GT(boundary, 1e-3);  // the sides did exchange mass: the test is not vacuous
    }
}

TEST(TransportLattice, ThreadCountDoesNotChangeBits) {
  // A grid big enough to fork threads; 1 and 2 threads agree bitwise (row sums serial).
  const Grid g{160, 128};  // above the kernel's threading threshold (128²)
  auto run = [&](int threads) {
#if defined(_OPENMP)
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    TransportLattice lat(g, Stencil::d2q5, {});
    std::vector<double> C(g.size());
    for (std::size_t n = 0; n < g.size(); ++n) C[n] = std::sin(0.1 * double(n));
    lat.initialize(C);
    for (int s = 0; s < 10; ++s) lat.step();
    return std::make_pair(std::vector<double>(lat.concentration().begin(), lat.concentration().end()),
                          lat.mass_balance().amount);
  };
  const auto a = run(1), b = run(2);
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
}

TEST(TransportLattice, RejectsInconsistentInput) {
  TransportBoundaries b;
  b.left.kind = SideKind::zero_flux;
  EXPECT_THROW(TransportLattice(Grid{4, 4}, Stencil::d2q5, b), std::invalid_argument);
  TransportLattice lat(Grid{4, 4}, Stencil::d2q5, {});
  EXPECT_THROW(lat.set_uniform_diffusivity(0.0), std::invalid_argument);
  std::vector<double> wrong(3);
  EXPECT_THROW(lat.initialize(wrong), std::invalid_argument);
  lat.diffusivity()[5] = -0.1;
  const auto h = lat.check_health();
  EXPECT_FALSE(h.healthy);
  EXPECT_EQ(h.quantity, "tau_margin");
  EXPECT_EQ(h.node_x, 1);
  EXPECT_EQ(h.node_y, 1);
}
