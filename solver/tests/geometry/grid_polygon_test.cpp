// Polygons on the grid (geometry/grid_polygon.hpp): signed distance sign and accuracy,
// even–odd ray casting with periodic wrap, clipped area, area in a node's square.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/grid_polygon.hpp"
#include "geometry/polygon.hpp"
#include "geometry/shapes.hpp"

using namespace erythro;
using namespace erythro::geometry;

TEST(SignedDistance, SquareSignAndValue) {
  Polygon sq{{0, 4, 4, 0}, {0, 0, 4, 4}};  // counter-clockwise
  EXPECT_NEAR(signed_distance(sq, 2.0, 2.0), -2.0, 1e-15);
  EXPECT_NEAR(signed_distance(sq, 1.0, 2.0), -1.0, 1e-15);
  EXPECT_NEAR(signed_distance(sq, 5.0, 2.0), 1.0, 1e-15);
  EXPECT_NEAR(signed_distance(sq, 5.0, 5.0), std::sqrt(2.0), 1e-15);  // nearest point: a vertex
  EXPECT_NEAR(signed_distance(sq, -3.0, -4.0), 5.0, 1e-15);
}

TEST(SignedDistance, CircleAccuracy) {
  // A 400-gon of radius 10: d = r − 10 to within the chord sagitta 10(1 − cos(π/400)) ≈ 3e-4.
  const auto c = geometry::circle(400, 10.0);
  for (double r : {0.5, 7.3, 9.5, 10.4, 13.0})
    for (double th = 0.1; th < 6.2; th += 0.7)
      EXPECT_NEAR(signed_distance(c, r * std::cos(th), r * std::sin(th)), r - 10.0, 3.1e-4) << r << " " << th;
}

TEST(RayCast, PeriodicWrapMatchesUnwrappedImage) {
  // A circle centred at (1, 1) on a 20 × 16 periodic grid: its nodes wrap to the far sides.
  const geometry::Domain d{Grid{20, 16}, true, true};
  const auto c = geometry::transformed(geometry::circle(64, 4.0), 1.0, 0.0, 1.0, 1.0);
  const auto mask = ray_cast_inside(c, d);
  long inside = 0;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 20; ++i) {
      // The nearest image of node (i, j) relative to the centre.
      double dx = i + 0.5 - 1.0, dy = j + 0.5 - 1.0;
      if (dx > 10) dx -= 20;
      if (dy > 8) dy -= 16;
      const bool expect = signed_distance(c, 1.0 + dx, 1.0 + dy) < 0;
      EXPECT_EQ(mask[d.grid.index(i, j)] != 0, expect) << i << " " << j;
      inside += mask[d.grid.index(i, j)];
    }
  EXPECT_GT(inside, 40);
  // Without periodic wrap the images beyond x = 0 and y = 0 are dropped.
  const auto walls = ray_cast_inside(c, geometry::Domain{Grid{20, 16}, false, false});
  long kept = 0;
  for (auto v : walls) kept += v;
  EXPECT_LT(kept, inside / 2);
}

TEST(ClippedArea, ClipsOnlyNonPeriodicAxes) {
  Polygon r{{-2, 6, 6, -2}, {1, 1, 3, 3}};  // 8 × 2, crossing x = 0
  EXPECT_NEAR(clipped_area(r, geometry::Domain{Grid{10, 10}, true, false}), 16.0, 1e-12);
  EXPECT_NEAR(clipped_area(r, geometry::Domain{Grid{10, 10}, false, false}), 12.0, 1e-12);
  EXPECT_NEAR(clipped_area(r, geometry::Domain{Grid{4, 10}, false, true}), 8.0, 1e-12);
}

// The node list is the mask's set, ascending and without repeats, also across a periodic side.
TEST(RayCast, NodeListEqualsTheMask) {
  for (double cx : {20.0, 2.0}) {  // inside, and wrapping across x = 0
    const geometry::Domain d{Grid{40, 30}, true, true};
    const Polygon p = geometry::transformed(geometry::biconcave(120, 16.0), 1.0, 0.3, cx, 15.0);
    const std::vector<std::uint8_t> mask = ray_cast_inside(p, d);
    std::vector<std::size_t> nodes, expected;
    ray_cast_inside_nodes(p, d, nodes);
    for (std::size_t k = 0; k < mask.size(); ++k)
      if (mask[k]) expected.push_back(k);
    EXPECT_EQ(nodes, expected) << "centre x = " << cx;
    EXPECT_GT(nodes.size(), 200u);  // area 13.627 (16/3.91)² ≈ 228 h²
  }
}

TEST(AreaInBox, CoverFractionsOfNodeSquares) {
  // Square [0.5, 2.5]² (counter-clockwise): node squares fully in, half in, a quarter in, out.
  Polygon sq;
  sq.x = {0.5, 2.5, 2.5, 0.5};
  sq.y = {0.5, 0.5, 2.5, 2.5};
  EXPECT_DOUBLE_EQ(area_in_box(sq, 1, 2, 1, 2), 1.0);
  EXPECT_DOUBLE_EQ(area_in_box(sq, 0, 1, 1, 2), 0.5);
  EXPECT_DOUBLE_EQ(area_in_box(sq, 2, 3, 2, 3), 0.25);
  EXPECT_DOUBLE_EQ(area_in_box(sq, 3, 4, 0, 1), 0.0);
  // Fractions over the covering node squares sum to the polygon's area; a clockwise
  // polygon gives negative areas.
  const Polygon c = geometry::transformed(geometry::circle(400, 2.3), 1.0, 0.0, 3.1, 2.9);
  double sum = 0.0;
  for (int j = 0; j < 7; ++j)
    for (int i = 0; i < 7; ++i) sum += area_in_box(c, i, i + 1, j, j + 1);
  EXPECT_NEAR(sum, geometry::signed_area(c), 1e-12);
  Polygon cw = sq;
  std::reverse(cw.x.begin(), cw.x.end());
  std::reverse(cw.y.begin(), cw.y.end());
  EXPECT_DOUBLE_EQ(area_in_box(cw, 1, 2, 1, 2), -1.0);
}
