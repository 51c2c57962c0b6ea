#include "doublet_run.hpp"

#include <cmath>
#include <numbers>
#include <cstdio>
#include <stdexcept>

#include "aggregation/morse_aggregation.hpp"
#include "common/case_support.hpp"
#include "fluid/fluid_lattice.hpp"
#include "geometry/polygon.hpp"
#include "geometry/shapes.hpp"
#include "membrane/immersed_cells.hpp"
#include "membrane/rest_shape.hpp"

namespace erythro::vv {

namespace {

double image(double d, double L) { return d - L * std::round(d / L); }

struct Shape {
  double cx = 0, cy = 0, R = 0, dev = 0;
};

Shape measure(std::span<const double> x, std::span<const double> y) {
  Shape s;
  const double n = double(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    s.cx += x[i] / n;
    s.cy += y[i] / n;
  }
  for (std::size_t i = 0; i < x.size(); ++i) s.R += std::hypot(x[i] - s.cx, y[i] - s.cy) / n;
  for (std::size_t i = 0; i < x.size(); ++i) s.dev = std::max(s.dev, std::abs(std::hypot(x[i] - s.cx, y[i] - s.cy) - s.R));
  return s;
}

// Net Morse force on rigid polygon b, shifted by s along the unit vector e (from a's
// centre to b's), projected on e: > 0 pushes b away from a (repulsion).
double force_along(aggregation::MorseAggregation& agg, const geometry::Polygon& a, const geometry::Polygon& b,
                   double ex, double ey, double s) {
  std::vector<double> x(a.x), y(a.y);
  for (std::size_t i = 0; i < b.size(); ++i) {
    x.push_back(b.x[i] + s * ex);
    y.push_back(b.y[i] + s * ey);
  }
  const std::vector<std::size_t> off{0, a.size(), a.size() + b.size()};
  std::vector<double> fx(x.size(), 0.0), fy(x.size(), 0.0);
  agg.add_forces(aggregation::MarkerView{x, y, off}, fx, fy);
  double f = 0.0;
  for (std::size_t i = a.size(); i < x.size(); ++i) f += fx[i] * ex + fy[i] * ey;
  return f;
}

// The shift s ∈ (lo, hi) of b along e where that force changes sign from + to −
// (first sign change on a 0.05 grid, then bisection).
double balance_root(aggregation::MorseAggregation& agg, const geometry::Polygon& a, const geometry::Polygon& b,
                    double ex, double ey, double lo, double hi) {
  double l = lo, h = lo;
  bool found = false;
  for (double s = lo + 0.05; s < hi; s += 0.05) {
    if (force_along(agg, a, b, ex, ey, s) < 0.0) {
      h = s;
      found = true;
      break;
    }
    l = s;
  }
  if (!found) return NAN;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (l + h);
    (force_along(agg, a, b, ex, ey, mid) > 0.0 ? l : h) = mid;
  }
  return 0.5 * (l + h);
}

// Gap where the discrete Morse force between the rigid INITIAL polygons vanishes.
double discrete_rigid_gap(const geometry::Domain& dom, const aggregation::MorseParameters& p, const geometry::Polygon& a,
                          const geometry::Polygon& b, double R) {
  aggregation::MorseAggregation agg(dom, p);
  const double gap0 = measure(b.x, b.y).cx - measure(a.x, a.y).cx - 2.0 * R;
  return gap0 + balance_root(agg, a, b, 1.0, 0.0, 0.1 * p.r0 - gap0, p.cutoff - gap0);
}

}  // namespace

DoubletResult run_doublet(const DoubletSetup& s, bool verbose) {
  Stopwatch sw;
  DoubletResult r;
  fluid::FluidLattice lat(Grid{s.nx, s.ny}, fluid::CollisionConfig{fluid::CollisionModel::bgk, s.tau, 3.0 / 16.0},
                          fluid::BoundaryConfig{});
  membrane::ImmersedCells cells(s.kernel, lat);
  const geometry::Polygon circle = geometry::circle(s.markers, s.radius);
  const membrane::RestShape rest = membrane::RestShape::from_polygon(circle);
  const double xm = 0.5 * s.nx, D0 = 2.0 * s.radius + s.initial_gap;
  const geometry::Polygon p0 = geometry::transformed(circle, 1.0, s.angle0, xm - 0.5 * D0, s.y0);
  const geometry::Polygon p1 = geometry::transformed(circle, 1.0, s.angle1, xm + 0.5 * D0, s.y0);
  cells.add_cell(p0, rest, s.model);
  cells.add_cell(p1, rest, s.model);
  const geometry::Domain dom = cells.transfer().domain();
  aggregation::MorseAggregation agg(dom, s.morse);
  r.discrete_rigid_gap = discrete_rigid_gap(dom, s.morse, p0, p1, measure(p0.x, p0.y).R);

  auto gap_now = [&](Shape& a, Shape& b) {
    a = measure(cells.x(0), cells.y(0));
    b = measure(cells.x(1), cells.y(1));
    return std::hypot(image(b.cx - a.cx, s.nx), image(b.cy - a.cy, s.ny)) - a.R - b.R;
  };
  Shape a, b;
  gap_now(a, b);
  double comx = 0.5 * (a.cx + b.cx), comy = 0.5 * (a.cy + b.cy), dcx = 0.0, dcy = 0.0;
  auto angle0 = [&](int c, const Shape& sh) { return std::atan2(cells.y(c)[0] - sh.cy, cells.x(c)[0] - sh.cx); };
  double th0 = angle0(0, a), th1 = angle0(1, b), rot0 = 0.0, rot1 = 0.0;
  for (long k = 0; k < s.steps; ++k) {
    cells.compute_forces();
    agg.add_forces(cells);
    cells.advance_after_forces(lat);
    r.steps_done = k + 1;
    r.max_marker_speed = std::max(r.max_marker_speed, cells.max_marker_speed());
    if ((k + 1) % s.sample_every == 0 || k + 1 == s.steps) {
      const double g = gap_now(a, b);
      if (!std::isfinite(g)) {
        r.diverged = true;
        break;
      }
      // Unwrapped displacement of the pair's centre (cells may be shifted by ±n).
      const double cx = 0.5 * (a.cx + b.cx), cy = 0.5 * (a.cy + b.cy);
      dcx += image(cx - comx, 0.5 * s.nx);
      dcy += image(cy - comy, 0.5 * s.ny);
      comx = cx;
      comy = cy;
      const double t0 = angle0(0, a), t1 = angle0(1, b);
      rot0 += std::remainder(t0 - th0, 2.0 * std::numbers::pi);
      rot1 += std::remainder(t1 - th1, 2.0 * std::numbers::pi);
      th0 = t0;
      th1 = t1;
      r.step.push_back(double(k + 1));
      r.gap.push_back(g);
      if (verbose && (k + 1) % (20 * s.sample_every) == 0) {
        std::printf("step %ld gap %.6f com (%.3e, %.3e) dev %.4f rot arcs %.4f %.4f\n", k + 1, g, dcx, dcy,
                    std::max(a.dev, b.dev), rot0 * a.R, rot1 * b.R);
      }
    }
  }
  r.final_gap = r.gap.empty() ? NAN : r.gap.back();
  const std::size_t n = r.gap.size();
  if (n >= 10) r.gap_change_last_10pc = std::abs(r.gap.back() - r.gap[n - 1 - n / 10]);
  r.com_drift = std::hypot(dcx, dcy);
  r.max_deformation = std::max(a.dev, b.dev);
  r.rotation_arc0 = rot0 * a.R;
  r.rotation_arc1 = rot1 * b.R;
  {
    // Force balance of the final state: the shift of cell 1 (frozen shape) along the
    // line of centres at which the net Morse force between the two membranes vanishes.
    geometry::Polygon fa = cells.polygon(0), fb = cells.polygon(1);
    double ex = image(b.cx - a.cx, s.nx), ey = image(b.cy - a.cy, s.ny);
    const double D = std::hypot(ex, ey);
    ex /= D;
    ey /= D;
    // Bring cell 1 next to cell 0 (undo a periodic shift) so plain differences apply.
    const double bx = a.cx + ex * D - b.cx, by = a.cy + ey * D - b.cy;
    for (std::size_t i = 0; i < fb.size(); ++i) {
      fb.x[i] += bx;
      fb.y[i] += by;
    }
    r.balance_shift = balance_root(agg, fa, fb, ex, ey, -1.0, 1.0);
  }
  const std::vector<std::size_t> off = aggregation::cell_offsets(cells);
  cells.compute_forces();
  agg.add_forces(cells);
  r.contact_area0 = aggregation::relative_contact_area(agg.force_magnitude(), off, 0);
  r.contact_area1 = aggregation::relative_contact_area(agg.force_magnitude(), off, 1);
  r.wall_time_s = sw.seconds();
  return r;
}

}  // namespace erythro::vv
