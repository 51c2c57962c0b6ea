// Unit tests of the short-range repulsion (aggregation/repulsion.hpp, docs/model.md §4b):
// the pair density and its derivative, the wall's closed form against a quadrature of the
// pair density, and CellContacts with repulsion (and Morse): forces = −∇E, the cell list
// equal to the brute force bit for bit, Morse alone unchanged.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "aggregation/cell_contacts.hpp"
#include "aggregation/repulsion.hpp"
#include "common/portable_hypot.hpp"
#include "tests/aggregation/ring_grid.hpp"

using namespace erythro;
using namespace erythro::aggregation;

namespace {

const RepulsionParameters kRep{0.02, 2.0, true};
const MorseParameters kMorse{0.3, 2.5, 0.8, 6.0};

// W(s) = ∫ Φ_r(√(s² + u²)) du over |u| < √(d² − s²), composite Simpson (the integrand is
// smooth there; its derivative is continuous at the ends, so the error falls like n⁻²).
double wall_quadrature(const RepulsionParameters& p, double s, int n = 200000) {
  const Repulsion rep(p);
  const double a = std::sqrt(p.range * p.range - s * s), hstep = 2.0 * a / n;
  auto f = [&](double u) {
    double phi = 0.0, dphi = 0.0;
    rep.evaluate(std::hypot(s, u), phi, dphi);
    return phi;
  };
  double sum = f(-a) + f(a);
  for (int i = 1; i < n; ++i) sum += f(-a + i * hstep) * (i % 2 ? 4.0 : 2.0);
  return sum * hstep / 3.0;
}

// Two rings of n markers (radius R) with centres a distance `sep` apart along x, at height y0.
struct TwoRings {
  std::vector<double> x, y;
  std::vector<std::size_t> off;
  TwoRings(int n, double R, double cx, double sep, double y0) {
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < n; ++k) {
        const double t = 2.0 * std::numbers::pi * k / n + 0.1 * c;
        x.push_back(cx + c * sep + R * std::cos(t));
        y.push_back(y0 + R * std::sin(t));
      }
    off = {0, static_cast<std::size_t>(n), static_cast<std::size_t>(2 * n)};
  }
  MarkerView view() const { return {x, y, off}; }
};

}  // namespace

TEST(Repulsion, PairDensityValuesAndDerivative) {
  const Repulsion r(kRep);
  double phi = 0.0, dphi = 0.0;
  ASSERT_TRUE(r.evaluate(1.0, phi, dphi));  // d/r − 1 = 1
  EXPECT_DOUBLE_EQ(phi, kRep.pressure);
  EXPECT_DOUBLE_EQ(dphi, -2.0 * kRep.pressure * 2.0);
  EXPECT_FALSE(r.evaluate(kRep.range, phi, dphi));
  EXPECT_EQ(phi, 0.0);
  EXPECT_EQ(dphi, 0.0);
  // Energy and force continuous at d; repulsive (dΦ/dr < 0) inside.
  r.evaluate(kRep.range * (1.0 - 1e-9), phi, dphi);
  EXPECT_NEAR(phi, 0.0, 1e-18);
  EXPECT_NEAR(dphi, 0.0, 1e-10);
  for (double x : {0.3, 0.9, 1.5, 1.99}) {
    double pp, dp, pm, dm, p0, d0;
    const double e = 1e-6;
    r.evaluate(x + e, pp, dp);
    r.evaluate(x - e, pm, dm);
    r.evaluate(x, p0, d0);
    EXPECT_NEAR(d0, (pp - pm) / (2 * e), 1e-7 * std::max(1.0, std::abs(d0))) << x;
    EXPECT_LT(d0, 0.0) << x;
  }
  EXPECT_THROW(Repulsion({0.0, 2.0, true}), std::invalid_argument);
  EXPECT_THROW(Repulsion({0.1, -1.0, true}), std::invalid_argument);
  EXPECT_THROW(Repulsion({std::nan(""), 1.0, true}), std::invalid_argument);
}

TEST(Repulsion, WallClosedFormMatchesQuadratureAndItsDerivative) {
  for (double s : {0.1, 0.5, 1.0, 1.7, 1.99}) {
    const double W = wall_energy(kRep, s);
    EXPECT_NEAR(W, wall_quadrature(kRep, s), 1e-8 * W) << s;
    const double e = 1e-6 * s;
    const double fd = (wall_energy(kRep, s + e) - wall_energy(kRep, s - e)) / (2 * e);
    EXPECT_NEAR(wall_energy_derivative(kRep, s), fd, 1e-6 * std::abs(fd)) << s;
  }
  EXPECT_EQ(wall_energy(kRep, kRep.range), 0.0);
  EXPECT_EQ(wall_energy_derivative(kRep, 3.0), 0.0);
  EXPECT_TRUE(std::isinf(wall_energy(kRep, 0.0)));
  // eq 4.12: the flat-contact pressure −W'(s) is 2P(4π/3 − √3) ≈ 4.91 P at s = d/2 and
  // tends to πPd²/s² as s → 0.
  EXPECT_NEAR(-wall_energy_derivative(kRep, 1.0), 2.0 * kRep.pressure * (4.0 * std::numbers::pi / 3.0 - std::sqrt(3.0)),
              1e-14);
  const double s = 1e-3;
  EXPECT_NEAR(-wall_energy_derivative(kRep, s) / (std::numbers::pi * kRep.pressure * 4.0 / (s * s)), 1.0, 2e-3);
}

TEST(ContactPotential, MorseAloneIsBitwiseShiftedMorseAndBothAdd) {
  const ShiftedMorse morse(kMorse);
  const Repulsion rep(kRep);
  const ContactPotential alone(ContactLaw{kMorse, std::nullopt});
  const ContactPotential both(ContactLaw{kMorse, kRep});
  EXPECT_EQ(alone.cutoff(), kMorse.cutoff);
  for (double r : {0.2, 1.0, 1.99, 2.0, 3.0, 5.9}) {
    double a, da, m, dm, b, db, q, dq;
    alone.evaluate(r, a, da);
    morse.evaluate(r, m, dm);
    EXPECT_EQ(a, m);
    EXPECT_EQ(da, dm);
    both.evaluate(r, b, db);
    rep.evaluate(r, q, dq);
    EXPECT_EQ(b, m + q) << r;
    EXPECT_EQ(db, dm + dq) << r;
  }
  const ContactPotential repulsion_only(ContactLaw{std::nullopt, kRep});
  EXPECT_EQ(repulsion_only.cutoff(), kRep.range);
  EXPECT_THROW(ContactPotential(ContactLaw{std::nullopt, std::nullopt}), std::invalid_argument);
}

TEST(ContactPotential, EvaluateManyGivesTheBitsOfEvaluate) {
  // The vector loop writes the two parts' formulas out (calling the parts from it was measured
  // not to vectorise): every lane must give evaluate()'s bits, for each combination of parts,
  // inside and beyond each cut-off.
  const std::vector<ContactPotential> laws{ContactPotential(ContactLaw{kMorse, std::nullopt}),
                                           ContactPotential(ContactLaw{std::nullopt, kRep}),
                                           ContactPotential(ContactLaw{kMorse, kRep})};
  std::vector<double> r;
  for (int i = 1; i <= 301; ++i) r.push_back(0.021 * i);  // 0.021 … 6.32: across d and r_c
  r.push_back(kRep.range);
  r.push_back(kMorse.cutoff);
  for (const ContactPotential& law : laws) {
    std::vector<double> phi(r.size()), dphi(r.size());
    std::vector<unsigned char> on(r.size());
    law.evaluate_many(r.data(), r.size(), phi.data(), dphi.data(), on.data());
    for (std::size_t i = 0; i < r.size(); ++i) {
      double p, dp;
      const bool o = law.evaluate(r[i], p, dp);
      ASSERT_EQ(on[i] != 0, o) << r[i];
      ASSERT_EQ(phi[i], p) << r[i];
      ASSERT_EQ(dphi[i], dp) << r[i];
    }
  }
}

// Forces are −∂E/∂X (pairs, edges and walls), the cell list gives the brute force's bits, and
// without walls the total force vanishes.
TEST(CellContacts, RepulsionForcesAreTheNegativeGradient) {
  for (const bool walls : {false, true}) {
    SCOPED_TRACE(walls ? "walls in y" : "periodic");
    const geometry::Domain dom{Grid{40, 30}, true, !walls};
    for (const ContactLaw& law : {ContactLaw{std::nullopt, kRep}, ContactLaw{kMorse, kRep}}) {
      TwoRings rings(24, 4.0, 10.0, 9.5, 5.2);  // gap 1.5 < d; the bottom 1.2 above the wall
      CellContacts contacts(dom, law);
      std::vector<double> fx(rings.x.size(), 0.0), fy(rings.x.size(), 0.0);
      const ContactStats st = contacts.add_forces(rings.view(), fx, fy);
      EXPECT_GT(st.pairs, 0u);
      EXPECT_EQ(st.wall_markers > 0, walls);
      EXPECT_NEAR(st.energy, contacts.energy(rings.view()), 1e-15 * std::abs(st.energy));
      double sx = 0.0, sy = 0.0;
      for (std::size_t m = 0; m < rings.x.size(); ++m) {
        sx += fx[m];
        sy += fy[m];
        const double e = 1e-6;
        for (std::vector<double>* q : {&rings.x, &rings.y}) {
          const double keep = (*q)[m];
          (*q)[m] = keep + e;
          const double ep = contacts.energy(rings.view());
          (*q)[m] = keep - e;
          const double em = contacts.energy(rings.view());
          (*q)[m] = keep;
          const double f = q == &rings.x ? fx[m] : fy[m];
          EXPECT_NEAR(f, -(ep - em) / (2 * e), 1e-6 * (std::abs(f) + 1e-3)) << m;
        }
      }
      EXPECT_NEAR(sx, 0.0, 1e-13);
      if (walls) EXPECT_GT(sy, 0.0);  // the bottom wall pushes the cells up
      else EXPECT_NEAR(sy, 0.0, 1e-13);
      std::vector<double> bx(rings.x.size(), 0.0), by(rings.x.size(), 0.0);
      const ContactStats b = add_forces_brute_force(dom, law, rings.view(), bx, by);
      EXPECT_EQ(b.energy, st.energy);
      EXPECT_EQ(b.pairs, st.pairs);
      for (std::size_t m = 0; m < bx.size(); ++m) {
        EXPECT_EQ(bx[m], fx[m]);
        EXPECT_EQ(by[m], fy[m]);
      }
    }
  }
}

TEST(CellContacts, RepulsionPushesApartAndAMarkerOnAWallIsReported) {
  const geometry::Domain dom{Grid{40, 30}, true, false};
  CellContacts contacts(dom, ContactLaw{std::nullopt, kRep});
  TwoRings rings(24, 4.0, 10.0, 9.5, 15.0);
  std::vector<double> fx(rings.x.size(), 0.0), fy(rings.x.size(), 0.0);
  contacts.add_forces(rings.view(), fx, fy);
  double left = 0.0, right = 0.0;
  for (std::size_t m = 0; m < 24; ++m) left += fx[m];
  for (std::size_t m = 24; m < 48; ++m) right += fx[m];
  EXPECT_LT(left, 0.0);  // ring 0 pushed towards −x, ring 1 towards +x
  EXPECT_GT(right, 0.0);
  rings.y[3] = -0.1;  // beyond the bottom wall
  try {
    contacts.add_forces(rings.view(), fx, fy);
    ADD_FAILURE() << "no error for a marker beyond the wall";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("marker 3 (cell 0) is 0.1"), std::string::npos) << e.what();
  }
  // The range must stay below half a periodic side.
  EXPECT_THROW(CellContacts(geometry::Domain{Grid{3, 30}, true, false}, ContactLaw{std::nullopt, kRep}),
               std::invalid_argument);
}

TEST(CellContacts, WallsAndStatisticsSameOnAnyThreadCount) {
  // 3 000 markers (above kParallelMarkers, so the per-marker passes run in parallel) in a
  // channel, the lowest rings within the bottom wall's range: forces, energy and every
  // statistic (closest pair, pairs, closest wall, markers near a wall) equal on 1 and 2
  // threads; a marker beyond a wall and a non-finite one are reported by their first index.
  const geometry::Domain dom{Grid{200, 204}, true, false};
  const ContactLaw law{kMorse, kRep};
  test_support::RingGrid rings(10.5, 20.0);  // the lowest rings come within 1.2 of the wall
  std::vector<double>&x = rings.x, &y = rings.y;
  const std::vector<std::size_t>& off = rings.off;
  ASSERT_GE(x.size(), CellContacts::kParallelMarkers);
  const std::size_t N = x.size();
  const int threads = omp_get_max_threads();
  auto run = [&](int t, std::vector<double>& fx, std::vector<double>& fy) {
    omp_set_num_threads(t);
    CellContacts c(dom, law);
    fx.assign(N, 0.0);
    fy.assign(N, 0.0);
    const ContactStats s = c.add_forces(MarkerView{x, y, off}, fx, fy);
    omp_set_num_threads(threads);
    return s;
  };
  std::vector<double> f1, g1, f2, g2;
  const ContactStats a = run(1, f1, g1), b = run(2, f2, g2);
  ASSERT_GT(a.wall_markers, 0u);
  ASSERT_GT(a.pairs, 0u);
  EXPECT_EQ(a.wall_markers, b.wall_markers);
  EXPECT_EQ(a.min_wall_distance, b.min_wall_distance);
  EXPECT_EQ(a.min_pair_distance, b.min_pair_distance);
  EXPECT_EQ(a.pairs, b.pairs);
  EXPECT_EQ(a.energy, b.energy);
  EXPECT_EQ(a.max_force, b.max_force);
  for (std::size_t m = 0; m < N; ++m) {
    ASSERT_EQ(f1[m], f2[m]) << m;
    ASSERT_EQ(g1[m], g2[m]) << m;
  }
  // The error names the first offending marker, on one thread and on two.
  auto expect_error_naming = [&](const std::string& text) {
    for (const int t : {1, 2}) {
      omp_set_num_threads(t);
      CellContacts c(dom, law);
      try {
        c.add_forces(MarkerView{x, y, off}, f1, g1);
        ADD_FAILURE() << "no error on " << t << " thread(s); expected one naming: " << text;
      } catch (const std::domain_error& e) {
        EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
      }
      omp_set_num_threads(threads);
    }
  };
  // Markers 2 990 and 1 215 beyond the walls (top, then bottom): the lower index is named.
  y[2990] = 204.3;
  y[1215] = -0.25;
  expect_error_naming("marker 1215 (cell 40) is 0.25");
  y[2990] = NAN;
  x[1701] = INFINITY;
  expect_error_naming("marker 1701 has a non-finite position");
}

TEST(CellContacts, ForceMagnitudesAreHypotsOfTheForcesBitForBit) {
  // force_magnitude() is |F_m| of the contact force by hypot_portable's bits: from the fast
  // path of a vectorised loop for a crowded channel (markers with no partner have F = 0
  // exactly), and for a cell where one force lies beyond the kernel's common range
  // (|F_x| < 2^-54 |F_y|, below), where the fallback runs. (There the kernel would give the
  // same bits; only forces near 2^-459 or 2^511, which positions on a lattice cannot make,
  // tell the two apart, so this checks the bits, not which path gave them.)
  auto check = [](const geometry::Domain& dom, const MarkerView& v) {
    CellContacts c(dom, ContactLaw{kMorse, kRep});
    std::vector<double> fx(v.x.size(), 0.0), fy(v.x.size(), 0.0);
    const ContactStats st = c.add_forces(v, fx, fy);
    const std::span<const double> mag = c.force_magnitude();
    EXPECT_EQ(st.max_force, *std::max_element(mag.begin(), mag.end()));  // the statistic is the largest |F_m|
    for (std::size_t m = 0; m < fx.size(); ++m)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(mag[m]), std::bit_cast<std::uint64_t>(numeric::hypot_portable(fx[m], fy[m])))
          << m;
    return std::make_pair(fx, fy);
  };
  const test_support::RingGrid rings(10.5, 20.0);
  const auto [fx, fy] = check(geometry::Domain{Grid{200, 204}, true, false}, rings.view());
  EXPECT_GT(std::count(fx.begin(), fx.end(), 0.0), 0);  // isolated markers: zero force
  // Marker 1 of cell A sits between two vertical edges (their tensions add nothing along x),
  // its partner of cell B half a unit above it but 2^-62 to the side: F_x is the pair part's
  // tiny x component, F_y of order 100.
  const double a = 1.0 / 1024.0, d = std::ldexp(1.0, -62);
  const std::vector<double> x{a, a, a, a + d, 20.0, 25.0}, y{9.0, 10.0, 11.0, 10.5, 25.0, 25.0};
  const std::vector<std::size_t> off{0, 3, 6};
  const auto [gx, gy] = check(geometry::Domain{Grid{40, 40}, true, true}, MarkerView{x, y, off});
  ASSERT_NE(gx[1], 0.0);
  ASSERT_LT(std::fabs(gx[1]), std::ldexp(std::fabs(gy[1]), -54));  // the fallback ran
}
