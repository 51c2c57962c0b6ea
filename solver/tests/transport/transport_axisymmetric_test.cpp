// Unit checks of the axisymmetric transport lattice (TransportLattice::set_axisymmetric;
// docs/model.md §7b, eqs 7.6–7.10): the lattice carries φ = r C with the drift D/r, so
//  - the r-weighted amount Σ r C balances to round-off in every step (eq T5 on φ), with a
//    per-node D, an axial velocity, a source, a sink and fixed-concentration sides;
//  - a uniform concentration between zero-flux sides stays uniform (the drift balances the
//    gradient of φ = r C exactly);
//  - the steady D2Q5 TRT (Λ = ¼) state, offset-corrected (eq T7), solves the conservative
//    cylindrical finite-volume equations (eq 7.9) to round-off, at the axis and off it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "transport/transport_lattice.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

using namespace erythro;
using namespace erythro::transport;

namespace {

constexpr Side kZeroFlux{SideKind::zero_flux, 0.0};
constexpr Side kPeriodic{SideKind::periodic, 0.0};

// Residual of the steady cylindrical finite-volume equations (eq 7.9, h = 1) at every node of a
// lattice periodic in x with uniform D, axial velocity u and zero-flux bottom and top sides, for
// the offset-corrected Ĉ (eq T7) and q_tot = q − k C:
//   D r_y (Ĉ_E − 2Ĉ + Ĉ_W) + D [r_{y+½}(Ĉ_N − Ĉ) − r_{y−½}(Ĉ − Ĉ_S)] − r_y u (Ĉ_E − Ĉ_W)/2
//   + r_y q_tot = 0,
// the faces of the bottom and top sides carrying nothing. Returns max |residual| / max |r q_tot|.
double finite_volume_residual(const TransportLattice& lat, const std::vector<double>& C, double D, double u,
                              const std::vector<double>& q_tot) {
  const Grid& g = lat.grid();
  const auto r = lat.row_radius();
  double worst = 0.0, scale = 0.0;
  for (int y = 0; y < g.ny; ++y) {
    const double ry = r[static_cast<std::size_t>(y)];
    for (int x = 0; x < g.nx; ++x) {
      const std::size_t n = g.index(x, y), e = g.index((x + 1) % g.nx, y), w = g.index((x + g.nx - 1) % g.nx, y);
      double div = D * ry * (C[e] - 2.0 * C[n] + C[w]) - ry * u * 0.5 * (C[e] - C[w]);
      if (y + 1 < g.ny) div += D * (ry + 0.5) * (C[g.index(x, y + 1)] - C[n]);
      if (y > 0) div -= D * (ry - 0.5) * (C[n] - C[g.index(x, y - 1)]);
      worst = std::max(worst, std::fabs(div + ry * q_tot[n]));
      scale = std::max(scale, std::fabs(ry * q_tot[n]));
    }
  }
  return worst / scale;
}

struct SteadyCase {
  double inner_radius = 0.0;
  double axial_velocity = 0.0;
  double D = 0.12;
};

// The steady state of a 6 × 16 lattice (D2Q5, TRT Λ = ¼), periodic in x, zero flux at both
// radial sides, uniform D, a source varying in x and y and a uniform sink: the residual of eq 7.9.
double steady_residual(const SteadyCase& c, bool corrected) {
  const Grid g{6, 16};
  const double k = 2e-3;
  TransportLattice lat(g, Stencil::d2q5, {kPeriodic, kPeriodic, kZeroFlux, kZeroFlux});
  lat.set_axisymmetric(c.inner_radius);
  lat.set_collision({Collision::trt, 0.25});
  lat.set_uniform_diffusivity(c.D);
  if (c.axial_velocity != 0.0) lat.set_uniform_velocity(c.axial_velocity, 0.0);
  auto q = lat.source();
  auto decay = lat.decay_rate();
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) {
      q[g.index(x, y)] = 1e-3 * (1.0 + std::cos(0.3 * y) + 0.5 * std::sin(2.0 * M_PI * x / g.nx));
      decay[g.index(x, y)] = k;
    }
  lat.initialize_uniform(0.0);
  for (int s = 0; s < 60000; ++s) lat.step();
  std::vector<double> C(g.size()), q_tot(g.size());
  for (std::size_t n = 0; n < g.size(); ++n) {
    C[n] = corrected ? lat.source_corrected_concentration(n) : lat.concentration()[n];
    q_tot[n] = q[n] - decay[n] * lat.concentration()[n];
  }
  return finite_volume_residual(lat, C, c.D, c.axial_velocity, q_tot);
}

}  // namespace

TEST(TransportAxisymmetric, SteadyStateIsTheCylindricalFiniteVolumeScheme) {
  // At the axis and off it, with and without an axial velocity, at two D: round-off (the
  // source's antisymmetric part scaled by Λ⁺/Λ⁻, eq 7.9); without the offset of eq T7 the
  // residual is O(1e-3) or more.
  for (const SteadyCase& c : {SteadyCase{0.0, 0.0, 0.12}, SteadyCase{3.0, 0.0, 0.12}, SteadyCase{0.0, 0.05, 0.12},
                              SteadyCase{0.0, 0.02, 0.05}}) {
    EXPECT_LT(steady_residual(c, true), 1e-11) << c.inner_radius << " " << c.axial_velocity << " " << c.D;
    EXPECT_GT(steady_residual(c, false), 1e-3);
  }
}

TEST(TransportAxisymmetric, FixedConcentrationSidesAreHalfwayFiniteVolumeFaces) {
  // Pure diffusion in an annulus r ∈ [3, 19] held at C = 1 and 2: every row solves eq 7.9 with
  // the side faces' flux 2 D R (C_side − C_row) (the side halfway, R its radius), to round-off;
  // and the profile is the exact 1 + ln(r/3)/ln(19/3) to the scheme's O(h²).
  const Grid g{1, 16};
  const double D = 0.12;
  TransportLattice lat(g, Stencil::d2q5,
                       {kPeriodic, kPeriodic, {SideKind::fixed_concentration, 1.0}, {SideKind::fixed_concentration, 2.0}});
  lat.set_axisymmetric(3.0);
  lat.set_collision({Collision::trt, 0.25});
  lat.set_uniform_diffusivity(D);
  lat.initialize_uniform(0.0);
  for (int s = 0; s < 60000; ++s) lat.step();
  const auto r = lat.row_radius();
  const auto C = lat.concentration();
  double worst = 0.0, worst_exact = 0.0;
  for (int y = 0; y < g.ny; ++y) {
    const auto j = static_cast<std::size_t>(y);
    double div = y + 1 < g.ny ? D * (r[j] + 0.5) * (C[j + 1] - C[j]) : 2.0 * D * 19.0 * (2.0 - C[j]);
    div -= y > 0 ? D * (r[j] - 0.5) * (C[j] - C[j - 1]) : 2.0 * D * 3.0 * (C[j] - 1.0);
    worst = std::max(worst, std::fabs(div));
    worst_exact = std::max(worst_exact, std::fabs(C[j] - (1.0 + std::log(r[j] / 3.0) / std::log(19.0 / 3.0))));
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_LT(worst_exact, 1e-2);
  EXPECT_GT(worst_exact, 1e-4);  // a finite-volume solution on 16 rows, not the exact one
}

TEST(TransportAxisymmetric, RWeightedAmountBalancesToRoundOff) {
  // Eq T5 on φ = r C: per-node D, an axial velocity, a source, a sink, the axis (zero flux),
  // a fixed concentration and a fixed flux on the outer side.
  const Grid g{10, 12};
  for (const Side outer : {Side{SideKind::fixed_concentration, 0.7}, Side{SideKind::fixed_flux, 2e-3}}) {
    TransportLattice lat(g, Stencil::d2q5, {kPeriodic, kPeriodic, kZeroFlux, outer});
    lat.set_axisymmetric(0.0);
    auto D = lat.diffusivity();
    auto q = lat.source();
    auto k = lat.decay_rate();
    std::vector<double> ux(g.size()), uy(g.size(), 0.0), C0(g.size());
    for (std::size_t n = 0; n < g.size(); ++n) {
      D[n] = 0.04 + 0.02 * std::sin(0.7 * double(n));
      q[n] = 1e-3 * std::cos(0.3 * double(n));
      k[n] = 1e-3 * (1.0 + std::sin(double(n)));
      ux[n] = 0.03 * std::cos(0.1 * double(n));
      C0[n] = 1.0 + 0.5 * std::sin(0.9 * double(n));
    }
    lat.set_velocity(ux, uy);
    lat.initialize(C0);
    const double start = lat.stored_amount();
    for (int s = 0; s < 300; ++s) {
      lat.step();
      EXPECT_LT(lat.mass_balance().relative_residual(), 1e-13) << s;
    }
    // The amount is r-weighted: Σ g* = Σ r C + ½ Σ r q_tot.
    const auto r = lat.row_radius();
    double weighted_source = 0.0;
    for (std::size_t n = 0; n < g.size(); ++n)
      weighted_source += r[n / 10] * (q[n] - k[n] * lat.concentration()[n]);
    EXPECT_NEAR(lat.stored_amount(), lat.total_amount() + 0.5 * weighted_source, 1e-12 * lat.mass_balance().scale);
    EXPECT_NE(lat.stored_amount(), start);
  }
}

TEST(TransportAxisymmetric, UniformConcentrationIsTheSteadyState) {
  // Between the axis and a zero-flux outer side, with an axial velocity and a per-node D varying
  // along the axis, D2Q5 (BGK and TRT): the drift D/r balances the gradient of φ = r C, so the
  // steady state is C = 1 (the equilibrium start is not steady: the first steps move C by
  // ~1e-4 and it relaxes back).
  const Grid g{8, 10};
  for (const Collision kind : {Collision::bgk, Collision::trt}) {
    TransportLattice lat(g, Stencil::d2q5, {kPeriodic, kPeriodic, kZeroFlux, kZeroFlux});
    lat.set_axisymmetric(0.0);
    lat.set_collision({kind, 0.25});
    auto D = lat.diffusivity();
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) D[g.index(x, y)] = 0.05 + 0.01 * x;
    lat.set_uniform_velocity(0.02, 0.0);
    lat.initialize_uniform(1.0);
    for (int s = 0; s < 20000; ++s) lat.step();
    for (double c : lat.concentration()) EXPECT_NEAR(c, 1.0, 1e-11);
  }
}

TEST(TransportAxisymmetric, ThreadCountDoesNotChangeBits) {
  // Above the kernel's threading threshold, with a D field (the per-node source scaling), an axial
  // velocity, a source and a sink: 1 and 2 threads agree bitwise.
  const Grid g{160, 128};
  auto run = [&](int threads) {
#if defined(_OPENMP)
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    TransportLattice lat(g, Stencil::d2q5, {kPeriodic, kPeriodic, kZeroFlux, Side{SideKind::fixed_concentration, 1.0}});
    lat.set_axisymmetric(0.0);
    lat.set_collision({Collision::trt, 0.25});
    auto D = lat.diffusivity();
    auto q = lat.source();
    auto k = lat.decay_rate();
    std::vector<double> C(g.size());
    for (std::size_t n = 0; n < g.size(); ++n) {
      D[n] = 0.1 + 0.05 * std::sin(0.3 * double(n));
      q[n] = 1e-3 * std::cos(0.2 * double(n));
      k[n] = 1e-3;
      C[n] = std::sin(0.1 * double(n));
    }
    lat.set_uniform_velocity(0.02, 0.0);
    lat.initialize(C);
    for (int s = 0; s < 10; ++s) lat.step();
    return std::make_pair(std::vector<double>(lat.concentration().begin(), lat.concentration().end()),
                          lat.mass_balance().amount);
  };
  const auto a = run(1), b = run(2);
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
}

TEST(TransportAxisymmetric, RejectsInconsistentSides) {
  const Grid g{4, 4};
  const Side held{SideKind::fixed_concentration, 1.0};
  TransportLattice periodic(g, Stencil::d2q5, {kPeriodic, kPeriodic, kPeriodic, kPeriodic});
  EXPECT_THROW(periodic.set_axisymmetric(0.0), std::invalid_argument);
  TransportLattice held_axis(g, Stencil::d2q5, {kPeriodic, kPeriodic, held, held});
  EXPECT_THROW(held_axis.set_axisymmetric(0.0), std::invalid_argument);  // the axis must be zero flux
  EXPECT_NO_THROW(held_axis.set_axisymmetric(2.0));                      // an annulus may be held
  EXPECT_THROW(held_axis.set_axisymmetric(-1.0), std::invalid_argument);
}
