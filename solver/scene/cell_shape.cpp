#include "scene/cell_shape.hpp"

#include <cmath>
#include <stdexcept>

#include "geometry/shapes.hpp"
#include "scene/units.hpp"

namespace erythro::scene {

geometry::Polygon cell_shape_at_origin(const CellSpec& c, int markers, double unit_um, double shrink) {
  if (c.shape == "circle") return geometry::circle(markers, c.radius_um / unit_um / shrink);
  if (c.shape == "ellipse")
    return geometry::ellipse(markers, c.semi_axes_um[0] / unit_um / shrink, c.semi_axes_um[1] / unit_um / shrink);
  if (c.shape == "biconcave") return geometry::biconcave(markers, c.radius_um / unit_um / shrink);
  throw std::logic_error("cell shape \"" + c.shape + "\" passed the schema's choices");
}

double automatic_marker_count(const CellSpec& c, double spacing_um) {
  return std::ceil(geometry::perimeter(cell_shape_at_origin(c, 512, spacing_um)) * c.scale / kAutoMarkerSpacing);
}

}  // namespace erythro::scene
