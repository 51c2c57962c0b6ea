// Unit checks of the TRT collision of the transport lattice (transport_lattice.hpp,
// Collision::trt; docs/transport.md §1 eq T3'): it reduces to BGK (T3) when Λ = (τ − ½)², and
// its steady states depend on D only through Λ (parametrisation invariance, also across a
// jump of D), which BGK's do not. Its mass balance (T5) is checked with BGK's in
// transport_lattice_test.cpp.
// At Λ = 1/4 the source-offset-corrected concentration is the steady finite-volume solution (T7).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "busy_lattice.hpp"
#include "transport/stencils.hpp"
#include "transport/transport_lattice.hpp"

using namespace erythro;
using namespace erythro::transport;

namespace {

// Steady state of a square with a D jump (left half D_a, right half D_b), a uniform
// source and all four sides held at 0 (anti-bounce-back): C after `steps` steps.
std::vector<double> steady_jump(CollisionModel c, double D_a, double D_b, double q, int steps) {
  const Grid g{12, 12};
  const Side held{SideKind::fixed_concentration, 0.0};
  TransportLattice lat(g, Stencil::d2q5, {held, held, held, held});
  lat.set_collision(c);
  auto D = lat.diffusivity();
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) D[g.index(x, y)] = x < g.nx / 2 ? D_a : D_b;
  for (auto& v : lat.source()) v = q;
  lat.initialize_uniform(0.0);
  for (int s = 0; s < steps; ++s) lat.step();
  return {lat.concentration().begin(), lat.concentration().end()};
}

double max_relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0, s = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n) {
    d = std::max(d, std::fabs(a[n] - b[n]));
    s = std::max(s, std::fabs(a[n]));
  }
  return d / s;
}

}  // namespace

TEST(TransportTrt, ReducesToBgkWhenMagicIsTauSquared) {
  // T3' with ω⁺ = ω⁻ is T3: Λ = (τ − ½)² at a uniform D gives the BGK populations.
  for (auto st : {Stencil::d2q5, Stencil::d2q9}) {
    const double D = 0.11, s = kInvCs2 * D;
    auto bgk = test_support::busy_lattice(st, {}, D, false);
    auto trt = test_support::busy_lattice(st, {Collision::trt, s * s}, D, false);
    for (int k = 0; k < 40; ++k) {
      bgk.step();
      trt.step();
    }
    double worst = 0.0;
    for (std::size_t i = 0; i < bgk.populations().size(); ++i)
      worst = std::max(worst, std::fabs(bgk.populations()[i] - trt.populations()[i]));
    EXPECT_LT(worst, 1e-14);
  }
}

TEST(TransportTrt, SteadyStateDependsOnDiffusivityOnlyThroughMagic) {
  // Steady ∇·(D∇C) + q = 0 is unchanged when D and q are scaled together. TRT at a fixed Λ
  // reproduces that to the steady residual, across the D jump too; BGK (whose Λ_n = (τ_n − ½)²
  // changes with the scaling) does not: its steady state depends on τ.
  const double Da = 0.05, Db = 0.3, q = 1e-3;
  const int steps = 30000;
  const CollisionModel trt{Collision::trt, 0.25};
  const double trt_change = max_relative_difference(steady_jump(trt, Da, Db, q, steps),
                                                    steady_jump(trt, 2 * Da, 2 * Db, 2 * q, steps));
  const double bgk_change = max_relative_difference(steady_jump({}, Da, Db, q, steps),
                                                    steady_jump({}, 2 * Da, 2 * Db, 2 * q, steps));
  EXPECT_LT(trt_change, 1e-10);
  EXPECT_GT(bgk_change, 1e-4);
}

TEST(TransportTrt, RejectsNonPositiveMagic) {
  TransportLattice lat(Grid{4, 4}, Stencil::d2q5, {});
  EXPECT_THROW(lat.set_collision({Collision::trt, 0.0}), std::invalid_argument);
  EXPECT_NO_THROW(lat.set_collision({Collision::bgk, 0.0}));  // Λ unused by BGK
  EXPECT_NO_THROW(lat.set_collision({Collision::trt, 0.25}));
  EXPECT_EQ(lat.collision().kind, Collision::trt);
}

TEST(TransportTrt, SteadyOffsetCorrectedConcentrationIsFiniteVolume) {
  // Eq T7: with TRT Λ = 1/4 on D2Q5, Ĉ_n = C_n + q_n/(12 D_n) of the steady state solves the
  // 5-point finite-volume equations with harmonic face D exactly, with a disc of source and a
  // disc of low D (once apart, once coinciding: the membrane of a cell). Without the offset
  // (or at another Λ) the residual is O(q).
  const int N = 20;
  const Grid g{N, N};
  auto residual = [&](double magic, double r_q, double r_D, bool corrected) {
    const Side held{SideKind::fixed_concentration, 0.0};
    TransportLattice lat(g, Stencil::d2q5, {held, held, held, held});
    lat.set_collision({Collision::trt, magic});
    auto D = lat.diffusivity();
    auto q = lat.source();
    for (int y = 0; y < N; ++y)
      for (int x = 0; x < N; ++x) {
        const double r = std::hypot(x + 0.5 - 0.5 * N, y + 0.5 - 0.5 * N);
        q[g.index(x, y)] = r < r_q ? 1e-3 : 0.0;
        D[g.index(x, y)] = r < r_D ? 0.08 : 0.3;
      }
    lat.initialize_uniform(0.0);
    for (int s = 0; s < 40000; ++s) lat.step();
    std::vector<double> C(g.size());
    for (std::size_t n = 0; n < g.size(); ++n)
      C[n] = corrected ? lat.source_corrected_concentration(n) : lat.concentration()[n];
    double worst = 0.0;
    for (int y = 1; y + 1 < N; ++y)
      for (int x = 1; x + 1 < N; ++x) {
        const std::size_t n = g.index(x, y);
        double div = 0.0;
        for (const std::size_t m : {g.index(x + 1, y), g.index(x - 1, y), g.index(x, y + 1), g.index(x, y - 1)})
          div += 2.0 / (1.0 / D[n] + 1.0 / D[m]) * (C[m] - C[n]);
        worst = std::max(worst, std::fabs(div + q[n]));
      }
    return worst / 1e-3;
  };
  EXPECT_DOUBLE_EQ(source_offset_coefficient(0.25), 1.0 / 12.0);
  for (const auto& [rq, rD] : {std::pair{4.3, 6.7}, std::pair{5.2, 5.2}}) {
    EXPECT_LT(residual(0.25, rq, rD, true), 1e-10) << rq << " " << rD;
    EXPECT_GT(residual(0.25, rq, rD, false), 0.05);
    EXPECT_GT(residual(1.0 / 6.0, rq, rD, true), 0.01);  // the offset is exact at Λ = 1/4 only
  }
}
