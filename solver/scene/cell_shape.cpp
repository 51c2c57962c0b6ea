#include "scene/cell_shape.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "geometry/shapes.hpp"
#include "scene/units.hpp"

namespace erythro::scene {

namespace {

geometry::Polygon build_shape_at_origin(const CellSpec& c, int markers, double unit_um, double shrink) {
  if (c.shape == "circle") return geometry::circle(markers, c.radius_um / unit_um / shrink);
  if (c.shape == "ellipse")
    return geometry::ellipse(markers, c.semi_axes_um[0] / unit_um / shrink, c.semi_axes_um[1] / unit_um / shrink);
  if (c.shape == "biconcave") return geometry::biconcave(markers, c.radius_um / unit_um / shrink);
  throw std::logic_error("cell shape \"" + c.shape + "\" passed the schema's choices");
}

// What a shape at the origin depends on: the shape, its sizes, the marker count, the unit and
// the shrink.
using ShapeKey = std::tuple<std::string, double, double, double, int, double, double>;

}  // namespace

// The shapes already built, per thread: the cells of a population share one shape, and an
// outline placed at equal arc length costs thousands of curve evaluations (geometry/shapes.cpp),
// built three times per cell by the checks and the seeding (a 300-cell box spent 18 % of a
// 100-step run here). The same arguments give the same polygon, so a copy of the first is the
// polygon a new build would give, bit for bit. Bounded: emptied when it holds 64 shapes.
geometry::Polygon cell_shape_at_origin(const CellSpec& c, int markers, double unit_um, double shrink) {
  thread_local std::map<ShapeKey, geometry::Polygon> built;
  const ShapeKey key{c.shape, c.radius_um, c.semi_axes_um[0], c.semi_axes_um[1], markers, unit_um, shrink};
  if (const auto it = built.find(key); it != built.end()) return it->second;
  geometry::Polygon p = build_shape_at_origin(c, markers, unit_um, shrink);
  if (built.size() >= 64) built.clear();
  built.emplace(key, p);
  return p;
}

double automatic_marker_count(const CellSpec& c, double spacing_um) {
  return std::ceil(geometry::perimeter(cell_shape_at_origin(c, 512, spacing_um)) * c.scale / kAutoMarkerSpacing);
}

}  // namespace erythro::scene
