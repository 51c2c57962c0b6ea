#pragma once
// Per-edge and per-vertex constants of one membrane polygon for the band pass
// (band_pass.cpp): edge vectors and normals, the bisector ("wedge") lines at the vertices
// and the reciprocals the row loops need. Built in branch-free loops over all edges at
// once (they vectorise), so the row loops of the band pass do no division.
// Lattice units; edge a runs from marker a to marker a + 1 (mod n), vertex v joins edge
// v − 1 (mod n) to edge v. Every array has n + 1 entries, entry n repeating entry 0.
#include <cstddef>
#include <vector>

#include "geometry/polygon.hpp"

namespace erythro::interior {

struct EdgeTable {
  // Edge a.
  std::vector<double> ex, ey;          // edge vector B − A
  std::vector<double> len;             // |B − A|
  std::vector<double> nx, ny;          // outward unit normal (0 for a zero-length edge)
  std::vector<double> inv_len2;        // 1/|B − A|²
  std::vector<double> inv_ey;          // 1/e_y (0 for a horizontal edge)
  std::vector<double> ylo, yhi;        // wedge mode: y range of the edge's wedge parallelogram
  // Vertex v.
  std::vector<double> tx, ty;          // forward tangent of the bisector line (unit)
  std::vector<double> inv_tx;          // 1/t_x (0 where t_x = 0)
  std::vector<double> tan_half;        // |tan(θ_v/2)|, θ_v the turning angle
  bool wedges = false;                 // the wedge conditions hold at every vertex and edge
  double perimeter = 0.0;              // Σ len

  // Fills the table for polygon p with orientation sign `orient` (+1 counter-clockwise)
  // and band margin `margin` (the largest distance the band pass records); `wedge_tol`
  // widens every wedge's row range (band_pass.cpp).
  void build(const geometry::Polygon& p, double orient, double margin, double wedge_tol);

 private:
  std::vector<double> x_, y_;  // the marker coordinates, marker 0 repeated at the end
};

}  // namespace erythro::interior
