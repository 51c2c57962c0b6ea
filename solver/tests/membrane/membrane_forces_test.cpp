// The membrane's tension forces (membrane_energy.cpp: an edge pass that vectorises, then a node
// pass) against the same sums written as one loop over the edges, bit for bit (and the bending's
// vertex and node passes against its one loop over the vertices): for a flowing
// cell, for one so small that its edges lie outside hypot_portable's common range (so the edge
// pass falls back to hypot_portable itself), and with every tension law.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "common/portable_hypot.hpp"
#include "membrane/membrane_energy.hpp"
#include "membrane/rest_shape.hpp"

using namespace erythro;
using namespace erythro::membrane;

namespace {

// The one-loop form (eq 3.7): edge e adds its pull to marker e and takes it from marker e + 1.
void one_loop_tension(const TensionLaw& law, const RestShape& rest, const std::vector<double>& x,
                      const std::vector<double>& y, std::vector<double>& fx, std::vector<double>& fy) {
  const std::size_t n = x.size();
  for (std::size_t e = 0; e < n; ++e) {
    const std::size_t f = (e + 1 == n) ? 0 : e + 1;
    const double dx = x[f] - x[e], dy = y[f] - y[e];
    const double l = numeric::hypot_portable(dx, dy);
    const double T = law.tension(l / rest.length[e]) / l;
    fx[e] += T * dx;
    fy[e] += T * dy;
    fx[f] -= T * dx;
    fy[f] -= T * dy;
  }
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_one_loop_bits(const geometry::Polygon& rest_polygon, const std::vector<double>& x,
                          const std::vector<double>& y) {
  const RestShape rest = RestShape::from_polygon(rest_polygon);
  for (TensionLawType type : {TensionLawType::neo_hookean, TensionLawType::skalak, TensionLawType::hookean}) {
    MembraneModel model;  // tension only: bending and area are separate passes, unchanged
    model.tension = TensionLaw{type, 0.013, 0.7};
    std::vector<double> fx(x.size(), 0.25), fy(x.size(), -0.5), gx = fx, gy = fy;  // nonzero start
    add_membrane_forces_only(model, rest, x, y, fx, fy);
    one_loop_tension(model.tension, rest, x, y, gx, gy);
    EXPECT_TRUE(same_bits(fx, gx) && same_bits(fy, gy)) << to_string(type);
    std::vector<double> hx(x.size(), 0.25), hy(x.size(), -0.5);
    add_membrane_forces(model, rest, x, y, hx, hy);  // the path with the energy: the same forces
    EXPECT_TRUE(same_bits(fx, hx) && same_bits(fy, hy)) << to_string(type);
  }
}

}  // namespace

TEST(MembraneForces, EdgePassGivesTheOneLoopBits) {
  // A 37-marker ellipse at rest, then sheared and stretched unevenly.
  geometry::Polygon p;
  std::vector<double> x, y;
  const int n = 37;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    p.x.push_back(10.0 + 4.0 * std::cos(t));
    p.y.push_back(20.0 + 2.0 * std::sin(t));
    x.push_back(10.0 + 4.3 * std::cos(t) + 0.4 * std::sin(t) + 0.01 * std::sin(7.0 * t));
    y.push_back(20.0 + 1.9 * std::sin(t) + 0.02 * std::cos(3.0 * t));
  }
  expect_one_loop_bits(p, x, y);
}

TEST(MembraneForces, TinyEdgesTakeTheFallbackWithTheSameBits) {
  // The same cell scaled by 1e-160: the edges' squares underflow, outside the common range of
  // hypot's kernel, so the edge pass must fall back to hypot_portable (which calls the library).
  // (An axis-aligned edge does not need it: the kernel gives |dx| exactly there.)
  geometry::Polygon p;
  std::vector<double> x, y;
  const int n = 37;
  const double s = 1e-160;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    p.x.push_back(s * (10.0 + 4.0 * std::cos(t)));
    p.y.push_back(s * (20.0 + 2.0 * std::sin(t)));
    x.push_back(s * (10.0 + 4.3 * std::cos(t) + 0.4 * std::sin(t)));
    y.push_back(s * (20.0 + 1.9 * std::sin(t)));
  }
  expect_one_loop_bits(p, x, y);
}

// The bending's vertex and node passes (forces alone) against the one loop over the vertices (the
// path with the energy), bit for bit, for cells of 37 markers and of 3 (every marker then an end
// of the passes), flowing and with rest angles near ±π (a thin sliver folds back on itself).
TEST(MembraneForces, BendingPassesGiveTheOneLoopBits) {
  for (int n : {37, 3}) {
    for (double aspect : {0.5, 0.02}) {
      geometry::Polygon p;
      std::vector<double> x, y;
      for (int i = 0; i < n; ++i) {
        const double t = 2.0 * M_PI * i / n;
        p.x.push_back(10.0 + 4.0 * std::cos(t));
        p.y.push_back(20.0 + 4.0 * aspect * std::sin(t));
        x.push_back(10.0 + 4.3 * std::cos(t) + 0.4 * std::sin(t) + 0.01 * std::sin(7.0 * t));
        y.push_back(20.0 + 3.9 * aspect * std::sin(t) + 0.02 * std::cos(3.0 * t));
      }
      const RestShape rest = RestShape::from_polygon(p);
      MembraneModel model;
      model.tension = TensionLaw{TensionLawType::skalak, 0.013, 0.7};
      model.bending = 0.37;
      model.area_modulus = 0.05;
      std::vector<double> fx(x.size(), 0.25), fy(x.size(), -0.5), gx = fx, gy = fy;  // nonzero start
      add_membrane_forces_only(model, rest, x, y, fx, fy);
      add_membrane_forces(model, rest, x, y, gx, gy);
      EXPECT_TRUE(same_bits(fx, gx) && same_bits(fy, gy)) << n << " markers, aspect " << aspect;
      double moved = 0.0;  // the bending acts: the forces differ from those without it
      model.bending = 0.0;
      std::vector<double> hx(x.size(), 0.25), hy(x.size(), -0.5);
      add_membrane_forces_only(model, rest, x, y, hx, hy);
      for (std::size_t i = 0; i < x.size(); ++i) moved = std::max(moved, std::fabs(hx[i] - fx[i]));
      EXPECT_GT(moved, 1e-3) << n << " markers, aspect " << aspect;
    }
  }
}

// The wrap of θ_i − θ0_i into (−π, π] (eq 3.6): at a hairpin whose rest turning angle is π − ψ
// and whose current one is −π + φ, the vertex is bent by φ + ψ, not by −2π + φ + ψ. Its energy
// is ½ E_B (φ + ψ)² / D̄ (the path with the energy), and the forces alone (the vertex pass that
// vectorises) are minus that energy's gradient (central differences): each fails if its path
// leaves the difference unwrapped.
TEST(MembraneForces, BendingWrapsTheAngleAtAHairpin) {
  const double phi = 0.03, psi = 0.02;
  const std::vector<double> x = {0.0, 1.0, 1.0 - std::cos(phi)}, y = {0.0, 0.0, -std::sin(phi)};
  RestShape rest;
  rest.length = {1.0, 1.0, std::hypot(x[2], y[2])};
  rest.dual = {1.0, 1.0, 1.0};
  // Vertices 0 and 2 at their current angles (no bending there); vertex 1 at π − ψ.
  rest.turning = {turning_angle(x[0] - x[2], y[0] - y[2], x[1] - x[0], y[1] - y[0]), M_PI - psi,
                  turning_angle(x[2] - x[1], y[2] - y[1], x[0] - x[2], y[0] - y[2])};
  ASSERT_NEAR(turning_angle(x[1] - x[0], y[1] - y[0], x[2] - x[1], y[2] - y[1]), -M_PI + phi, 1e-14);
  MembraneModel model;  // bending alone: no tension modulus, no area term
  model.bending = 1.0;
  const double bent = phi + psi;
  EXPECT_NEAR(membrane_energy(model, rest, x, y).bending, 0.5 * bent * bent, 1e-12);
  std::vector<double> fx(3, 0.0), fy(3, 0.0);
  add_membrane_forces_only(model, rest, x, y, fx, fy);
  const double h = 1e-6;
  for (std::size_t m = 0; m < 3; ++m) {
    for (int axis = 0; axis < 2; ++axis) {
      std::vector<double> xp = x, yp = y, xm = x, ym = y;
      (axis == 0 ? xp : yp)[m] += h;
      (axis == 0 ? xm : ym)[m] -= h;
      const double dE =
          (membrane_energy(model, rest, xp, yp).total() - membrane_energy(model, rest, xm, ym).total()) / (2.0 * h);
      EXPECT_NEAR((axis == 0 ? fx : fy)[m], -dE, 1e-6) << "marker " << m << " axis " << axis;
    }
  }
}
