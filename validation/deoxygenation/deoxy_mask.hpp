#pragma once
// Heme weights of the deoxygenation model's cell by first moments
// (docs/validation-deoxygenation.md, "Set-up", Representation::area_fraction_moment).
//
// With plain area fractions the heme of a cut node (0 < φ < 1) sits at the node centre,
// while the part of the node's square inside the cell has its centroid displaced by
// δ = (1/φ)∫_{square ∩ cell} (x − x_node) dA (|δ_x|, |δ_y| ≤ ½, always towards the cell's
// inside). Release and mean P are then both off by a dipole per cut node: an O(h²) error
// of the cell's mean P whose size changes irregularly with h (it depends on how the lattice
// cuts the membrane). Here each cut node's φ is spread bilinearly from its centroid
// (cloud-in-cell weights on the node and its neighbours towards δ):
//   w_k = Σ_n φ_n W_nk,  W = (1 − |δ_x|)(1 − |δ_y|), |δ_x|(1 − |δ_y|), (1 − |δ_x|)|δ_y|, |δ_x||δ_y|,
// which keeps Σ w = Σ φ (the cell's area) and the first moment of the heme exactly. The same
// weights sample the mean P (P̄ = Σ w_k C_k / (α Σ w)): bilinear interpolation of C at each
// centroid, the adjoint of the spreading.
#include <vector>

#include "deoxy_run.hpp"
#include "geometry/polygon.hpp"

namespace erythro::deoxy {

// First moment ∫ (x − x_c, y − y_c) dA of the part of node (i, j)'s unit square
// [i, i+1] × [j, j+1] inside polygon p (lattice units, x_c = i + ½, y_c = j + ½), by
//   ∫ (x − x_c) a(x) dx = ½ φ − ∫_0^1 A(i, i + s) ds   (integration by parts; A(x0, x1) =
// area of p in [x0, x1] × [j, j+1], geometry::area_in_box), composite 3-point Gauss–Legendre
// on 8 panels (A is C¹ and piecewise quadratic between marker abscissae).
struct Moment {
  double mx = 0.0, my = 0.0;
};
Moment first_moment(const geometry::Polygon& p, int i, int j, double phi);

// Heme weights w_k (node, w > 0) from the area fractions of an nx × ny grid (above).
std::vector<NodeFraction> first_moment_weights(const geometry::Polygon& p, int nx, int ny,
                                               const std::vector<NodeFraction>& fractions);

}  // namespace erythro::deoxy

namespace erythro::deoxy {

// Node resistivities R_n = 1/D_n (physical units) by link-wise least squares (probe option
// Setup::link_diffusivity; docs/validation-deoxygenation.md, "Findings"). With TRT Λ = 1/4
// the lattice's steady flux between neighbours n, m uses the harmonic face D, i.e. the face
// resistance (R_n + R_m)/2 (transport eq T7). The link's own series resistance is
//   R*_nm = θ_nm/D_in + (1 − θ_nm)/D_out,   θ_nm = fraction of the segment x_n → x_m inside p,
// exact for the normal flux through an interface crossing the link. The R_n of the nodes on
// cut links minimise Σ_links ((R_n + R_m)/2 − R*_nm)² + μ Σ_n (R_n − R_n^φ)² (R^φ: the
// area-fraction value; μ = 0.1 damps the near-checkerboard null mode), by Gauss–Seidel,
// clamped to [1/D_out, 1/D_in]. Returns R_n for every node of the nx × ny grid.
std::vector<double> link_resistivities(const geometry::Polygon& p, int nx, int ny, double D_in, double D_out,
                                       const std::vector<double>& R_phi);

// Fraction of the segment (x0, y0) → (x1, y1) inside polygon p (even–odd crossings).
double segment_fraction_inside(const geometry::Polygon& p, double x0, double y0, double x1, double y1);

}  // namespace erythro::deoxy
