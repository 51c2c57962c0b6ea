#pragma once
// A node grid and, per axis, whether it is periodic: the Eulerian side of an
// immersed-boundary transfer, of the index field and of the transport's cells. Node (i, j) sits at (i + ½, j + ½) (cell-centred, h = 1);
// a non-periodic axis has halfway walls at 0 and n (fluid/boundary.hpp; a fluid's
// domain: fluid::domain_of).
//
// Kernel support across a periodic side wraps (index mod n). Across a wall there
// are no nodes: the weight of support nodes beyond a wall is DROPPED. Consequences,
// tested in solver/tests/ib: a marker closer than width/2 to a wall spreads less
// than its force into the fluid (Σ_x f < Σ_m F_m) and interpolation there loses
// partition of unity (a uniform field u is read as u·Σφ < u). Markers are kept
// outside the wall layer by the physics (no-slip); the loss is a wall-proximity
// error of the IB method, not a conservation bug.
#include "lattice/grid.hpp"

namespace erythro::geometry {

struct Domain {
  Grid grid;
  bool periodic_x = true;
  bool periodic_y = true;
};

}  // namespace erythro::geometry
