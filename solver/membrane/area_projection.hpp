#pragma once
// The enclosed area of a closed polygon restored by a projection (docs/model.md eq 3.14):
// every vertex moves along the gradient of the shoelace area,
//   g_i = ∂A/∂X_i = ½ (y_{i+1} − y_{i−1}, x_{i−1} − x_{i+1}),   X_i ← X_i + λ g_i,
// with λ the root of A(X + λg) = A_target nearest zero (A is quadratic in λ: solved exactly).
// The smallest change of the markers (in the least-squares sense, to first order) that gives
// the polygon its area back: the immersed boundary's leakage (fluid crossing the membrane, a
// consequence of interpolating a velocity that is not divergence-free at the markers) no
// longer accumulates into a loss of area.
#include <span>

namespace erythro::membrane {

// Moves the vertices of the polygon (x, y) (counter-clockwise or clockwise; ≥ 3 vertices) so
// that its signed area becomes `target_area` (same sign as the polygon's); returns the signed
// area change applied (target − area before).
double project_area(std::span<double> x, std::span<double> y, double target_area);

}  // namespace erythro::membrane
