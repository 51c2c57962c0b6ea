#include "transport/subpixel_diffusivity.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/grid_polygon.hpp"

namespace erythro::transport {
namespace {

// Length of the part of segment (x0, y0) → (x1, y1) inside the box [bx0, bx1] × [by0, by1]
// (Liang–Barsky: the parameter interval t ∈ [t0, t1] of the segment inside every slab).
double clipped_length(double x0, double y0, double x1, double y1, double bx0, double bx1, double by0, double by1) {
  const double dx = x1 - x0, dy = y1 - y0;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0 - bx0, bx1 - x0, y0 - by0, by1 - y0};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return 0.0;  // parallel and outside
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
  }
  return t1 > t0 ? (t1 - t0) * std::hypot(dx, dy) : 0.0;
}

}  // namespace

std::vector<AreaFraction> area_fractions(const geometry::Polygon& p, int nx, int ny) {
  const auto [xmin, xmax] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [ymin, ymax] = std::minmax_element(p.y.begin(), p.y.end());
  const int i0 = std::max(0, static_cast<int>(std::floor(*xmin))), i1 = std::min(nx - 1, static_cast<int>(*xmax));
  const int j0 = std::max(0, static_cast<int>(std::floor(*ymin))), j1 = std::min(ny - 1, static_cast<int>(*ymax));
  const double orientation = geometry::signed_area(p) >= 0.0 ? 1.0 : -1.0;  // +1: counter-clockwise
  std::vector<AreaFraction> out;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const double phi = std::clamp(orientation * geometry::area_in_box(p, i, i + 1.0, j, j + 1.0), 0.0, 1.0);
      if (phi > 0.0) out.push_back({static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i), phi});
    }
  return out;
}

std::vector<CutCell> cut_cells(const geometry::Polygon& p, int nx, int ny) {
  const double orientation = geometry::signed_area(p) >= 0.0 ? 1.0 : -1.0;  // +1: counter-clockwise
  const std::size_t m = p.x.size();
  std::vector<CutCell> out;
  for (const AreaFraction& f : area_fractions(p, nx, ny)) {
    CutCell c{f.node, f.phi};
    if (f.phi < 1.0) {
      const double i = static_cast<double>(f.node % static_cast<std::size_t>(nx));
      const double j = static_cast<double>(f.node / static_cast<std::size_t>(nx));
      double sx = 0.0, sy = 0.0;
      for (std::size_t k = 0; k < m; ++k) {
        const std::size_t l = (k + 1) % m;
        const double ex = p.x[l] - p.x[k], ey = p.y[l] - p.y[k], len = std::hypot(ex, ey);
        if (len == 0.0) continue;
        const double w = clipped_length(p.x[k], p.y[k], p.x[l], p.y[l], i, i + 1.0, j, j + 1.0) / len;
        // outward normal of a counter-clockwise edge: (e_y, −e_x)/|e|; w·len·n summed
        sx += w * orientation * ey;
        sy += -w * orientation * ex;
      }
      const double s = std::hypot(sx, sy);
      if (s > 0.0) {
        c.nx = sx / s;
        c.ny = sy / s;
      }
    }
    out.push_back(c);
  }
  return out;
}

double series_diffusivity(double phi, double D_in, double D_out) { return 1.0 / (phi / D_in + (1.0 - phi) / D_out); }

double parallel_diffusivity(double phi, double D_in, double D_out) { return phi * D_in + (1.0 - phi) * D_out; }

DiffusivityTensor subpixel_diffusivity(const CutCell& c, double D_in, double D_out) {
  const double Ds = series_diffusivity(c.phi, D_in, D_out);
  if (c.nx == 0.0 && c.ny == 0.0) return {Ds, Ds, 0.0};
  const double Dp = parallel_diffusivity(c.phi, D_in, D_out);
  // eq T10: D = Dp I + (Ds − Dp) n nᵀ
  return {Dp + (Ds - Dp) * c.nx * c.nx, Dp + (Ds - Dp) * c.ny * c.ny, (Ds - Dp) * c.nx * c.ny};
}

void set_node_subpixel_tensor(TransportLattice& lat, const std::vector<CutCell>& cells, double D_in, double D_out) {
  auto T = lat.diffusivity_tensor();
  for (const auto& c : cells) {
    const DiffusivityTensor d = subpixel_diffusivity(c, D_in, D_out);
    T.xx[c.node] = d.xx;
    T.yy[c.node] = d.yy;
    T.xy[c.node] = d.xy;
  }
}

std::vector<FaceTarget> subpixel_face_targets(const geometry::Polygon& p, int nx, int ny, double D_in, double D_out) {
  const std::size_t N = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  std::vector<FaceTarget> out;
  for (int axis = 0; axis < 2; ++axis) {
    const bool x_face = axis == 0;
    // dual cells of the faces = the node squares of p shifted by −½ along the face normal
    const auto shifted = geometry::transformed(p, 1.0, 0.0, x_face ? -0.5 : 0.0, x_face ? 0.0 : -0.5);
    std::vector<CutCell> dual(N);
    std::vector<char> has(N, 0);
    for (const auto& c : cut_cells(shifted, nx, ny)) {
      dual[c.node] = c;
      has[c.node] = 1;
    }
    const auto [xmin, xmax] = std::minmax_element(p.x.begin(), p.x.end());
    const auto [ymin, ymax] = std::minmax_element(p.y.begin(), p.y.end());
    const int i0 = std::max(0, static_cast<int>(std::floor(*xmin)) - 1);
    const int i1 = std::min(nx - 1 - (x_face ? 1 : 0), static_cast<int>(*xmax) + 1);
    const int j0 = std::max(0, static_cast<int>(std::floor(*ymin)) - 1);
    const int j1 = std::min(ny - 1 - (x_face ? 0 : 1), static_cast<int>(*ymax) + 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t a = static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
        FaceTarget t{a, x_face, D_out, 0.0};
        if (has[a]) {
          const DiffusivityTensor d = subpixel_diffusivity(dual[a], D_in, D_out);
          t.K = x_face ? d.xx : d.yy;
          t.X = d.xy;
        }
        out.push_back(t);
      }
  }
  return out;
}

}  // namespace erythro::transport
