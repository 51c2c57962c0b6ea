// Geometry of a pair of cells (geometry/pair_geometry.hpp), as the pair probe uses it:
// smallest membrane gap, the pair's equivalent ellipse (area moments), the contact line's
// Legendre shape amplitudes. Exact values of simple shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/pair_geometry.hpp"
#include "geometry/shapes.hpp"

using namespace erythro::geometry;

namespace {
Polygon shifted(const Polygon& p, double dx, double dy) { return transformed(p, 1.0, 0.0, dx, dy); }
}  // namespace

// Two 64-gons of radius 2 with centres 5 apart along x: markers 0 and 32 face each other.
TEST(PairGeometry, MinMarkerGapOfTwoCircles) {
  const Polygon a = circle(64, 2.0), b = shifted(circle(64, 2.0), 5.0, 0.0);
  EXPECT_NEAR(min_marker_gap(a, b), 1.0, 1e-12);
  EXPECT_NEAR(min_marker_gap(b, a), 1.0, 1e-12);
}

// One ellipse a/b = 2 at 30°: axis ratio 2 (the polygon inscribed: within 1e-3) and angle 30°.
// Two equal discs of radius R at ±d: ∫x²dA = 2(πR⁴/4 + πR²d²), ∫y²dA = 2πR⁴/4, so the axis
// ratio is √(1 + 4d²/R²), along x.
TEST(PairGeometry, EquivalentEllipseOfAnEllipseAndOfTwoDiscs) {
  const std::vector<Polygon> one{transformed(ellipse(256, 6.0, 3.0), 1.0, std::numbers::pi / 6, 4.0, -2.0)};
  const EquivalentEllipse e = equivalent_ellipse(one);
  EXPECT_NEAR(e.axis_ratio, 2.0, 1e-3);
  EXPECT_NEAR(e.angle_deg, 30.0, 1e-6);
  EXPECT_NEAR(e.cx, 4.0, 1e-12);
  const double R = 2.0, d = 3.0;
  const std::vector<Polygon> two{shifted(circle(512, R), -d, 1.0), shifted(circle(512, R), d, 1.0)};
  const EquivalentEllipse p = equivalent_ellipse(two);
  EXPECT_NEAR(p.axis_ratio, std::sqrt(1.0 + 4.0 * d * d / (R * R)), 1e-3);
  EXPECT_NEAR(p.angle_deg, 0.0, 1e-9);
  EXPECT_NEAR(p.cy, 1.0, 1e-12);
}

// A contact line n(s) = c2 P2(u) + c3 P3(u) (u = s over the half-length) in the frame of
// the line of centres e = (0, 1): the fit returns |c2| (bow) and |c3| (sigmoid) exactly;
// a straight line gives 0; fewer than 5 contact markers give no fit.
TEST(PairGeometry, ContactShapeAmplitudes) {
  const double c2 = 0.3, c3 = -0.2;
  Polygon line;
  for (int k = 0; k <= 20; ++k) {
    const double u = -1.0 + 0.1 * k;
    line.x.push_back(-4.0 * u);  // s = (X − C)·t with t = (−e_y, e_x) = (−1, 0): s = −x = 4u
    line.y.push_back(1.5 + c2 * 0.5 * (3 * u * u - 1) + c3 * 0.5 * (5 * u * u * u - 3 * u));
  }
  const std::vector<char> all(line.size(), 1);
  const ContactShape s = contact_shape(line, all, 0.0, 0.0, 0.0, 1.0);
  EXPECT_EQ(s.points, 21);
  EXPECT_NEAR(s.length, 8.0, 1e-12);
  EXPECT_NEAR(s.bow, std::abs(c2), 1e-12);
  EXPECT_NEAR(s.sigmoid, std::abs(c3), 1e-12);
  Polygon flat = line;
  for (double& y : flat.y) y = 1.5;
  const ContactShape f = contact_shape(flat, all, 0.0, 0.0, 0.0, 1.0);
  EXPECT_NEAR(f.bow, 0.0, 1e-12);
  EXPECT_NEAR(f.sigmoid, 0.0, 1e-12);
  std::vector<char> few(line.size(), 0);
  for (int k = 0; k < 4; ++k) few[static_cast<std::size_t>(k)] = 1;
  const ContactShape g = contact_shape(line, few, 0.0, 0.0, 0.0, 1.0);
  EXPECT_EQ(g.points, 4);
  EXPECT_EQ(g.sigmoid, 0.0);
  EXPECT_EQ(g.bow, 0.0);
}
