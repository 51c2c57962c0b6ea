#include "configs.hpp"

#include <cmath>
#include <random>

#include "geometry/polygon.hpp"
#include "geometry/shapes.hpp"

namespace erythro::vv {

void add_cell(MarkerConfig& c, const std::vector<double>& x, const std::vector<double>& y) {
  c.x.insert(c.x.end(), x.begin(), x.end());
  c.y.insert(c.y.end(), y.begin(), y.end());
  c.offsets.push_back(c.x.size());
}

MarkerConfig random_cells(int cells, int markers, int nx, int ny, bool periodic, std::uint64_t seed) {
  MarkerConfig c;
  c.domain = geometry::Domain{Grid{nx, ny}, periodic, periodic};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < cells; ++k) {
    const double a = 6.0 + 4.0 * u(rng);
    const geometry::Polygon shape = u(rng) < 0.5 ? geometry::circle(markers, a) : geometry::biconcave(markers, a);
    double cx = nx * u(rng), cy = ny * u(rng);
    if (periodic && u(rng) < 0.33) cx += (u(rng) < 0.5 ? -1.0 : 1.0) * nx;  // unwrapped storage
    if (periodic && u(rng) < 0.33) cy += (u(rng) < 0.5 ? -1.0 : 1.0) * ny;
    geometry::Polygon p = geometry::transformed(shape, 1.0, 2.0 * 3.141592653589793 * u(rng), cx, cy);
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.x[i] += 0.1 * (u(rng) - 0.5);
      p.y[i] += 0.1 * (u(rng) - 0.5);
    }
    add_cell(c, p.x, p.y);
  }
  return c;
}

MarkerConfig lattice_cells(int k, int markers, double a, double fraction, std::uint64_t seed) {
  MarkerConfig c;
  const double pi = 3.141592653589793;
  const int L = static_cast<int>(std::lround(std::sqrt(pi * a * a * k * k / fraction)));
  c.domain = geometry::Domain{Grid{L, L}, true, true};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double spacing = double(L) / k;
  const geometry::Polygon shape = geometry::circle(markers, a);
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) {
      const geometry::Polygon p =
          geometry::transformed(shape, 1.0, pi * u(rng), (i + 0.5) * spacing + u(rng), (j + 0.5) * spacing + u(rng));
      add_cell(c, p.x, p.y);
    }
  }
  return c;
}

}  // namespace erythro::vv
