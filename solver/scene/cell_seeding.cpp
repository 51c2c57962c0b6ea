// Random sequential addition of [[cell_populations]] (cell_seeding.hpp).
#include "scene/cell_seeding.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "geometry/grid_polygon.hpp"
#include "scene/cell_shape.hpp"

namespace erythro::scene {
namespace {

using geometry::Polygon;

// A uniform double in [0, 1) from the top 53 bits of one draw: the same on every platform.
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// The marker count of the set-up: the cell's own, or the automatic one, at least 16 (the
// rule of cell_checks.cpp). Seeded cells carry it explicitly, so the set-up builds exactly
// the polygons checked here.
int marker_count(const CellSpec& c, double spacing_um) {
  if (c.markers != 0) return static_cast<int>(c.markers);
  return std::max(16, static_cast<int>(automatic_marker_count(c, spacing_um)));
}

// Largest distance of a vertex from (cx, cy): the polygon's bounding circle.
double bounding_radius(const Polygon& p, double cx, double cy) {
  double r = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) r = std::max(r, std::hypot(p.x[i] - cx, p.y[i] - cy));
  return r;
}

struct Point {
  double x, y;
};

double point_segment_distance(Point p, Point a, Point b) {
  const double ex = b.x - a.x, ey = b.y - a.y;
  const double len2 = ex * ex + ey * ey;
  const double t = len2 > 0.0 ? std::clamp(((p.x - a.x) * ex + (p.y - a.y) * ey) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - (a.x + t * ex), p.y - (a.y + t * ey));
}

double cross(Point o, Point a, Point b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Distance between segments pq and rs: 0 when they cross, else the nearest endpoint–segment distance.
double segment_distance(Point p, Point q, Point r, Point s) {
  const double d1 = cross(p, q, r), d2 = cross(p, q, s), d3 = cross(r, s, p), d4 = cross(r, s, q);
  if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) return 0.0;
  return std::min({point_segment_distance(p, r, s), point_segment_distance(q, r, s), point_segment_distance(r, p, q),
                   point_segment_distance(s, p, q)});
}

struct Box {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  void add(double x, double y) {
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  bool near(const Box& o, double gap) const {
    return x0 - gap <= o.x1 && o.x0 - gap <= x1 && y0 - gap <= o.y1 && o.y0 - gap <= y1;
  }
};

// The edges of p (shifted by dx, dy) that come within `gap` of box `other`: only they can
// be closer than `gap` to the other polygon.
std::vector<std::size_t> edges_near(const Polygon& p, double dx, double dy, const Box& other, double gap) {
  std::vector<std::size_t> out;
  for (std::size_t e = 0; e < p.size(); ++e) {
    const std::size_t f = (e + 1) % p.size();
    Box edge;
    edge.add(p.x[e] + dx, p.y[e] + dy);
    edge.add(p.x[f] + dx, p.y[f] + dy);
    if (edge.near(other, gap)) out.push_back(e);
  }
  return out;
}

Box box_of(const Polygon& p, double dx, double dy) {
  Box b;
  for (std::size_t i = 0; i < p.size(); ++i) b.add(p.x[i] + dx, p.y[i] + dy);
  return b;
}

// A cell already in the domain: its polygon and bounding circle.
struct Obstacle {
  Polygon outline;
  double cx = 0.0, cy = 0.0, radius = 0.0;
};

class Placer {
 public:
  Placer(const SeedingDomain& d, double gap) : domain_(d), gap_(gap) {
    for (int a = 0; a < 2; ++a)  // a cell's images: itself and, across a periodic side, its neighbours
      shifts_[a] = domain_.periodic[a] ? std::vector<double>{0.0, -d.size_um[a], d.size_um[a]} : std::vector<double>{0.0};
  }

  void add(Polygon outline, double cx, double cy) {
    const double r = bounding_radius(outline, cx, cy);
    obstacles_.push_back({std::move(outline), cx, cy, r});
  }

  // Is the candidate (centre cx, cy; bounding radius r) at least the gap from every wall and cell?
  bool fits(const Polygon& c, double cx, double cy, double r) const {
    for (int a = 0; a < 2; ++a) {
      if (domain_.periodic[a]) continue;
      const auto& coords = a == 0 ? c.x : c.y;
      const auto [lo, hi] = std::minmax_element(coords.begin(), coords.end());
      if (*lo < gap_ || *hi > domain_.size_um[a] - gap_) return false;
    }
    for (const Obstacle& o : obstacles_)
      for (double sx : shifts_[0])
        for (double sy : shifts_[1]) {
          if (std::hypot(cx - (o.cx + sx), cy - (o.cy + sy)) > r + o.radius + gap_) continue;
          if (polygons_closer_than(c, o.outline, sx, sy, gap_)) return false;
        }
    return true;
  }

 private:
  SeedingDomain domain_;
  double gap_;
  std::array<std::vector<double>, 2> shifts_;  // x, y offsets of the images of a cell
  std::vector<Obstacle> obstacles_;
};

}  // namespace

SeedingDomain seeding_domain(const Scene& s) {
  return {s.domain.size_um,
          {s.boundaries.left.type == "periodic", s.boundaries.bottom.type == "periodic"},
          s.domain.spacing_um,
          std::max(2.0, s.limits.min_cell_gap) * s.domain.spacing_um};
}

Polygon cell_outline_um(const CellSpec& c, double spacing_um) {
  Polygon p = geometry::transformed(cell_shape_at_origin(c, marker_count(c, spacing_um), 1.0), c.scale,
                                    c.angle_deg * std::numbers::pi / 180.0, c.center_um[0], c.center_um[1]);
  geometry::make_counter_clockwise(p);
  return p;
}

bool polygons_closer_than(const Polygon& a, const Polygon& b, double dx, double dy, double gap) {
  // One polygon inside the other (even–odd rule: a negative signed distance).
  if (geometry::signed_distance(b, a.x[0] - dx, a.y[0] - dy) < 0.0 ||
      geometry::signed_distance(a, b.x[0] + dx, b.y[0] + dy) < 0.0)
    return true;
  const Box box_a = box_of(a, 0.0, 0.0), box_b = box_of(b, dx, dy);
  if (!box_a.near(box_b, gap)) return false;
  const std::vector<std::size_t> ea = edges_near(a, 0.0, 0.0, box_b, gap), eb = edges_near(b, dx, dy, box_a, gap);
  for (std::size_t i : ea) {
    const std::size_t i1 = (i + 1) % a.size();
    for (std::size_t j : eb) {
      const std::size_t j1 = (j + 1) % b.size();
      const double d = segment_distance({a.x[i], a.y[i]}, {a.x[i1], a.y[i1]}, {b.x[j] + dx, b.y[j] + dy},
                                        {b.x[j1] + dx, b.y[j1] + dy});
      if (d < gap) return true;
    }
  }
  return false;
}

SeedingResult seed_population(const CellPopulationSpec& pop, const SeedingDomain& domain,
                              const std::vector<CellSpec>& existing) {
  SeedingResult result;
  result.gap_um = pop.min_gap_um.value_or(domain.default_gap_um);
  Placer placer(domain, result.gap_um);
  for (const CellSpec& c : existing) placer.add(cell_outline_um(c, domain.spacing_um), c.center_um[0], c.center_um[1]);

  CellSpec prototype;
  prototype.shape = pop.shape;
  prototype.radius_um = pop.radius_um;
  prototype.semi_axes_um = pop.semi_axes_um;
  prototype.shear_modulus_dyn_cm = pop.shear_modulus_dyn_cm;
  prototype.markers = pop.markers;
  prototype.markers = marker_count(prototype, domain.spacing_um);
  const Polygon at_origin = cell_outline_um(prototype, domain.spacing_um);
  const double radius = bounding_radius(at_origin, 0.0, 0.0);
  const double domain_area = domain.size_um[0] * domain.size_um[1];
  result.cell_area_um2 = std::abs(geometry::signed_area(at_origin));
  result.target = pop.count ? *pop.count
                            : std::max(1L, std::lround(*pop.area_fraction * domain_area / result.cell_area_um2));

  std::mt19937_64 rng(static_cast<std::uint64_t>(pop.seed));
  for (long n = 0; n < result.target; ++n) {
    bool placed = false;
    for (long attempt = 0; attempt < pop.attempts_per_cell && !placed; ++attempt) {
      CellSpec c = prototype;
      c.center_um = {uniform01(rng) * domain.size_um[0], uniform01(rng) * domain.size_um[1]};
      c.angle_deg = uniform01(rng) * 360.0;
      // The shape at the origin moved into place (as cell_outline_um, without rebuilding
      // the equal-arc shape at every draw).
      const Polygon outline = geometry::transformed(at_origin, 1.0, c.angle_deg * std::numbers::pi / 180.0,
                                                    c.center_um[0], c.center_um[1]);
      if (!placer.fits(outline, c.center_um[0], c.center_um[1], radius)) continue;
      placer.add(outline, c.center_um[0], c.center_um[1]);
      result.cells.push_back(c);
      placed = true;
    }
    if (!placed) break;
  }
  result.area_fraction = static_cast<double>(result.cells.size()) * result.cell_area_um2 / domain_area;
  return result;
}

}  // namespace erythro::scene
