#pragma once
// The polygon of a [[cells]] entry before it is placed: the one rule the set-up
// (cell_checks.cpp) and the seeding of [[cell_populations]] (cell_seeding.cpp) share, so
// a seeded cell is checked with exactly the polygon the set-up then builds.
#include "geometry/polygon.hpp"
#include "scene/scene.hpp"

namespace erythro::scene {

// The cell's shape (circle, ellipse, biconcave) centred at the origin, unrotated and
// unscaled, with `markers` markers; its lengths are the scene's µm divided by `unit_um`
// and then by `shrink` (h for lattice units, 1 for µm; shrink = the prestretch of a rest
// shape). The shape is one of the schema's choices (std::logic_error otherwise).
geometry::Polygon cell_shape_at_origin(const CellSpec& c, int markers, double unit_um, double shrink = 1.0);

// The automatic marker count of a cell without `markers`, before its minimum of 16:
// ⌈perimeter (in h) × scale / kAutoMarkerSpacing⌉ (the perimeter of a 512-marker shape).
double automatic_marker_count(const CellSpec& c, double spacing_um);

}  // namespace erythro::scene
