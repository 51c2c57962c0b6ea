// The axisymmetric lattice across jumps of D, and the face-flux correction on it
// (FaceFluxCorrection with row radii; docs/model.md eq 7.9'):
//  - the lattice alone: its steady state (offset-corrected, T7) solves the conservative
//    cylindrical finite-volume scheme with face conductances r_f K, K the harmonic mean of the
//    node D's, to round-off, also across jumps (the TRT advective flux of the drift D/r is weighted
//    by 1/D like the diffusive one, so it gives K φ/r = K C at the face), and a uniform C stays;
//  - with the correction and listed targets K*: the same scheme with r_f K* on those faces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "transport/face_flux_correction.hpp"
#include "transport/transport_lattice.hpp"

using namespace erythro;
using namespace erythro::transport;

namespace {

constexpr Side kZeroFlux{SideKind::zero_flux, 0.0};
constexpr Side kPeriodic{SideKind::periodic, 0.0};
constexpr Side kHeld{SideKind::fixed_concentration, 1.0};

struct Faces {
  std::vector<double> east, north;  // per radian: r_f × conductance (0: no face)
};

// Conductances of the target scheme: harmonic K of the node D's times the face's radius, with
// the listed targets replacing K.
Faces target_conductances(const Grid& g, std::span<const double> r, const std::vector<double>& D,
                          const std::vector<FaceTarget>& targets) {
  Faces f{std::vector<double>(g.size(), 0.0), std::vector<double>(g.size(), 0.0)};
  const auto harmonic = [&](std::size_t a, std::size_t b) { return 2.0 / (1.0 / D[a] + 1.0 / D[b]); };
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) {
      const std::size_t n = g.index(x, y);
      f.east[n] = r[static_cast<std::size_t>(y)] * harmonic(n, g.index((x + 1) % g.nx, y));
      if (y + 1 < g.ny) f.north[n] = (r[static_cast<std::size_t>(y)] + 0.5) * harmonic(n, g.index(x, y + 1));
    }
  for (const auto& t : targets) {
    const double ry = r[t.a / static_cast<std::size_t>(g.nx)];
    (t.x_face ? f.east : f.north)[t.a] = (t.x_face ? ry : ry + 0.5) * t.K;
  }
  return f;
}

// A D2Q5 TRT (Λ = ¼) lattice on g, axisymmetric about its bottom side, periodic in x, held at
// C = 1 on top, D = 0.15 until a per-node field is written.
TransportLattice cylinder(const Grid& g) {
  TransportLattice lat(g, Stencil::d2q5, {kPeriodic, kPeriodic, kZeroFlux, kHeld});
  lat.set_axisymmetric(0.0);
  lat.set_collision({Collision::trt, 0.25});
  lat.set_uniform_diffusivity(0.15);
  return lat;
}

// Steady state of a 6 × 12 cylinder with a block of low D next to the axis and a source inside
// it; returns max |FV residual| / max |r q|.
double steady_residual(bool corrected, bool with_targets) {
  const Grid g{6, 12};
  TransportLattice lat = cylinder(g);
  auto Dspan = lat.diffusivity();
  std::vector<double> base(g.size(), 0.0);
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) {
      const bool inside = x >= 1 && x <= 3 && y <= 4;
      Dspan[g.index(x, y)] = inside ? (y == 4 ? 0.09 : 0.05) : 0.15;
      base[g.index(x, y)] = inside ? 2e-3 * (1.0 + 0.2 * y) : 0.0;
    }
  const std::vector<double> D(Dspan.begin(), Dspan.end());
  std::vector<FaceTarget> targets;
  if (with_targets)  // two faces with their own conductance: a radial one on the axis row, an axial one
    targets = {{g.index(2, 0), false, 0.07, 0.0}, {g.index(3, 4), true, 0.11, 0.0}};
  FaceFluxCorrection correction(g, D, targets, lat.row_radius());
  auto q = lat.source();
  std::copy(base.begin(), base.end(), q.begin());
  lat.initialize_uniform(1.0);
  for (int s = 0; s < 40000; ++s) {
    if (corrected) {
      correction.evaluate(lat);
      std::copy(base.begin(), base.end(), q.begin());
      correction.add_to(q);
    }
    lat.step();
  }
  std::vector<double> C(g.size());
  for (std::size_t n = 0; n < g.size(); ++n) C[n] = lat.source_corrected_concentration(n);  // eq T7
  const Faces f = target_conductances(g, lat.row_radius(), D, targets);
  const auto r = lat.row_radius();
  double worst = 0.0, scale = 0.0;
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) {
      const std::size_t n = g.index(x, y), w = g.index((x + g.nx - 1) % g.nx, y);
      const double ry = r[static_cast<std::size_t>(y)];
      double div = f.east[n] * (C[g.index((x + 1) % g.nx, y)] - C[n]) - f.east[w] * (C[n] - C[w]);
      if (y + 1 < g.ny) div += f.north[n] * (C[g.index(x, y + 1)] - C[n]);
      else div += 2.0 * (ry + 0.5) * D[n] * (1.0 - C[n]);  // the held side, halfway (eq 7.10)
      if (y > 0) div -= f.north[g.index(x, y - 1)] * (C[n] - C[g.index(x, y - 1)]);
      worst = std::max(worst, std::fabs(div + ry * base[n]));
      scale = std::max(scale, std::fabs(ry * base[n]));
    }
  return worst / scale;
}

}  // namespace

TEST(FaceFluxAxisymmetric, SteadyStateIsTheCylindricalFiniteVolumeSchemeAcrossJumps) {
  EXPECT_LT(steady_residual(false, false), 1e-10);  // the lattice alone: the harmonic K of the node D's
  EXPECT_LT(steady_residual(true, true), 1e-10);    // corrected towards two targets of their own
  EXPECT_GT(steady_residual(false, true), 1e-3);    // uncorrected: not the targets' scheme
}

TEST(FaceFluxAxisymmetric, UniformConcentrationStaysUniformAcrossJumps) {
  // Without a source a held C = 1 everywhere is the steady state of the lattice alone: it stays, to
  // round-off, whatever the jumps of D (a face flux of C itself, which a node drift could leave,
  // would move it). A correction without targets lists no face.
  const Grid g{4, 8};
  TransportLattice lat = cylinder(g);
  auto D = lat.diffusivity();
  for (int y = 0; y < 4; ++y) D[g.index(1, y)] = D[g.index(2, y)] = 0.04;
  EXPECT_EQ(FaceFluxCorrection(g, std::vector<double>(D.begin(), D.end()), {}, lat.row_radius()).faces(), 0u);
  lat.initialize_uniform(1.0);
  for (int s = 0; s < 2000; ++s) lat.step();
  double worst = 0.0;
  for (const double c : lat.concentration()) worst = std::max(worst, std::fabs(c - 1.0));
  EXPECT_LT(worst, 1e-12);  // round-off over 2000 steps (1.5e-13 measured)
}
