// The keys of [[cell_populations]] (scene.hpp CellPopulationSpec; placement:
// cell_seeding.hpp), declared like every other key (scene_keys.cpp), in a block of their own.
#include "scene/scene_schema.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"  // designated initializers, as in scene_keys.cpp

namespace erythro::scene::detail {

void add_cell_population_keys(std::vector<KeySpec>& k) {
  const Bound positive{0.0, true};
  k.push_back({.path = "cell_populations.shape",
               .kind = Kind::string,
               .choices = {"circle", "ellipse", "biconcave"},
               .when_absent = quoted("circle"),
               .meaning = "The shape of every cell of the population, as `cells.shape`"});
  k.push_back({.path = "cell_populations.radius_um",
               .unit = "µm",
               .bound = positive,
               .when_absent = note("required for `circle` and `biconcave`"),
               .rule = "not with `ellipse`",
               .meaning = "As `cells.radius_um` (3.91 µm for a human RBC)"});
  k.push_back({.path = "cell_populations.semi_axes_um",
               .kind = Kind::vec2,
               .unit = "µm",
               .bound = positive,
               .when_absent = note("required for `ellipse`"),
               .rule = "only with `ellipse`",
               .meaning = "As `cells.semi_axes_um`"});
  k.push_back({.path = "cell_populations.markers",
               .kind = Kind::integer,
               .unit = "markers",
               .bound = Bound{8.0, false, 1e6, false},
               .when_absent = note("⌈perimeter / 0.7 h⌉, at least 16"),
               .meaning = "Markers of every cell, as `cells.markers`"});
  k.push_back({.path = "cell_populations.shear_modulus_dyn_cm",
               .unit = "dyn/cm",
               .bound = Bound{0.0, false},
               .when_absent = note("`membrane.shear_modulus_dyn_cm`"),
               .meaning = "E_s of the population's cells (the other moduli are `[membrane]`'s)"});
  k.push_back({.path = "cell_populations.area_fraction",
               .bound = Bound{0.0, true, 1.0, true},
               .when_absent = note("exactly one of `area_fraction` and `count`"),
               .rule = "reachable within `attempts_per_cell` draws per cell",
               .meaning = "Target fraction of the domain's area covered by the population's cells (2D haematocrit); "
                          "the count is the nearest whole number of cells"});
  k.push_back({.path = "cell_populations.count",
               .kind = Kind::integer,
               .unit = "cells",
               .bound = Bound{1.0, false, 1e6, false},
               .when_absent = note("exactly one of `area_fraction` and `count`"),
               .rule = "reachable within `attempts_per_cell` draws per cell",
               .meaning = "Number of cells to place"});
  k.push_back({.path = "cell_populations.min_gap_um",
               .unit = "µm",
               .bound = positive,
               .when_absent = note("2 h, or `limits.min_cell_gap` h if larger"),
               .rule = "≥ `limits.min_cell_gap` h",
               .meaning = "Smallest distance between the marker polygons of two cells (any cell of the scene, across "
                          "periodic sides) and between a polygon and a wall"});
  k.push_back({.path = "cell_populations.seed",
               .kind = Kind::integer,
               .bound = Bound{0.0, false},
               .when_absent = literal("1"),
               .meaning = "Seed of the random positions and orientations (std::mt19937_64): the same seed places "
                          "the same cells, bit for bit"});
  k.push_back({.path = "cell_populations.attempts_per_cell",
               .kind = Kind::integer,
               .bound = Bound{1.0, false, 1e7, false},
               .when_absent = literal("1000"),
               .meaning = "Random draws allowed for one cell; when they all fail, the target is unreachable "
                          "(an input error giving the fraction reached)"});
}

}  // namespace erythro::scene::detail

#pragma GCC diagnostic pop
