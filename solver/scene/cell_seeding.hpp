#pragma once
// [[cell_populations]] → ordinary cells: random sequential addition. Each cell of a
// population gets a centre drawn uniformly over the domain and an orientation drawn
// uniformly in [0°, 360°); a candidate whose marker polygon comes closer than the gap to
// the polygon of a cell already there (the scene's [[cells]], earlier populations, this
// one's cells; across periodic sides by the nearest images) or to a wall is drawn again,
// up to `attempts_per_cell` times. Draws come from std::mt19937_64 seeded by the
// population's `seed`, turned into doubles by bit arithmetic (not by a standard
// distribution, whose algorithm the library chooses): the same seed places the same
// cells, bit for bit, with any compiler. The parser calls this (scene_parser.cpp) and
// refuses a target the attempts cannot reach.
#include <array>
#include <vector>

#include "geometry/polygon.hpp"
#include "scene/scene.hpp"

namespace erythro::scene {

struct SeedingDomain {
  std::array<double, 2> size_um{0.0, 0.0};
  std::array<bool, 2> periodic{true, true};  // x, y; a side that is not periodic is a wall
  double spacing_um = 0.0;                    // h: the automatic marker count
  double default_gap_um = 0.0;                // the gap where a population gives no min_gap_um
};

// The domain of a parsed scene (its [domain], [boundaries] and limits.min_cell_gap); the
// default gap is 2 h, or limits.min_cell_gap h if larger (the set-up rejects closer cells).
SeedingDomain seeding_domain(const Scene& scene);

struct SeedingResult {
  std::vector<CellSpec> cells;  // placed, with explicit markers, centre and angle
  long target = 0;              // cells asked for (count, or the area fraction's whole number)
  double cell_area_um2 = 0.0;   // of one cell's marker polygon
  double area_fraction = 0.0;   // reached: cells.size() · cell_area / domain area
  double gap_um = 0.0;          // the gap used (min_gap_um, or the domain's default)
  bool reached() const { return static_cast<long>(cells.size()) == target; }
};

// Places the population among the `existing` cells. Never throws for an unreachable
// target: the result then holds fewer than `target` cells, and the caller reports it.
SeedingResult seed_population(const CellPopulationSpec& population, const SeedingDomain& domain,
                              const std::vector<CellSpec>& existing);

// The marker polygon of a cell in µm, as the set-up builds it (scene/cell_checks.cpp):
// the shape with `markers` markers (0: the automatic count), scaled, rotated, placed.
geometry::Polygon cell_outline_um(const CellSpec& cell, double spacing_um);

// True when polygons a and b (b shifted by (dx, dy)) come closer than `gap`: an edge of
// one within `gap` of an edge of the other (crossing edges: distance 0), or one inside the other.
bool polygons_closer_than(const geometry::Polygon& a, const geometry::Polygon& b, double dx, double dy, double gap);

}  // namespace erythro::scene
