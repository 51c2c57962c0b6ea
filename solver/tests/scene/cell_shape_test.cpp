// scene::cell_shape_at_origin keeps the outlines it has built (cell_shape.cpp): a kept outline
// must be served only for its own arguments. Every call below, in an order where a key that left
// out one argument would serve an earlier shape, gives the polygon geometry/shapes.hpp builds
// for that call's own arguments, bit for bit, and so does a call made again after more shapes
// than are kept.
#include "scene/cell_shape.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "geometry/shapes.hpp"

using namespace erythro;

namespace {

scene::CellSpec spec(const std::string& shape, double radius_um, double a_um = 0.0, double b_um = 0.0) {
  scene::CellSpec c;
  c.shape = shape;
  c.radius_um = radius_um;
  c.semi_axes_um = {a_um, b_um};
  return c;
}

struct Call {
  scene::CellSpec c;
  int markers;
  double unit_um, shrink;
};

// The polygon a fresh build gives for the call's own arguments (cell_shape.hpp's rule).
geometry::Polygon built(const Call& k) {
  if (k.c.shape == "circle") return geometry::circle(k.markers, k.c.radius_um / k.unit_um / k.shrink);
  if (k.c.shape == "ellipse")
    return geometry::ellipse(k.markers, k.c.semi_axes_um[0] / k.unit_um / k.shrink,
                             k.c.semi_axes_um[1] / k.unit_um / k.shrink);
  return geometry::biconcave(k.markers, k.c.radius_um / k.unit_um / k.shrink);
}

bool same_bits(const geometry::Polygon& a, const geometry::Polygon& b) {
  const std::size_t bytes = a.size() * sizeof(double);
  return a.size() == b.size() && b.y.size() == a.y.size() && std::memcmp(a.x.data(), b.x.data(), bytes) == 0 &&
         std::memcmp(a.y.data(), b.y.data(), bytes) == 0;
}

}  // namespace

TEST(CellShape, KeptOutlinesServeOnlyTheirOwnArguments) {
  const std::vector<Call> calls = {
      {spec("biconcave", 3.91), 184, 0.15, 1.0},  // the first
      {spec("biconcave", 3.91), 96, 0.15, 1.0},   // another marker count
      {spec("biconcave", 3.91), 184, 0.25, 1.0},  // another unit
      {spec("biconcave", 3.91), 184, 0.15, 1.1},  // another shrink
      {spec("biconcave", 3.5), 184, 0.15, 1.0},   // another radius
      {spec("circle", 3.91), 184, 0.15, 1.0},     // another shape, the same sizes
      {spec("ellipse", 0.0, 4.0, 2.0), 184, 0.15, 1.0},
      {spec("ellipse", 0.0, 2.0, 4.0), 184, 0.15, 1.0},  // the semi-axes swapped
      {spec("ellipse", 0.0, 4.0, 2.5), 184, 0.15, 1.0},  // the second semi-axis alone changed
  };
  for (int round = 0; round < 2; ++round) {  // built, then served from what is kept
    for (std::size_t i = 0; i < calls.size(); ++i) {
      const Call& k = calls[i];
      EXPECT_TRUE(same_bits(scene::cell_shape_at_origin(k.c, k.markers, k.unit_um, k.shrink), built(k)))
          << "call " << i << ", round " << round;
    }
  }
  // More distinct shapes than are kept (64), then the first again.
  for (int n = 0; n < 70; ++n) scene::cell_shape_at_origin(spec("circle", 1.0 + n), 16, 1.0);
  const Call& first = calls.front();
  EXPECT_TRUE(
      same_bits(scene::cell_shape_at_origin(first.c, first.markers, first.unit_um, first.shrink), built(first)));
}
