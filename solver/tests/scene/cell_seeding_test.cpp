// [[cell_populations]] (scene/cell_seeding.hpp): the same seed places the same cells bit for
// bit, no two polygons (nor a polygon and a wall) come closer than the gap, across periodic
// sides too, the target fraction is met to within one cell, an unreachable target is an
// input error, and the placed cells are ordinary cells of the set-up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geometry/polygon.hpp"
#include "input_error_matchers.hpp"
#include "scene/cell_seeding.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"
#include "scene_fixtures.hpp"

namespace erythro::scene {
namespace {

using testing::channel_scene;
using testing::error_of;

// 40 µm × 40 µm at h = 0.25 µm; walls at bottom and top unless `walls` is false; with the
// [repulsion] that crowded cells need.
std::string box(bool walls) { return channel_scene("40, 40", "0.25", "1.0", "10", walls) + "\n[repulsion]\n"; }

std::string population(const std::string& body) { return "\n[[cell_populations]]\n" + body + "\n"; }
// 2D haematocrit 0.25 (the random addition of these cells with a 2 h gap jams near 0.3 at this
// resolution, so 0.25 is reached for any seed).
const std::string rbcs = population("shape = \"biconcave\"\nradius_um = 3.91\nmarkers = 120\narea_fraction = 0.25");

double point_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double ex = bx - ax, ey = by - ay;
  const double t = std::clamp(((px - ax) * ex + (py - ay) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
  return std::hypot(px - ax - t * ex, py - ay - t * ey);
}

// Every vertex of a to every edge of b (shifted by dx, dy) and back: the distance of two
// polygons that do not cross, and below half the longest edge when they do.
double vertex_edge_distance(const geometry::Polygon& a, const geometry::Polygon& b, double dx, double dy) {
  double d = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < 2; ++pass) {
    const geometry::Polygon& p = pass == 0 ? a : b;
    const geometry::Polygon& q = pass == 0 ? b : a;
    const double sx = pass == 0 ? -dx : dx, sy = pass == 0 ? -dy : dy;  // p's vertices in q's frame
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = 0; j < q.size(); ++j) {
        const std::size_t k = (j + 1) % q.size();
        d = std::min(d, point_segment(p.x[i] + sx, p.y[i] + sy, q.x[j], q.y[j], q.x[k], q.y[k]));
      }
  }
  return d;
}

double longest_edge(const geometry::Polygon& p) {
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t j = (i + 1) % p.size();
    e = std::max(e, std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]));
  }
  return e;
}

// The smallest distance between the polygons of two cells of `s`, over the periodic images.
double closest_pair(const Scene& s) {
  const SeedingDomain d = seeding_domain(s);
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.cells.size(); ++i)
    for (std::size_t j = i + 1; j < s.cells.size(); ++j) {
      const auto a = cell_outline_um(s.cells[i], d.spacing_um), b = cell_outline_um(s.cells[j], d.spacing_um);
      for (int kx = -1; kx <= 1; ++kx)
        for (int ky = -1; ky <= 1; ++ky) {
          if ((kx != 0 && !d.periodic[0]) || (ky != 0 && !d.periodic[1])) continue;
          const double dx = s.cells[j].center_um[0] + kx * d.size_um[0] - s.cells[i].center_um[0];
          const double dy = s.cells[j].center_um[1] + ky * d.size_um[1] - s.cells[i].center_um[1];
          if (std::hypot(dx, dy) > 2.0 * (3.91 + 2.0) + 5.0) continue;  // far beyond any cell here and the gap
          closest = std::min(closest, vertex_edge_distance(a, b, kx * d.size_um[0], ky * d.size_um[1]));
        }
    }
  return closest;
}

TEST(CellSeeding, TheSameSeedPlacesTheSameCellsBitForBit) {
  const Scene a = parse_scene(box(true) + rbcs, "a.toml"), b = parse_scene(box(true) + rbcs, "b.toml");
  ASSERT_EQ(a.cells.size(), b.cells.size());
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    EXPECT_EQ(a.cells[i].center_um, b.cells[i].center_um);
    EXPECT_EQ(a.cells[i].angle_deg, b.cells[i].angle_deg);
  }
  const Scene c = parse_scene(box(true) + rbcs, "c.toml", {"cell_populations[0].seed=2"});
  EXPECT_NE(a.cells[0].center_um, c.cells[0].center_um);
}

TEST(CellSeeding, ReachesTheAreaFractionToWithinOneCell) {
  const Scene s = parse_scene(box(true) + rbcs, "scene.toml");
  ASSERT_EQ(s.population_placements.size(), 1u);
  const PopulationPlacement& placed = s.population_placements[0];
  EXPECT_EQ(placed.first_cell, 0u);
  EXPECT_EQ(placed.count, s.cells.size());
  const double cell_area = std::abs(geometry::signed_area(cell_outline_um(s.cells[0], 0.25)));
  EXPECT_NEAR(placed.area_fraction, 0.25, cell_area / (40.0 * 40.0));
  EXPECT_NEAR(placed.area_fraction, static_cast<double>(placed.count) * cell_area / 1600.0, 1e-12);
}

TEST(CellSeeding, NoTwoCellsComeCloserThanTheGap) {
  const Scene s = parse_scene(box(false) + rbcs, "scene.toml");  // periodic: across the sides too
  const double gap = 2.0 * 0.25;                                 // the default, 2 h
  ASSERT_GT(gap, 0.5 * longest_edge(cell_outline_um(s.cells[0], 0.25)));  // so crossing edges would show
  EXPECT_GE(closest_pair(s), gap);
  const Scene wide = parse_scene(box(false) + rbcs, "scene.toml",
                                 {"cell_populations[0].min_gap_um=1.5", "cell_populations[0].area_fraction=0.15"});
  EXPECT_GE(closest_pair(wide), 1.5);
}

TEST(CellSeeding, PeriodicSidesWrapAndWallsKeepTheirGap) {
  const Scene s = parse_scene(box(true) + rbcs, "scene.toml");  // periodic in x, walls in y
  bool straddles_x = false;
  for (const CellSpec& c : s.cells) {
    const auto p = cell_outline_um(c, 0.25);
    const auto [x0, x1] = std::minmax_element(p.x.begin(), p.x.end());
    const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
    straddles_x = straddles_x || *x0 < 0.0 || *x1 > 40.0;
    EXPECT_GE(*y0, 0.5);
    EXPECT_LE(*y1, 40.0 - 0.5);
    EXPECT_GE(c.center_um[0], 0.0);
    EXPECT_LT(c.center_um[0], 40.0);
  }
  EXPECT_TRUE(straddles_x) << "no cell crosses the periodic side: the wrap is untested";
  EXPECT_GE(closest_pair(s), 0.5);
}

TEST(CellSeeding, PopulationsAvoidTheScenesCellsAndEachOther) {
  const std::string fixed = "\n[[cells]]\nshape = \"circle\"\nradius_um = 5.0\ncenter_um = [20, 20]\nmarkers = 120\n";
  const std::string circles = population("radius_um = 2.0\nmarkers = 48\ncount = 10\nseed = 7");
  const Scene s = parse_scene(box(true) + fixed + rbcs + circles, "scene.toml", {"cell_populations[0].area_fraction=0.15"});
  ASSERT_EQ(s.population_placements.size(), 2u);
  EXPECT_EQ(s.population_placements[0].first_cell, 1u);
  EXPECT_EQ(s.population_placements[1].first_cell, 1u + s.population_placements[0].count);
  EXPECT_EQ(s.population_placements[1].count, 10u);
  EXPECT_EQ(s.cells.size(), 11u + s.population_placements[0].count);
  EXPECT_GE(closest_pair(s), 0.5);
}

TEST(CellSeeding, AnUnreachableTargetNamesTheKeyTheValueAndTheFractionReached) {
  const std::string dense = population("radius_um = 3.0\nmarkers = 64\narea_fraction = 0.8\nattempts_per_cell = 200");
  const std::string message = error_of([&] { parse_scene(box(true) + dense, "dense.toml"); });
  EXPECT_CONTAINS(message, "dense.toml:");
  EXPECT_CONTAINS(message, "cell_populations[0].area_fraction' = 0.8");
  EXPECT_CONTAINS(message, "cannot be reached");
  EXPECT_CONTAINS(message, "(area fraction 0.");
  const std::string close = population("radius_um = 3.0\ncount = 3\nmin_gap_um = 0.2");  // < 1 h
  EXPECT_CONTAINS(error_of([&] { parse_scene(box(true) + close, "close.toml"); }),
                  "cell_populations[0].min_gap_um' = 0.2 is below limits.min_cell_gap");
  const std::string both = population("radius_um = 3.0\narea_fraction = 0.1\ncount = 3");
  EXPECT_CONTAINS(error_of([&] { parse_scene(box(true) + both, "both.toml"); }), "give exactly one of them");
}

TEST(CellSeeding, PopulationsNeedRepulsion) {
  const std::string bare = channel_scene("40, 40", "0.25", "1.0", "10", true);
  const std::string message = error_of([&] { parse_scene(bare + rbcs, "crowd.toml"); });
  EXPECT_CONTAINS(message, "crowd.toml:");
  EXPECT_CONTAINS(message, "add a [repulsion] table");
}

TEST(CellSeeding, SeededCellsAreOrdinaryCellsOfTheSetUp) {
  const Scene s = parse_scene(box(true) + rbcs, "scene.toml");
  const LatticeSetup setup = derive_lattice(s);
  ASSERT_TRUE(setup.membrane);
  ASSERT_EQ(setup.membrane->cells.size(), s.cells.size());
  EXPECT_EQ(setup.membrane->cells[0].shape.size(), 120u);
}

}  // namespace
}  // namespace erythro::scene
