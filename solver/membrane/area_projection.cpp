// docs/model.md eq 3.14: restores a polygon's area along the gradient of the shoelace area.
#include "membrane/area_projection.hpp"

#include <cmath>
#include <cstddef>

namespace erythro::membrane {

double project_area(std::span<double> x, std::span<double> y, double target_area) {
  const std::size_t n = x.size();
  const auto prev = [n](std::size_t i) { return i == 0 ? n - 1 : i - 1; };
  const auto next = [n](std::size_t i) { return i + 1 == n ? 0 : i + 1; };
  // A(X + λg) = A + λ L + λ² Q,  A = ½ Σ X_i × X_{i+1},  L = ½ Σ (X_i × g_{i+1} + g_i × X_{i+1}),
  // Q = ½ Σ g_i × g_{i+1}  (× the 2D cross product; every sum in vertex order: the same bits
  // for any number of threads running other cells).
  double area = 0.0, linear = 0.0, quadratic = 0.0;
  const auto gx = [&](std::size_t i) { return 0.5 * (y[next(i)] - y[prev(i)]); };
  const auto gy = [&](std::size_t i) { return 0.5 * (x[prev(i)] - x[next(i)]); };
  double gxi = gx(0), gyi = gy(0);  // g_i, carried over from the previous vertex's g_{i+1}
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = next(i);
    const double gxj = gx(j), gyj = gy(j);
    area += x[i] * y[j] - x[j] * y[i];
    linear += x[i] * gyj - gxj * y[i] + gxi * y[j] - x[j] * gyi;
    quadratic += gxi * gyj - gxj * gyi;
    gxi = gxj;
    gyi = gyj;
  }
  area *= 0.5;
  linear *= 0.5;
  quadratic *= 0.5;
  const double deficit = area - target_area;  // solve Q λ² + L λ + deficit = 0
  if (deficit == 0.0 || linear == 0.0) return 0.0;
  // The root nearest zero, in the form without cancellation: λ = −2c / (b + sign(b)√(b² − 4ac)).
  const double disc = linear * linear - 4.0 * quadratic * deficit;
  const double lambda =
      disc >= 0.0 ? -2.0 * deficit / (linear + std::copysign(std::sqrt(disc), linear)) : -deficit / linear;
  // X ← X + λ g with g of the polygon before the move: X_{i−1} is kept before it moves, and
  // X_0 for the last vertex.
  const double x0 = x[0], y0 = y[0];
  double xp = x[n - 1], yp = y[n - 1];
  for (std::size_t i = 0; i < n; ++i) {
    const double xn = i + 1 == n ? x0 : x[i + 1], yn = i + 1 == n ? y0 : y[i + 1];
    const double move_x = lambda * (0.5 * (yn - yp)), move_y = lambda * (0.5 * (xp - xn));
    xp = x[i];
    yp = y[i];
    x[i] += move_x;
    y[i] += move_y;
  }
  return target_area - area;
}

}  // namespace erythro::membrane
