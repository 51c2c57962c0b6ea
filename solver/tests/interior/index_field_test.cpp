// The index field (interior/index_field.hpp): method names, eq 26 in the band, the
// interior of each method, periodic wrap, overlapping bands, small cells, eq 27.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "geometry/grid_polygon.hpp"
#include "geometry/shapes.hpp"
#include "interior/geometry.hpp"
#include "interior/index_field.hpp"
#include "lattice/d2q9.hpp"

using namespace erythro;
using namespace erythro::interior;
using namespace erythro::geometry;

namespace {
geometry::Polygon disc(double r, double cx, double cy, int markers = 100) {
  return geometry::transformed(geometry::circle(markers, r), 1.0, 0.0, cx, cy);
}
IndexField field(int nx, int ny, Method m, bool px = true, bool py = true) {
  return IndexField(geometry::Domain{Grid{nx, ny}, px, py}, IndexFieldOptions{m, 2.0});
}
}  // namespace

TEST(Method, NamesRoundTripAndUnknownThrows) {
  for (Method m : {Method::indexless, Method::band_only, Method::flood_fill, Method::ray_casting})
    EXPECT_EQ(parse_method(to_string(m)), m);
  EXPECT_EQ(to_string(Method::flood_fill), "flood_fill");
  try {
    parse_method("floodfill");
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const char* n : {"floodfill", "indexless", "band_only", "flood_fill", "ray_casting"})
      EXPECT_NE(what.find(n), std::string::npos) << what;
  }
}

TEST(IndexField, RejectsBadOptions) {
  EXPECT_THROW(IndexField(geometry::Domain{Grid{0, 5}}, {}), std::invalid_argument);
  EXPECT_THROW(IndexField(geometry::Domain{Grid{5, 5}}, IndexFieldOptions{Method::flood_fill, 0.0}), std::invalid_argument);
}

TEST(IndexField, FloodFillDiscValuesFollowEq26) {
  auto f = field(40, 40, Method::flood_fill);
  const auto c = disc(10.0, 20.0, 20.0, 400);
  const std::vector<geometry::Polygon> cells{c};
  const FillReport& r = f.update(cells);
  EXPECT_EQ(r.cells, 1);
  EXPECT_EQ(r.fill_starts, 1);
  EXPECT_EQ(r.fallback_cells, 0);
  EXPECT_GT(r.interior_nodes, 0);
  long band = 0;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) {
      const double d = signed_distance(c, i + 0.5, j + 0.5);
      const double I = f.values()[j * 40 + i];
      if (std::abs(d) < 2.0) {
        ++band;
        EXPECT_NEAR(I, smoothed_heaviside(d), 1e-12) << i << " " << j;
      } else {
        EXPECT_EQ(I, d < 0 ? 0.0 : 1.0) << i << " " << j;
      }
    }
  EXPECT_EQ(r.band_nodes, band);
  // Σ(1 − I) − A → (π/3 − 2/π) w² for a closed curve whose band does not overlap itself
  // (the curvature term of eq 26's first moment: docs/verification-interior.md).
  double s = 0;
  for (double I : f.values()) s += 1 - I;
  EXPECT_NEAR(s - geometry::signed_area(c), 4.0 * (std::numbers::pi / 3 - 2 / std::numbers::pi), 0.02);
}

TEST(IndexField, MethodsDifferAsSpecified) {
  const std::vector<geometry::Polygon> cells{disc(9.0, 16.0, 15.0)};
  auto none = field(32, 32, Method::indexless), band = field(32, 32, Method::band_only),
       fill = field(32, 32, Method::flood_fill), ray = field(32, 32, Method::ray_casting);
  none.update(cells);
  band.update(cells);
  fill.update(cells);
  ray.update(cells);
  long band_lt1 = 0;
  for (std::size_t k = 0; k < 32 * 32; ++k) {
    EXPECT_EQ(none.values()[k], 1.0);
    EXPECT_EQ(fill.values()[k], ray.values()[k]) << k;  // same band, same interior set
    if (band.values()[k] < 1.0) {
      ++band_lt1;
      EXPECT_EQ(band.values()[k], fill.values()[k]);    // band_only: eq 26 in the band …
    } else {
      EXPECT_TRUE(fill.values()[k] == 1.0 || fill.values()[k] == 0.0);  // … and 1 elsewhere
    }
  }
  EXPECT_EQ(band_lt1, band.report().band_nodes);
  EXPECT_EQ(band.report().interior_nodes, 0);
}

TEST(IndexField, PeriodicWrapGivesTheShiftedField) {
  // A cell across the corner equals the same cell in the middle, cyclically shifted.
  const int n = 36;
  auto a = field(n, n, Method::flood_fill), b = field(n, n, Method::flood_fill);
  const std::vector<geometry::Polygon> mid{geometry::transformed(geometry::biconcave(100, 12.0), 1.0, 0.3, 18.0, 18.0)};
  const std::vector<geometry::Polygon> corner{geometry::transformed(geometry::biconcave(100, 12.0), 1.0, 0.3, 0.0, 36.0)};
  a.update(mid);
  b.update(corner);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(a.values()[j * n + i], b.values()[((j + 18) % n) * n + (i + 18) % n], 1e-12) << i << " " << j;
}

TEST(IndexField, UpdateResetsThePreviousField) {
  auto f = field(40, 40, Method::flood_fill);
  f.update(std::vector<geometry::Polygon>{disc(8.0, 12.0, 12.0)});
  const std::vector<geometry::Polygon> moved{disc(8.0, 27.0, 26.0)};
  f.update(moved);
  auto fresh = field(40, 40, Method::flood_fill);
  fresh.update(moved);
  for (std::size_t k = 0; k < 1600; ++k) EXPECT_EQ(f.values()[k], fresh.values()[k]);
  f.update(std::vector<geometry::Polygon>{});
  for (double I : f.values()) EXPECT_EQ(I, 1.0);
}

TEST(IndexField, OverlappingBandsKeepTheMinimum) {
  // Gap 1.5 h between two discs: their bands (±2 h) overlap.
  const auto c1 = disc(8.0, 12.0, 16.0), c2 = disc(8.0, 29.5, 16.0);
  auto f = field(44, 32, Method::flood_fill);
  const std::vector<geometry::Polygon> cells{c1, c2};
  const FillReport& r = f.update(cells);
  EXPECT_GT(r.overlap_nodes, 0);
  EXPECT_EQ(r.fill_starts, 2);
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 44; ++i) {
      const double d1 = signed_distance(c1, i + 0.5, j + 0.5), d2 = signed_distance(c2, i + 0.5, j + 0.5);
      const double expect = (d1 < -2 || d2 < -2) ? 0.0 : std::min(smoothed_heaviside(d1), smoothed_heaviside(d2));
      EXPECT_NEAR(f.values()[j * 44 + i], expect, 1e-12) << i << " " << j;
    }
}

TEST(IndexField, SmallCellFallsBackToRayCasting) {
  // Radius 2.2: every interior node lies within the band (no node with −d > 2) → no start.
  auto f = field(20, 20, Method::flood_fill);
  const FillReport& r = f.update(std::vector<geometry::Polygon>{disc(2.2, 10.0, 10.0, 20)});
  EXPECT_EQ(r.fallback_cells, 1);
  EXPECT_EQ(r.fill_starts + r.completion_starts, 0);
  EXPECT_EQ(r.interior_nodes, 0);
  EXPECT_GT(r.band_nodes, 0);
}

TEST(IndexField, FlatMembraneNeedsTheCompletionPass) {
  // A slab y ∈ [4, 14] across a non-periodic 6-wide domain: in a 4h × 4h window of a
  // marker on a flat edge every node has |d| ≤ 2, so the thesis rule finds no start node;
  // the completion pass starts from a node with 2 ≤ −d < 3 instead.
  geometry::Polygon slab;
  for (int k = -3; k <= 9; ++k) { slab.x.push_back(k); slab.y.push_back(4.0); }
  for (int k = 9; k >= -3; --k) { slab.x.push_back(k); slab.y.push_back(14.0); }
  auto f = field(6, 20, Method::flood_fill, false, false);
  const FillReport& r = f.update(std::vector<geometry::Polygon>{slab});
  EXPECT_EQ(r.fill_starts, 0);
  EXPECT_EQ(r.completion_starts, 1);
  EXPECT_EQ(r.fallback_cells, 0);
  for (int j = 0; j < 20; ++j) {
    const double y = j + 0.5;
    const double d = std::max(4.0 - y, y - 14.0);  // signed distance to the slab
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(f.values()[j * 6 + i], smoothed_heaviside(d), 1e-12) << i << " " << j;
  }
}

TEST(IndexField, WriteRelaxationTimesEq27) {
  auto f = field(30, 30, Method::flood_fill);
  f.update(std::vector<geometry::Polygon>{disc(8.0, 15.0, 15.0)});
  std::vector<double> tau(900);
  const double nu_in = 1.0 / 3.0, nu_ex = 0.2 / 3.0;
  f.write_relaxation_times(tau, nu_in, nu_ex);
  for (std::size_t k = 0; k < 900; ++k) {
    const double I = f.values()[k];
    EXPECT_NEAR(tau[k], d2q9::tau_of_viscosity(nu_in + (nu_ex - nu_in) * I), 1e-15);
    if (I == 0.0) { EXPECT_NEAR(tau[k], 1.5, 1e-15); }
    if (I == 1.0) { EXPECT_NEAR(tau[k], 0.7, 1e-15); }
  }
  std::vector<double> wrong(899);
  EXPECT_THROW(f.write_relaxation_times(wrong, nu_in, nu_ex), std::invalid_argument);
}

TEST(IndexField, ClockwisePolygonGivesTheSameField) {
  auto c = disc(9.0, 15.0, 15.0);
  geometry::Polygon cw{{c.x.rbegin(), c.x.rend()}, {c.y.rbegin(), c.y.rend()}};
  auto a = field(30, 30, Method::flood_fill), b = field(30, 30, Method::flood_fill);
  a.update(std::vector<geometry::Polygon>{c});
  b.update(std::vector<geometry::Polygon>{cw});
  for (std::size_t k = 0; k < 900; ++k) EXPECT_NEAR(a.values()[k], b.values()[k], 1e-12);
}

TEST(IndexField, WedgeAndCapsuleBandPassesAgree) {
  // A smooth biconcave cell takes the wedge path; the same polygon with a repeated marker
  // (a zero-length edge) takes the whole-capsule path. The fields must be identical.
  const auto c = geometry::transformed(geometry::biconcave(100, 20.0), 1.0, 0.4, 24.3, 23.8);
  geometry::Polygon dup = c;
  dup.x.insert(dup.x.begin() + 10, dup.x[10]);
  dup.y.insert(dup.y.begin() + 10, dup.y[10]);
  auto a = field(48, 48, Method::flood_fill), b = field(48, 48, Method::flood_fill);
  EXPECT_EQ(a.update(std::vector<geometry::Polygon>{c}).wedge_cells, 1);
  EXPECT_EQ(b.update(std::vector<geometry::Polygon>{dup}).wedge_cells, 0);
  for (std::size_t k = 0; k < 48 * 48; ++k) EXPECT_EQ(a.values()[k], b.values()[k]) << k;
  // Deterministic: a second update gives the same field bit for bit.
  const std::vector<double> first(a.values().begin(), a.values().end());
  a.update(std::vector<geometry::Polygon>{c});
  for (std::size_t k = 0; k < first.size(); ++k) EXPECT_EQ(a.values()[k], first[k]);
}

// The incremental τ write touches only nodes changed by this or the previous update, and
// gives the same bits as the full write over a sequence of moves (cells move, shrink,
// vanish across updates; both methods that fill).
TEST(IndexField, ChangedRelaxationTimesEqualTheFullWrite) {
  for (Method m : {Method::flood_fill, Method::band_only}) {
    IndexField f = field(60, 50, m);
    const double nu_in = 5.0 / 6.0, nu_ex = 1.0 / 6.0;
    std::vector<double> incremental(60 * 50, 0.0), full(60 * 50, 0.0);
    f.write_relaxation_times(incremental, nu_in, nu_ex);  // the starting field, as CellPhysics does
    const std::vector<std::vector<geometry::Polygon>> frames = {
        {disc(8.0, 20.0, 20.0), disc(6.0, 42.0, 30.0)},
        {disc(8.0, 21.3, 20.7), disc(6.0, 41.2, 29.5)},
        {disc(7.0, 24.0, 22.0)},
        {disc(9.0, 55.0, 25.0)},  // across the periodic side
        {}};
    for (const auto& cells : frames) {
      f.update(cells);
      f.write_changed_relaxation_times(incremental, nu_in, nu_ex);
      f.write_relaxation_times(full, nu_in, nu_ex);
      for (std::size_t k = 0; k < full.size(); ++k) ASSERT_EQ(incremental[k], full[k]) << "node " << k;
    }
  }
}

// The band pass works in a per-cell node box (geometry.hpp, BoxAxis): unwrapped and
// clipped at walls, or folded onto the whole axis when the cell's reach spans a periodic
// side. Both paths must give the brute-force field (nearest periodic image, walls drop
// the nodes beyond them).
TEST(IndexField, FoldedAndWallClippedBoxesMatchBruteForce) {
  const BoxAxis wall = BoxAxis::covering(-5.3, 20.2, 48, false);
  EXPECT_FALSE(wall.folded);
  EXPECT_EQ(wall.origin, 0);
  EXPECT_EQ(wall.index(-1), -1);  // beyond the wall
  const BoxAxis fold = BoxAxis::covering(-5.3, 70.2, 48, true);
  EXPECT_TRUE(fold.folded);
  EXPECT_EQ(fold.size, 48);
  EXPECT_EQ(fold.index(-3), 45);
  EXPECT_EQ(fold.neighbour(47, 1), 0);
  const BoxAxis plain = BoxAxis::covering(-5.3, 20.2, 48, true);
  EXPECT_FALSE(plain.folded);
  EXPECT_EQ(plain.node(0), 43);  // unwrapped −5 is node 43
  struct Case {
    int nx, ny;
    bool px, py;
    double r, cx, cy;
  };
  // A disc whose band reaches around a periodic side (radius 15 on 32 nodes: folded in x
  // and y), the same between walls in y, and a disc near a wall.
  for (const Case& k : {Case{32, 34, true, true, 15.0, 16.2, 17.1}, Case{32, 40, true, false, 14.5, 3.4, 20.3},
                        Case{40, 40, false, true, 9.0, 10.5, 38.0}}) {
    const auto c = disc(k.r, k.cx, k.cy, 160);
    IndexField f = field(k.nx, k.ny, Method::flood_fill, k.px, k.py);
    f.update(std::vector<geometry::Polygon>{c});
    for (int j = 0; j < k.ny; ++j)
      for (int i = 0; i < k.nx; ++i) {
        double best = 1e300;
        for (int sy = -1; sy <= 1; ++sy)
          for (int sx = -1; sx <= 1; ++sx) {
            if ((sx != 0 && !k.px) || (sy != 0 && !k.py)) continue;
            const double d = signed_distance(c, i + 0.5 + sx * k.nx, j + 0.5 + sy * k.ny);
            if (std::abs(d) < std::abs(best)) best = d;
          }
        const double expect = std::abs(best) < 2.0 ? smoothed_heaviside(best) : (best < 0 ? 0.0 : 1.0);
        ASSERT_NEAR(f.values()[static_cast<std::size_t>(j * k.nx + i)], expect, 1e-12)
            << "case " << k.nx << "x" << k.ny << " node " << i << " " << j;
      }
  }
}

TEST(Heaviside, Eq26Values) {
  // H(d) = ½[1 + d/w + (1/π) sin(πd/w)], w = 2.
  EXPECT_DOUBLE_EQ(smoothed_heaviside(-2.0), 0.0);
  EXPECT_DOUBLE_EQ(smoothed_heaviside(-5.0), 0.0);
  EXPECT_DOUBLE_EQ(smoothed_heaviside(2.0), 1.0);
  EXPECT_DOUBLE_EQ(smoothed_heaviside(7.0), 1.0);
  EXPECT_DOUBLE_EQ(smoothed_heaviside(0.0), 0.5);
  EXPECT_NEAR(smoothed_heaviside(1.0), 0.5 * (1.5 + 1.0 / std::numbers::pi), 1e-15);
  EXPECT_NEAR(smoothed_heaviside(-1.0), 0.5 * (0.5 - 1.0 / std::numbers::pi), 1e-15);
  // Odd symmetry about ½, monotone, C¹ at ±w (H' = (1 + cos(πd/w))/(2w) → 0).
  for (double d = -1.99; d < 2.0; d += 0.01) {
    EXPECT_NEAR(smoothed_heaviside(d) + smoothed_heaviside(-d), 1.0, 1e-14);
    EXPECT_LE(smoothed_heaviside(d - 0.01), smoothed_heaviside(d));
  }
  EXPECT_NEAR(smoothed_heaviside(-1.9999), 0.0, 1e-10);
  EXPECT_NEAR(smoothed_heaviside(3.0, 3.0), 1.0, 0.0);
  EXPECT_NEAR(smoothed_heaviside(1.5, 3.0), 0.5 * (1.5 + 1.0 / std::numbers::pi), 1e-15);
}
