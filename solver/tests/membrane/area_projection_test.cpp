// The area projection (docs/model.md eq 3.14): a polygon gets its target area back exactly (to
// round-off), a polygon at its target is left alone, the move is along the area gradient (its
// size scales with the deficit), either orientation works; in the IB cycle every cell keeps the
// area it was created with, with the same bits for one and two threads.
#include "membrane/area_projection.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/polygon.hpp"
#include "geometry/shapes.hpp"
#include "membrane/immersed_cells.hpp"

using namespace erythro;
using namespace erythro::membrane;
using namespace erythro::geometry;

namespace {
// A wavy ring: r = 5 (1 + 0.15 cos 3φ + 0.05 sin 7φ), n vertices, counter-clockwise.
Polygon wavy(int n) {
  Polygon p;
  for (int i = 0; i < n; ++i) {
    const double phi = 2.0 * M_PI * i / n, r = 5.0 * (1.0 + 0.15 * std::cos(3 * phi) + 0.05 * std::sin(7 * phi));
    p.x.push_back(10.0 + r * std::cos(phi));
    p.y.push_back(-3.0 + r * std::sin(phi));
  }
  return p;
}
}  // namespace

TEST(AreaProjection, RestoresTheTargetAreaToRoundOff) {
  for (double deficit : {-0.05, -1e-4, 1e-6, 0.02}) {
    Polygon p = wavy(80);
    const double before = signed_area(p), target = before * (1.0 + deficit);
    const double applied = project_area(p.x, p.y, target);
    EXPECT_NEAR(signed_area(p), target, 1e-13 * std::abs(target)) << deficit;
    EXPECT_NEAR(applied, target - before, 1e-15 * std::abs(target));
  }
}

TEST(AreaProjection, LeavesAPolygonAtItsTargetAlone) {
  Polygon p = wavy(50);
  const Polygon q = p;
  EXPECT_EQ(project_area(p.x, p.y, signed_area(p)), 0.0);
  EXPECT_EQ(p.x, q.x);
  EXPECT_EQ(p.y, q.y);
}

TEST(AreaProjection, MovesAlongTheAreaGradientInProportionToTheDeficit) {
  // The displacement of each vertex is λ g_i with g_i = ½ J (X_{i+1} − X_{i−1}): parallel to g_i,
  // and for a small deficit λ ≈ −deficit/Σ|g|², so doubling the deficit doubles every move.
  const Polygon p0 = wavy(64);
  const double A = signed_area(p0);
  Polygon p1 = p0, p2 = p0;
  project_area(p1.x, p1.y, A * (1.0 + 1e-6));
  project_area(p2.x, p2.y, A * (1.0 + 2e-6));
  const std::size_t n = p0.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = (i + n - 1) % n, b = (i + 1) % n;
    const double gx = 0.5 * (p0.y[b] - p0.y[a]), gy = 0.5 * (p0.x[a] - p0.x[b]);
    const double dx = p1.x[i] - p0.x[i], dy = p1.y[i] - p0.y[i];
    EXPECT_NEAR(dx * gy - dy * gx, 0.0, 1e-12 * std::hypot(gx, gy));  // parallel
    EXPECT_GT(dx * gx + dy * gy, 0.0);                                   // outwards: the area grows
    EXPECT_NEAR(p2.x[i] - p0.x[i], 2.0 * dx, 1e-6 * std::abs(dx) + 1e-15);
  }
}

TEST(AreaProjection, ClockwisePolygonsToo) {
  Polygon p = wavy(40);
  std::reverse(p.x.begin(), p.x.end());
  std::reverse(p.y.begin(), p.y.end());
  const double target = signed_area(p) * 1.01;  // negative: clockwise
  ASSERT_LT(target, 0.0);
  project_area(p.x, p.y, target);
  EXPECT_NEAR(signed_area(p), target, 1e-13 * std::abs(target));
}

namespace {
// Four cells in a sheared periodic box for `steps` IB cycles with the projection on.
std::vector<double> sheared_cells(int threads, int steps, std::vector<double>* areas, std::vector<double>* restored) {
  omp_set_num_threads(threads);
  fluid::BoundaryConfig walls;
  walls.bottom = {fluid::SideType::moving_wall, -0.02, 0.0};
  walls.top = {fluid::SideType::moving_wall, 0.02, 0.0};
  fluid::FluidLattice lat(Grid{64, 48}, {fluid::CollisionModel::bgk, 0.8, 3.0 / 16}, walls);
  lat.initialize_uniform(1.0, 0.0, 0.0);
  ImmersedCells cells(ib::KernelType::cosine4, lat);
  cells.set_area_projection(true);
  const MembraneModel model{{TensionLawType::neo_hookean, 0.002}, 0.0, 0.0};
  for (double cx : {8.0, 24.0, 40.0, 56.0}) {  // four cells: the projection runs in parallel over cells
    const Polygon shape = transformed(circle(60, 6.0), 1.0, 0.0, cx, 24.0);
    cells.add_cell(shape, RestShape::from_polygon(shape), model);
  }
  for (int s = 0; s < steps; ++s) cells.advance(lat);
  for (int c = 0; c < cells.cell_count(); ++c) {
    areas->push_back(signed_area(cells.polygon(c)));
    restored->push_back(cells.restored_area_fraction(c));
  }
  std::vector<double> out(cells.marker_x().begin(), cells.marker_x().end());
  out.insert(out.end(), cells.marker_y().begin(), cells.marker_y().end());
  return out;
}
}  // namespace

TEST(AreaProjection, EveryCellKeepsItsAreaInTheCycleWithTheSameBitsOnAnyThreadCount) {
  std::vector<double> a1, a2, r1, r2;
  const std::vector<double> one = sheared_cells(1, 300, &a1, &r1), two = sheared_cells(2, 300, &a2, &r2);
  EXPECT_EQ(one, two);
  const double target = signed_area(circle(60, 6.0));
  for (std::size_t c = 0; c < a1.size(); ++c) {
    EXPECT_NEAR(a1[c], target, 1e-12 * target) << c;
    EXPECT_NE(r1[c], 0.0) << c;  // the membrane did leak, and the projection gave it back
    EXPECT_LT(std::abs(r1[c]), 0.05) << c;
  }
}
