#pragma once
// Heme weights of a cell by first moments (docs/transport.md §4.2; docs/validation-deoxygenation.md,
// "Findings": the scene option hemoglobin.heme_weights = "first_moment").
//
// With plain area fractions the heme of a cut node (0 < φ < 1) sits at the node centre, while
// the part of the node's square inside the cell has its centroid displaced by
// δ = (1/φ)∫_{square ∩ cell} (x − x_node) dA (|δ_x|, |δ_y| ≤ ½, always towards the cell's
// inside). Release and mean P are then both off by a dipole per cut node: an O(h²) error of
// the cell's mean P whose size changes irregularly with h. Here each cut node's φ is spread
// bilinearly from its centroid (cloud-in-cell weights on the node and its neighbours towards δ):
//   w_k = Σ_n φ_n W_nk,  W = (1 − |δ_x|)(1 − |δ_y|), |δ_x|(1 − |δ_y|), (1 − |δ_x|)|δ_y|, |δ_x||δ_y|,
// which keeps Σ w = Σ φ (the cell's area) and the first moment of the heme exactly. The same
// weights sample the mean P (bilinear interpolation of C at each centroid, the adjoint).
#include <vector>

#include "geometry/polygon.hpp"
#include "transport/subpixel_diffusivity.hpp"

namespace erythro::transport {

// First moment ∫ (x − x_c, y − y_c) dA of the part of node (i, j)'s unit square
// [i, i+1] × [j, j+1] inside polygon p (lattice units, x_c = i + ½, y_c = j + ½), by
//   ∫ (x − x_c) a(x) dx = ½ φ − ∫_0^1 A(i, i + s) ds   (integration by parts; A(x0, x1) = area
// of p in [x0, x1] × [j, j+1], geometry::area_in_box), composite 3-point Gauss–Legendre on 8
// panels (A is C¹ and piecewise quadratic between marker abscissae).
struct Moment {
  double mx = 0.0, my = 0.0;
};
Moment first_moment(const geometry::Polygon& p, int i, int j, double phi);

// Heme weights w_k (node, w > 0), ascending nodes, from the area fractions of an nx × ny grid.
std::vector<AreaFraction> first_moment_weights(const geometry::Polygon& p, int nx, int ny,
                                               const std::vector<AreaFraction>& fractions);

}  // namespace erythro::transport
