#include "membrane/cell_health.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "common/portable_hypot.hpp"
#include "geometry/polygon.hpp"

namespace erythro::membrane {

HealthReport check_health(const ImmersedCells& cells, const CellHealthLimits& limits) {
  HealthReport r;
  auto fail = [&](int c, long marker, const std::string& what, double value, double limit) {
    r.healthy = false;
    r.quantity = "cell " + std::to_string(c) + " " + what;
    r.node_x = c;
    r.node_y = marker;
    r.value = value;
    r.limit = limit;
    return r;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int c = 0; c < cells.cell_count(); ++c) {
    const auto x = cells.x(c), y = cells.y(c), fx = cells.fx(c), fy = cells.fy(c);
    for (std::size_t m = 0; m < x.size(); ++m) {
      if (!std::isfinite(x[m]) || !std::isfinite(y[m]))
        return fail(c, static_cast<long>(m), "marker position", std::isfinite(x[m]) ? y[m] : x[m], nan);
      if (!std::isfinite(fx[m]) || !std::isfinite(fy[m]))
        return fail(c, static_cast<long>(m), "marker force", std::isfinite(fx[m]) ? fy[m] : fx[m], nan);
    }
    const RestShape& rest = cells.rest(c);
    const double dA = geometry::signed_area(x, y) / rest.area - 1.0;
    if (!(std::abs(dA) <= limits.max_area_change)) return fail(c, -1, "area change", dA, limits.max_area_change);
    for (std::size_t e = 0; e < x.size(); ++e) {
      const std::size_t f = (e + 1) % x.size();
      const double strain = numeric::hypot_portable(x[f] - x[e], y[f] - y[e]) / rest.length[e] - 1.0;
      if (!(std::abs(strain) <= limits.max_edge_strain))
        return fail(c, static_cast<long>(e), "edge strain", strain, limits.max_edge_strain);
    }
  }
  return r;
}

}  // namespace erythro::membrane
