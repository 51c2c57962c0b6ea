// Unit checks of the curved-interface tools of the transport layer (docs/transport.md §1
// "Curved diffusivity jumps"): the D2Q5 TRT diffusivity tensor (eq T8), the cut cells of a
// polygon and the subpixel tensor (T9–T10), the face-flux correction (T11). Their convergence
// across a curved jump is the case verification.transport_curved_interface.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "busy_lattice.hpp"
#include "geometry/polygon.hpp"
#include "transport/face_flux_correction.hpp"
#include "transport/subpixel_diffusivity.hpp"
#include "transport/transport_lattice.hpp"

using namespace erythro;
using namespace erythro::transport;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Amplitude decay rate per step of the periodic mode cos(k_x x + k_y y) under a uniform tensor D.
double mode_decay_rate(double dxx, double dyy, double dxy, int mx, int my) {
  const Grid g{64, 64};
  TransportLattice lat(g, Stencil::d2q5, {});
  lat.set_collision({Collision::trt, 0.25});
  auto T = lat.diffusivity_tensor();
  std::fill(T.xx.begin(), T.xx.end(), dxx);
  std::fill(T.yy.begin(), T.yy.end(), dyy);
  std::fill(T.xy.begin(), T.xy.end(), dxy);
  const double kx = 2.0 * kPi * mx / g.nx, ky = 2.0 * kPi * my / g.ny;
  std::vector<double> C(g.size());
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) C[g.index(x, y)] = 1.0 + std::cos(kx * x + ky * y);
  lat.initialize(C);
  auto amplitude = [&] {  // projection on the mode
    double s = 0.0;
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) s += (lat.concentration()[g.index(x, y)] - 1.0) * std::cos(kx * x + ky * y);
    return s;
  };
  for (int s = 0; s < 20; ++s) lat.step();  // let the initial non-equilibrium settle
  const double a0 = amplitude();
  const int steps = 200;
  for (int s = 0; s < steps; ++s) lat.step();
  return -std::log(amplitude() / a0) / steps;
}

}  // namespace

TEST(TransportTensor, ReducesToScalarTrtWhenIsotropic) {
  auto a = test_support::busy_lattice(Stencil::d2q5, {Collision::trt, 0.25}, 0.1, true);
  auto b = test_support::busy_lattice(Stencil::d2q5, {Collision::trt, 0.25}, 0.1, true);
  b.diffusivity_tensor();  // enabled: xx = yy = the scalar field, xy = 0
  for (int s = 0; s < 60; ++s) {
    a.step();
    b.step();
  }
  double d = 0.0;
  for (std::size_t n = 0; n < a.grid().size(); ++n) {
    d = std::max(d, std::fabs(a.concentration()[n] - b.concentration()[n]));
  }
  EXPECT_LT(d, 1e-13);
  EXPECT_LT(std::fabs(b.mass_balance().relative_residual()), 1e-13);
}

TEST(TransportTensor, NeedsTrtOnD2Q5) {
  auto bgk = test_support::busy_lattice(Stencil::d2q5, {}, 0.1, false);
  bgk.diffusivity_tensor();
  EXPECT_THROW(bgk.step(), std::logic_error);
  auto q9 = test_support::busy_lattice(Stencil::d2q9, {Collision::trt, 0.25}, 0.1, false);
  q9.diffusivity_tensor();
  EXPECT_THROW(q9.step(), std::logic_error);
}

// A long-wave mode decays at k·D·k: the off-diagonal D_xy speeds up the (1, 1) mode and slows
// the (1, −1) mode by 2 D_xy k_x k_y (discretisation error O(k²) ≈ 1 % at k = 2π/64).
TEST(TransportTensor, LongWaveModesDecayAtKDK) {
  const double dxx = 0.2, dyy = 0.1, dxy = 0.08, k = 2.0 * kPi / 64.0;
  EXPECT_NEAR(mode_decay_rate(dxx, dyy, dxy, 1, 1) / (k * k * (dxx + dyy + 2.0 * dxy)), 1.0, 0.02);
  EXPECT_NEAR(mode_decay_rate(dxx, dyy, dxy, 1, -1) / (k * k * (dxx + dyy - 2.0 * dxy)), 1.0, 0.02);
  EXPECT_NEAR(mode_decay_rate(dxx, dyy, dxy, 1, 0) / (k * k * dxx), 1.0, 0.02);
}

// The subpixel tensor (T10) has the interface normal as eigenvector with the series mean and
// the tangent with the parallel mean.
TEST(SubpixelDiffusivity, NormalSeesSeriesTangentSeesParallel) {
  const double Din = 0.1, Dout = 0.4, phi = 0.3, th = 0.7;
  const CutCell c{0, phi, std::cos(th), std::sin(th)};
  const auto d = subpixel_diffusivity(c, Din, Dout);
  const double Ds = series_diffusivity(phi, Din, Dout), Dp = parallel_diffusivity(phi, Din, Dout);
  EXPECT_NEAR(Ds, 1.0 / (phi / Din + (1 - phi) / Dout), 1e-15);
  EXPECT_NEAR(Dp, phi * Din + (1 - phi) * Dout, 1e-15);
  const double nx = c.nx, ny = c.ny;
  EXPECT_NEAR(d.xx * nx + d.xy * ny, Ds * nx, 1e-14);
  EXPECT_NEAR(d.xy * nx + d.yy * ny, Ds * ny, 1e-14);
  EXPECT_NEAR(d.xx * -ny + d.xy * nx, Dp * -ny, 1e-14);
  EXPECT_NEAR(d.xy * -ny + d.yy * nx, Dp * nx, 1e-14);
  const auto iso = subpixel_diffusivity({0, phi, 0.0, 0.0}, Din, Dout);  // no normal: series
  EXPECT_DOUBLE_EQ(iso.xx, Ds);
  EXPECT_DOUBLE_EQ(iso.xy, 0.0);
}

// Cut cells of a large rotated square whose one side crosses a 20 × 20 grid: the area fractions
// add up to the polygon's area within the grid, and every node cut by that side alone has the
// side's outward normal.
TEST(SubpixelDiffusivity, CutCellsHaveExactAreasAndNormals) {
  const double th = 0.4, c = std::cos(th), s = std::sin(th);
  // square of side 40 rotated by th; its right side passes through (10.3, 10.1) with outward
  // normal (cos th, sin th); the rest lies far outside the grid to the left
  geometry::Polygon p;
  const double cx = 10.3 - 20.0 * c, cy = 10.1 - 20.0 * s;
  const double u[4][2] = {{20, -20}, {20, 20}, {-20, 20}, {-20, -20}};  // counter-clockwise
  for (const auto& v : u) {
    p.x.push_back(cx + c * v[0] - s * v[1]);
    p.y.push_back(cy + s * v[0] + c * v[1]);
  }
  const auto cells = cut_cells(p, 20, 20);
  double area = 0.0;
  int checked = 0;
  for (const auto& k : cells) {
    area += k.phi;
    if (k.phi > 1e-9 && k.phi < 1.0 - 1e-9) {  // (round-off φ of squares touching nothing: no normal)
      EXPECT_NEAR(k.nx, c, 1e-12);
      EXPECT_NEAR(k.ny, s, 1e-12);
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
  // area left of the line (x − 10.3) c + (y − 10.1) s = 0 within [0, 20]²: midpoint rule per column
  // is exact for a line that does not cross y = 0 or 20 within the column; compare with fine sums
  double exact = 0.0;
  const int m = 20000;
  for (int i = 0; i < m; ++i) {
    const double x = (i + 0.5) * 20.0 / m;
    const double y_line = 10.1 - (x - 10.3) * c / s;  // inside: y < y_line
    exact += std::clamp(y_line, 0.0, 20.0) * 20.0 / m;
  }
  EXPECT_NEAR(area, exact, 1e-6);
}

// With FaceFluxCorrection, the steady lattice is the finite-volume scheme with the TARGET face
// fluxes: K*(Ĉ_a − Ĉ_b) − X* t on the listed faces, the lattice's harmonic face D elsewhere (T11).
TEST(FaceFluxCorrection, SteadyStateIsFiniteVolumeWithTargetFluxes) {
  const Grid g{16, 14};
  const Side held{SideKind::fixed_concentration, 0.0};
  TransportLattice lat(g, Stencil::d2q5, {held, held, held, held});
  lat.set_collision({Collision::trt, 0.25});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  auto D = lat.diffusivity();
  for (auto& d : D) d = 0.1 + 0.3 * u01(rng);
  std::vector<double> q_base(g.size());
  for (auto& v : q_base) v = 1e-3 * u01(rng);
  std::vector<FaceTarget> targets;
  for (int y = 2; y < 11; ++y)
    for (int x = 2; x < 12; ++x)
      for (bool xf : {true, false}) {
        targets.push_back({g.index(x, y), xf, 0.1 + 0.3 * u01(rng), 0.04 * (u01(rng) - 0.5)});
      }
  FaceFluxCorrection corr(g, D, targets);
  auto q = lat.source();
  std::copy(q_base.begin(), q_base.end(), q.begin());
  lat.initialize_uniform(0.0);
  double worst_sum = 0.0;
  for (int s = 0; s < 6000; ++s) {
    corr.evaluate(lat);
    std::copy(q_base.begin(), q_base.end(), q.begin());
    corr.add_to(q);
    double sum = 0.0, base = 0.0;
    for (std::size_t n = 0; n < g.size(); ++n) {
      sum += q[n];
      base += q_base[n];
    }
    worst_sum = std::max(worst_sum, std::fabs(sum - base));
    lat.step();
  }
  EXPECT_LT(worst_sum, 1e-15);  // mass-conserving source pairs
  // finite-volume residual with the target fluxes
  auto C = [&](int x, int y) { return lat.source_corrected_concentration(g.index(x, y)); };
  std::vector<double> K_x(g.size(), -1.0), K_y(g.size(), -1.0), X_x(g.size(), 0.0), X_y(g.size(), 0.0);
  for (const auto& t : targets) (t.x_face ? K_x : K_y)[t.a] = t.K, (t.x_face ? X_x : X_y)[t.a] = t.X;
  auto flux = [&](int x, int y, bool xf) {  // from (x, y) to its +x / +y neighbour
    const std::size_t a = g.index(x, y);
    const int bx = xf ? x + 1 : x, by = xf ? y : y + 1;
    const double K_lat = 2.0 / (1.0 / D[a] + 1.0 / D[g.index(bx, by)]);
    const double K = (xf ? K_x : K_y)[a] >= 0.0 ? (xf ? K_x : K_y)[a] : K_lat;
    double F = K * (C(x, y) - C(bx, by));
    const double X = (xf ? X_x : X_y)[a];
    if (X != 0.0) {
      const double t = xf ? 0.25 * (C(x, y + 1) - C(x, y - 1) + C(bx, by + 1) - C(bx, by - 1))
                          : 0.25 * (C(x + 1, y) - C(x - 1, y) + C(bx + 1, by) - C(bx - 1, by));
      F -= X * t;
    }
    return F;
  };
  double worst = 0.0;
  for (int y = 1; y + 1 < g.ny; ++y)
    for (int x = 1; x + 1 < g.nx; ++x) {
      const double out = flux(x, y, true) - flux(x - 1, y, true) + flux(x, y, false) - flux(x, y - 1, false);
      worst = std::max(worst, std::fabs(out - q_base[g.index(x, y)]) / 1e-3);
    }
  EXPECT_LT(worst, 1e-9);
}

// The face-flux correction is explicit and lagged, and reads Ĉ = C + φ q, which holds its own last
// correction: a feedback whose row-sum gain grows with the diffusivity contrast (not with Δt).
// On a disc of radius 9 in a held box: 950:2800 is far inside the limit and stays bounded;
// 1:20 exceeds it, is rejected by require_stable, and run anyway it does diverge (what the limit
// is for). docs/transport.md, "Stability of the face-flux correction".
TEST(FaceFluxCorrection, LaggedGainRejectsHighContrastsThatDiverge) {
  const int n = 30;
  geometry::Polygon disc;
  for (int k = 0; k < 200; ++k) {
    const double a = 2.0 * kPi * k / 200.0;
    disc.x.push_back(15.2 + 9.0 * std::cos(a));
    disc.y.push_back(14.9 + 9.0 * std::sin(a));
  }
  auto run = [&](double D_in, double D_out, double& gain) {
    const Grid g{n, n};
    const Side held{SideKind::fixed_concentration, 0.0};
    TransportLattice lat(g, Stencil::d2q5, {held, held, held, held});
    lat.set_collision({Collision::trt, 0.25});
    lat.set_uniform_diffusivity(D_out);
    auto D = lat.diffusivity();
    std::vector<double> C0(g.size(), 0.0);
    for (const auto& c : area_fractions(disc, n, n)) {
      D[c.node] = series_diffusivity(c.phi, D_in, D_out);
      C0[c.node] = c.phi;
    }
    lat.initialize(C0);
    FaceFluxCorrection corr(g, D, subpixel_face_targets(disc, n, n, D_in, D_out));
    gain = corr.lagged_gain(lat);
    auto q = lat.source();
    double peak = 0.0;
    for (int s = 0; s < 400; ++s) {
      corr.evaluate(lat);
      std::fill(q.begin(), q.end(), 0.0);
      corr.add_to(q);
      lat.step();
      for (double c : lat.concentration()) peak = std::max(peak, std::isfinite(c) ? std::abs(c) : 1e300);
    }
    EXPECT_EQ(gain > FaceFluxCorrection::kLaggedGainLimit, [&] {
      try {
        corr.require_stable(lat);
        return false;
      } catch (const std::invalid_argument&) {
        return true;
      }
    }());
    return peak;
  };
  double low = 0.0, high = 0.0;
  const double peak_low = run(0.05, 0.05 * 2800.0 / 950.0, low);
  const double peak_high = run(0.02, 0.4, high);
  EXPECT_LT(low, 0.5 * FaceFluxCorrection::kLaggedGainLimit);
  EXPECT_LE(peak_low, 1.0 + 1e-12);  // maximum principle: bounded by the initial 1
  EXPECT_GT(high, FaceFluxCorrection::kLaggedGainLimit);
  EXPECT_GT(peak_high, 10.0);  // the rejected set-up really diverges
}
