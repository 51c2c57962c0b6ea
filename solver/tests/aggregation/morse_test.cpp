// Unit tests of the Morse potential (aggregation/morse.hpp), its units
// (aggregation/morse_units.hpp) and small configurations of CellContacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <omp.h>

#include "aggregation/morse.hpp"
#include "aggregation/cell_contacts.hpp"
#include "aggregation/morse_units.hpp"
#include "tests/aggregation/ring_grid.hpp"
#include "fluid/fluid_lattice.hpp"
#include "geometry/shapes.hpp"
#include "membrane/immersed_cells.hpp"

using namespace erythro;
using namespace erythro::aggregation;

namespace {
const MorseParameters kP{0.3, 2.5, 0.8, 9.0};
}

TEST(Morse, ClosedFormValues) {
  // Φ(r0) = −D_e, Φ'(r0) = 0 (the well); Φ(r0 − ln2/β) = 0 (e^{β(r0−r)} = 2);
  // the largest attraction Φ' = βD_e/2 at r0 + ln2/β (e^{β(r0−r)} = ½).
  EXPECT_DOUBLE_EQ(morse_energy(kP, kP.r0), -kP.De);
  EXPECT_DOUBLE_EQ(morse_derivative(kP, kP.r0), 0.0);
  EXPECT_NEAR(morse_energy(kP, kP.r0 - std::log(2.0) / kP.beta), 0.0, 1e-15);
  EXPECT_NEAR(morse_derivative(kP, kP.r0 + std::log(2.0) / kP.beta), 0.5 * kP.beta * kP.De, 1e-15);
  EXPECT_LT(morse_derivative(kP, 1.0), 0.0);  // repulsive inside r0 (dΦ/dr < 0: force pushes apart)
  EXPECT_GT(morse_derivative(kP, 4.0), 0.0);  // attractive beyond
}

TEST(Morse, DerivativeMatchesFiniteDifference) {
  const ShiftedMorse m(kP);
  for (double r : {0.5, 1.7, 2.5, 3.3, 6.0, 8.9}) {
    const double e = 1e-6;
    const double fd = (m.energy(r + e) - m.energy(r - e)) / (2 * e);
    EXPECT_NEAR(m.derivative(r), fd, 1e-9 * std::max(1.0, std::abs(fd))) << r;
    const double fd0 = (morse_energy(kP, r + e) - morse_energy(kP, r - e)) / (2 * e);
    EXPECT_NEAR(morse_derivative(kP, r), fd0, 1e-9 * std::max(1.0, std::abs(fd0))) << r;
  }
}

TEST(Morse, ForceShiftedCutoff) {
  const ShiftedMorse m(kP);
  // Energy and force continuous (zero) at r_c, zero beyond.
  EXPECT_NEAR(m.energy(kP.cutoff - 1e-12), 0.0, 1e-14);
  EXPECT_NEAR(m.derivative(kP.cutoff - 1e-12), 0.0, 1e-14);
  EXPECT_EQ(m.energy(kP.cutoff), 0.0);
  EXPECT_EQ(m.derivative(kP.cutoff + 1.0), 0.0);
  // Φ_s − Φ is the linear function −Φ(r_c) − (r − r_c)Φ'(r_c).
  const double pc = morse_energy(kP, kP.cutoff), dc = morse_derivative(kP, kP.cutoff);
  for (double r : {1.0, 3.0, 7.0}) {
    EXPECT_NEAR(m.energy(r) - morse_energy(kP, r), -pc - (r - kP.cutoff) * dc, 1e-15);
    EXPECT_NEAR(m.derivative(r) - morse_derivative(kP, r), -dc, 1e-15);
  }
}

TEST(Morse, ParameterChecks) {
  EXPECT_THROW(check({-1.0, 2.5, 0.8, 9.0}), std::invalid_argument);
  EXPECT_THROW(check({0.3, 0.0, 0.8, 9.0}), std::invalid_argument);
  EXPECT_THROW(check({0.3, 2.5, 0.0, 9.0}), std::invalid_argument);
  EXPECT_THROW(check({0.3, 2.5, 0.8, 2.5}), std::invalid_argument);  // r_c must exceed r0
  EXPECT_THROW(check({0.3, 2.5, 0.8, NAN}), std::invalid_argument);
  EXPECT_NO_THROW(check(kP));
  EXPECT_THROW(ShiftedMorse({0.3, 2.5, -0.8, 9.0}), std::invalid_argument);
}

TEST(MorseUnits, ConversionToLattice) {
  // Thesis doublet lattice: h = 0.15 µm; Δt and ρ0 arbitrary but fixed.
  const membrane::LatticeScales s{0.15e-6, 2e-8, 1025.0};
  const MorsePhysical p{1.0e3, 0.49e-6, 3.84e6, 1.6e-6};
  const MorseParameters q = to_lattice(p, s);
  EXPECT_NEAR(q.r0, 0.49 / 0.15, 1e-12);
  EXPECT_NEAR(q.beta, 3.84 * 0.15, 1e-12);
  EXPECT_NEAR(q.cutoff, 1.6 / 0.15, 1e-12);
  EXPECT_NEAR(q.De, 1.0e3 * 2e-8 * 2e-8 / (1025.0 * 0.15e-6 * 0.15e-6), 1e-12 * q.De);  // a pressure
}

TEST(MorseUnits, ConversionErrors) {
  const membrane::LatticeScales s{0.15e-6, 2e-8, 1025.0};
  EXPECT_THROW(to_lattice({-1.0, 0.49e-6, 3.84e6, 1.6e-6}, s), std::invalid_argument);
  EXPECT_THROW(to_lattice({1.0, 0.0, 3.84e6, 1.6e-6}, s), std::invalid_argument);
  EXPECT_THROW(to_lattice({1.0, 0.49e-6, -3.84e6, 1.6e-6}, s), std::invalid_argument);
  EXPECT_THROW(to_lattice({1.0, 0.49e-6, 3.84e6, 0.4e-6}, s), std::invalid_argument);  // r_c < r0
  EXPECT_THROW(to_lattice({1.0, 0.49e-6, 3.84e6, 1.6e-6}, {0.0, 2e-8, 1025.0}), std::invalid_argument);
  EXPECT_THROW(to_lattice({1.0, 0.49e-6, 3.84e6, 1.6e-6}, {0.15e-6, 2e-8, -1.0}), std::invalid_argument);
}

TEST(MorseUnits, FlatContactIntegralMatchesBessel) {
  // Without cut-off J(d) = 2d[e^{2βr0}K1(2βd) − 2e^{βr0}K1(βd)]; a cut-off 40/β beyond r0
  // changes it by ~e^{−40} (relative), so the quadrature must match the closed form.
  const MorseParameters p{1.0, 2.5, 0.8, 2.5 + 40.0 / 0.8};
  for (double d : {1.0, 2.0, 3.0, 5.0}) {
    const double b = p.beta;
    const double exact = 2 * d * (std::exp(2 * b * p.r0) * std::cyl_bessel_k(1.0, 2 * b * d) -
                                  2 * std::exp(b * p.r0) * std::cyl_bessel_k(1.0, b * d));
    EXPECT_NEAR(flat_contact_integral(p, d), exact, 1e-10 * std::abs(exact)) << d;
    const double e = 1e-5;
    const double fd = (flat_contact_integral(p, d + e) - flat_contact_integral(p, d - e)) / (2 * e);
    EXPECT_NEAR(flat_contact_integral_derivative(p, d), fd, 1e-7 * std::max(1.0, std::abs(fd))) << d;
  }
}

TEST(MorseUnits, FlatContactGap) {
  // Laplace's method: J ≈ √(2πd/β)[e^{2β(r0−d)}/√2 − 2e^{β(r0−d)}], so J' = 0 at
  // e^{β(r0−d*)} = √2, d* → r0 − ln2/(2β) as β d* → ∞ (relative correction O(1/(βd*)) in the
  // offset ln2/(2β) ≈ 0.087 here: βd* ≈ 80).
  const MorseParameters sharp{1.0, 20.0, 4.0, 30.0};
  const FlatContact fc = flat_contact(sharp);
  EXPECT_NEAR(fc.gap, sharp.r0 - 0.5 * std::log(2.0) / sharp.beta, 0.005);
  EXPECT_LT(fc.integral, 0.0);
  EXPECT_NEAR(flat_contact_integral_derivative(sharp, fc.gap), 0.0, 1e-9);
  // The matching pair density reproduces the surface energy.
  const double De = pair_density_for(0.02, sharp);
  EXPECT_NEAR(De * std::abs(flat_contact_integral(sharp, fc.gap)), 0.02, 1e-14);
  EXPECT_THROW(pair_density_for(-0.1, sharp), std::invalid_argument);
}

// De* = γ / 2.6e-8 J/m² (docs/model.md eq 4.7): the thesis's 1.3e-7 J/m² (ch. IV) is De* = 5,
// Zhang et al.'s 5.2e-8 J/m² is De* = 2.
TEST(MorseUnits, DeStarIsInUnitsOf2point6e8JoulePerSquareMetre) {
  EXPECT_DOUBLE_EQ(surface_energy_for_de_star(5.0), 1.3e-7);
  EXPECT_DOUBLE_EQ(surface_energy_for_de_star(2.0), 5.2e-8);
  EXPECT_DOUBLE_EQ(de_star_for_surface_energy(1.3e-7), 5.0);
  EXPECT_EQ(surface_energy_for_de_star(0.0), 0.0);
  EXPECT_THROW(surface_energy_for_de_star(-1.0), std::invalid_argument);
  EXPECT_THROW(surface_energy_for_de_star(std::nan("")), std::invalid_argument);
  // The largest Morse stress γβ/2 (eq 4.8): De* = 1…5 at β = 3.84 µm⁻¹ is 0.05–0.25 Pa.
  EXPECT_NEAR(peak_adhesion_stress(surface_energy_for_de_star(1.0), 3.84e6), 0.04992, 1e-15);
  EXPECT_NEAR(peak_adhesion_stress(surface_energy_for_de_star(5.0), 3.84e6), 0.2496, 1e-15);
}

// Eq 4.8 against the Morse shape it stands for: w(d) = γ[e^{−2β(d−d*)} − 2e^{−β(d−d*)}] (depth γ at
// d*) has its largest attraction −w' = γβ/2 at d − d* = ln2/β.
TEST(MorseUnits, PeakAdhesionStressIsTheLargestSlopeOfAMorseWell) {
  const double gamma = 2.0, beta = 3.0;
  double largest = 0.0;
  for (int i = 0; i <= 20000; ++i) {
    const double x = 3.0 * i / 20000.0;  // d − d*
    const double pull = 2.0 * gamma * beta * (std::exp(-beta * x) - std::exp(-2.0 * beta * x));  // −w'(d)
    largest = std::max(largest, pull);
  }
  EXPECT_NEAR(peak_adhesion_stress(gamma, beta), largest, 1e-6 * largest);  // sampling: (βΔd/2)² ≈ 5e-8
}

TEST(CellContacts, TwoTrianglesMatchHandSum) {
  // Two 3-marker cells; E = Σ_{m in A, n in B} Φ_s(r) ℓ_m ℓ_n written out here independently.
  const std::vector<double> x{0, 2, 1, 4, 6, 5}, y{0, 0, 1.5, 0.2, 0.1, 1.8};
  const std::vector<std::size_t> off{0, 3, 6};
  const geometry::Domain dom{Grid{40, 40}, false, false};
  const MorseParameters p{0.3, 2.5, 0.8, 6.0};
  auto ell = [&](std::size_t m) {
    const std::size_t o = m < 3 ? 0 : 3, a = o + (m - o + 2) % 3, b = o + (m - o + 1) % 3;
    return 0.5 * (std::hypot(x[m] - x[a], y[m] - y[a]) + std::hypot(x[b] - x[m], y[b] - y[m]));
  };
  const ShiftedMorse m(p);
  double E = 0.0;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 3; j < 6; ++j) E += m.energy(std::hypot(x[i] - x[j], y[i] - y[j])) * ell(i) * ell(j);
  CellContacts agg(dom, p);
  const MarkerView v{x, y, off};
  EXPECT_NEAR(agg.energy(v), E, 1e-14 * std::abs(E));
  std::vector<double> fx(6, 0.0), fy(6, 0.0);
  const auto st = agg.add_forces(v, fx, fy);
  EXPECT_NEAR(st.energy, E, 1e-14 * std::abs(E));
  double sx = 0, sy = 0;
  for (int i = 0; i < 6; ++i) { sx += fx[i]; sy += fy[i]; }
  EXPECT_NEAR(sx, 0.0, 1e-15);
  EXPECT_NEAR(sy, 0.0, 1e-15);
  EXPECT_GT(st.pairs, 0u);
  EXPECT_LE(st.pairs, 9u);
}

TEST(CellContacts, SameCellNeverInteracts) {
  const std::vector<double> x{0, 1, 0.5}, y{0, 0, 1};
  const std::vector<std::size_t> off{0, 3};
  CellContacts agg(geometry::Domain{Grid{32, 32}, true, true}, {0.3, 2.5, 0.8, 6.0});
  std::vector<double> fx(3, 0.0), fy(3, 0.0);
  const auto st = agg.add_forces(MarkerView{x, y, off}, fx, fy);
  EXPECT_EQ(st.pairs, 0u);
  EXPECT_EQ(st.energy, 0.0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(fx[i], 0.0);
}

TEST(CellContacts, RejectsBadInput) {
  // A cut-off of half a periodic side or more would see two images.
  EXPECT_THROW(CellContacts(geometry::Domain{Grid{12, 40}, true, false}, {0.3, 2.5, 0.8, 6.0}), std::invalid_argument);
  EXPECT_NO_THROW(CellContacts(geometry::Domain{Grid{12, 40}, false, false}, {0.3, 2.5, 0.8, 6.0}));
  CellContacts agg(geometry::Domain{Grid{32, 32}, true, true}, {0.3, 2.5, 0.8, 6.0});
  const std::vector<double> x{0, 1, 0.5, 0, 1, 0.5}, y{0, 0, 1, 0, 0, 1};
  std::vector<double> fx(6, 0.0), fy(6, 0.0);
  const std::vector<std::size_t> bad{0, 2, 6};  // a cell of 2 markers
  EXPECT_THROW(agg.add_forces(MarkerView{x, y, bad}, fx, fy), std::invalid_argument);
  const std::vector<std::size_t> off{0, 3, 6};  // coinciding markers of two cells
  EXPECT_THROW(agg.add_forces(MarkerView{x, y, off}, fx, fy), std::domain_error);
}

TEST(CellContacts, RelativeContactArea) {
  const std::vector<double> mag{0.0, 1.0, 0.5, 0.011, 0.0, 0.02};
  const std::vector<std::size_t> off{0, 3, 6};
  EXPECT_DOUBLE_EQ(relative_contact_area(mag, off, 0), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(relative_contact_area(mag, off, 1), 1.0 / 3.0);  // 0.011 < 1.2 % of 1.0 < 0.02
  const std::vector<double> none(6, 0.0);
  EXPECT_EQ(relative_contact_area(none, off, 0), 0.0);
}

TEST(CellContacts, ImmersedCellsWrapperMatchesRawPath) {
  // add_forces(ImmersedCells&) ADDS to the membrane forces and equals the raw-array path.
  fluid::FluidLattice lat(Grid{48, 40}, fluid::CollisionConfig{fluid::CollisionModel::bgk, 1.0, 3.0 / 16.0},
                          fluid::BoundaryConfig{});
  membrane::ImmersedCells cells(ib::KernelType::cosine4, lat);
  const geometry::Polygon c = geometry::circle(40, 8.0);
  const membrane::RestShape rest = membrane::RestShape::from_polygon(geometry::transformed(c, 1.02, 0.0, 0.0, 0.0));
  const membrane::MembraneModel model{{membrane::TensionLawType::neo_hookean, 0.01}, 0.0, 0.0};
  cells.add_cell(geometry::transformed(c, 1.0, 0.0, 14.0, 20.0), rest, model);
  cells.add_cell(geometry::transformed(c, 1.0, 0.2, 33.5, 21.0), rest, model);
  cells.compute_forces();
  const std::vector<double> mfx(cells.marker_fx().begin(), cells.marker_fx().end());
  const MorseParameters p{1e-3, 3.0, 0.6, 11.0};
  CellContacts agg(fluid::domain_of(lat.grid(), lat.boundaries()), p);
  const ContactStats st = agg.add_forces(cells);
  const std::vector<std::size_t> off = cell_offsets(cells);
  ASSERT_EQ(off, (std::vector<std::size_t>{0, 40, 80}));
  std::vector<double> x(cells.marker_x().begin(), cells.marker_x().end()), y(cells.marker_y().begin(), cells.marker_y().end());
  std::vector<double> fx(80, 0.0), fy(80, 0.0);
  agg.add_forces(MarkerView{x, y, off}, fx, fy);
  for (std::size_t m = 0; m < 80; ++m) EXPECT_EQ(cells.marker_fx()[m], mfx[m] + fx[m]) << m;
  EXPECT_GT(st.pairs, 0u);
  EXPECT_EQ(agg.energy(cells), st.energy);
  EXPECT_EQ(agg.force_magnitude().size(), 80u);
  // A model built for another domain is refused.
  CellContacts other(geometry::Domain{Grid{64, 64}, true, true}, p);
  EXPECT_THROW(other.add_forces(cells), std::invalid_argument);
}

TEST(CellContacts, NonFiniteMarkerIsReported) {
  const std::vector<double> x{0, 1, 0.5, 5, 6, NAN}, y{0, 0, 1, 0, 0, 1};
  const std::vector<std::size_t> off{0, 3, 6};
  CellContacts agg(geometry::Domain{Grid{32, 32}, true, true}, {0.3, 2.5, 0.8, 6.0});
  std::vector<double> fx(6, 0.0), fy(6, 0.0);
  EXPECT_THROW(agg.add_forces(MarkerView{x, y, off}, fx, fy), std::domain_error);
}

TEST(CellContacts, FarOutsideWallsStillBinned) {
  // Markers far beyond the walls of a non-periodic box join the edge bins: same result as
  // the brute force.
  const std::vector<double> x{-1e6, -1e6 + 1, -1e6 + 0.5, -1e6 + 3, -1e6 + 4, -1e6 + 3.5},
      y{0, 0, 1, 0.2, 0.1, 1.3};
  const std::vector<std::size_t> off{0, 3, 6};
  const geometry::Domain dom{Grid{40, 40}, false, false};
  const MorseParameters p{0.3, 2.5, 0.8, 6.0};
  CellContacts agg(dom, p);
  std::vector<double> fx(6, 0.0), fy(6, 0.0), bx(6, 0.0), by(6, 0.0);
  const auto a = agg.add_forces(MarkerView{x, y, off}, fx, fy);
  const auto b = add_forces_brute_force(dom, ContactLaw{p, std::nullopt}, MarkerView{x, y, off}, bx, by);
  EXPECT_EQ(a.energy, b.energy);
  EXPECT_GT(a.pairs, 0u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(fx[i], bx[i]);
}

TEST(CellContacts, PairListsFollowMovingMarkersBitForBit) {
  // The pair lists are kept between calls and rebuilt once a marker has moved half the
  // skin: at every call the forces and energy equal the brute force's to the bit, whether
  // the lists were rebuilt or not, on one thread and on several; small moves reuse them,
  // a large move or a whole cell shifted by a period rebuilds them.
  const geometry::Domain dom{Grid{60, 50}, true, false};
  const ContactLaw law{MorseParameters{0.3, 2.5, 0.8, 6.0}, RepulsionParameters{0.2, 1.5, true}};
  std::vector<double> x, y;
  std::vector<std::size_t> off{0};
  const double centres[4][2] = {{12, 14}, {23.5, 15}, {17, 26}, {55, 30}};  // the last across the periodic side
  for (const auto& c : centres) {
    for (int k = 0; k < 40; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 40.0;
      x.push_back(c[0] + 5.2 * std::cos(a));
      y.push_back(c[1] + 4.6 * std::sin(a));
    }
    off.push_back(x.size());
  }
  CellContacts agg(dom, law);
  ASSERT_GT(agg.skin(), 0.0);
  std::size_t builds = 0;
  for (int call = 0; call < 40; ++call) {
    // Jiggle every marker by a deterministic small amount; the first cell slides along y.
    for (std::size_t m = 0; m < x.size(); ++m) {
      x[m] += 0.013 * std::sin(0.7 * double(m) + call);
      y[m] += 0.011 * std::cos(1.3 * double(m) - call) + (m < 40 ? 0.04 : 0.0);
    }
    if (call == 25)
      for (std::size_t m = 120; m < 160; ++m) x[m] -= 60.0;  // cell 3 unwrapped by one period
    const MarkerView v{x, y, off};
    std::vector<double> fx(x.size(), 0.0), fy(x.size(), 0.0), bx(x.size(), 0.0), by(x.size(), 0.0);
    const ContactStats a = agg.add_forces(v, fx, fy);
    const ContactStats b = add_forces_brute_force(dom, law, v, bx, by);
    ASSERT_GT(a.pairs, 0u) << call;
    EXPECT_EQ(a.pairs, b.pairs) << call;
    EXPECT_EQ(a.energy, b.energy) << call;
    EXPECT_EQ(a.min_pair_distance, b.min_pair_distance) << call;
    for (std::size_t m = 0; m < x.size(); ++m) {
      ASSERT_EQ(fx[m], bx[m]) << call << " " << m;
      ASSERT_EQ(fy[m], by[m]) << call << " " << m;
    }
    if (call == 25) {
      EXPECT_EQ(agg.pair_list_builds(), builds + 1) << "a whole cell shifted by a period rebuilds";
    }
    builds = agg.pair_list_builds();
  }
  // 40 calls, the first cell moving 0.04 per call, half the skin 0.25: a handful of builds.
  EXPECT_GE(builds, 3u);
  EXPECT_LE(builds, 12u);
}

TEST(CellContacts, ListedPairsSweptCountsEachListedPairOncePerCall) {
  // The benchmark's work counter (listed_pairs_swept): the pairs of the lists, each once, added
  // at every call. Markers at rest keep the lists of the first call, which hold every pair of
  // different cells within r_c + skin (minimum image along the periodic x), counted here by hand.
  const geometry::Domain dom{Grid{60, 50}, true, false};
  const ContactLaw law{MorseParameters{0.3, 2.5, 0.8, 6.0}, std::nullopt};
  std::vector<double> x, y;
  std::vector<std::size_t> off{0};
  const double centres[3][2] = {{12, 14}, {23.5, 15}, {55, 30}};  // the last near the periodic side
  for (const auto& c : centres) {
    for (int k = 0; k < 30; ++k) {
      const double a = 2.0 * std::numbers::pi * (k + 0.37) / 30.0;
      x.push_back(c[0] + 5.2 * std::cos(a));
      y.push_back(c[1] + 4.6 * std::sin(a));
    }
    off.push_back(x.size());
  }
  CellContacts contacts(dom, law);
  const double reach = contacts.cutoff() + contacts.skin();
  std::size_t by_hand = 0;
  for (std::size_t m = 0; m < x.size(); ++m)
    for (std::size_t n = m + 1; n < x.size(); ++n) {
      if (m / 30 == n / 30) continue;  // the same cell
      double dx = x[m] - x[n];
      dx -= 60.0 * std::round(dx / 60.0);
      const double dy = y[m] - y[n];
      if (dx * dx + dy * dy < reach * reach) ++by_hand;
    }
  ASSERT_GT(by_hand, 0u);
  const MarkerView v{x, y, off};
  std::vector<double> fx(x.size(), 0.0), fy(x.size(), 0.0);
  EXPECT_EQ(contacts.listed_pairs_swept(), 0u);
  for (std::size_t call = 1; call <= 3; ++call) {
    contacts.add_forces(v, fx, fy);
    EXPECT_EQ(contacts.listed_pairs_swept(), call * by_hand) << call;
  }
  EXPECT_EQ(contacts.pair_list_builds(), 1u);
}

TEST(CellContacts, PairListsSameOnAnyThreadCount) {
  // 3 000 markers (above kParallelMarkers): lists built and summed on 1, 2, 3 and 5 threads
  // agree. Each thread sweeps its own slab of cells, each pair inside it evaluated once and
  // the pairs between slabs once from each side (pair_sweep.hpp, sweep_owners.hpp): the
  // slabs change with the thread count, the bits must not.
  const geometry::Domain dom{Grid{200, 200}, true, true};
  const MorseParameters p{0.3, 2.5, 0.8, 6.0};
  const test_support::RingGrid rings(10.0, 19.5);
  const std::vector<double>& x = rings.x;
  ASSERT_GE(x.size(), CellContacts::kParallelMarkers);
  const MarkerView v = rings.view();
  const int threads = omp_get_max_threads();
  auto run = [&](int t, std::vector<double>& f, std::vector<double>& g) {
    f.assign(x.size(), 0.0);
    g.assign(x.size(), 0.0);
    omp_set_num_threads(t);
    CellContacts c(dom, p);
    const ContactStats s = c.add_forces(v, f, g);
    omp_set_num_threads(threads);
    return s;
  };
  std::vector<double> f1, g1, f2, g2;
  const ContactStats a = run(1, f1, g1);
  ASSERT_GT(a.pairs, 1000u);
  for (const int t : {2, 3, 5}) {
    const ContactStats b = run(t, f2, g2);
    EXPECT_EQ(a.energy, b.energy) << t;
    EXPECT_EQ(a.pairs, b.pairs) << t;
    EXPECT_EQ(a.min_pair_distance, b.min_pair_distance) << t;
    for (std::size_t m = 0; m < x.size(); ++m) {
      ASSERT_EQ(f1[m], f2[m]) << m << " on " << t << " threads";
      ASSERT_EQ(g1[m], g2[m]) << m << " on " << t << " threads";
    }
  }
}
