#pragma once
// The fused pull-scheme stream–collide kernel (internal to the fluid layer).
#include <cstddef>

#include "fluid/boundary.hpp"
#include "fluid/collision.hpp"
#include "lattice/grid.hpp"

namespace erythro::fluid::detail {

struct KernelArgs {
  Grid grid;
  const double* src = nullptr;  // post-collision populations of step t, [q*N + n]
  double* dst = nullptr;        // post-collision populations of step t+1
  CollisionConfig collision;
  BoundaryConfig boundaries;
  const double* tau_field = nullptr;  // optional τ(x)
  const double* force_x = nullptr;    // optional F(x)
  const double* force_y = nullptr;
  double uniform_fx = 0.0, uniform_fy = 0.0;
};

void stream_collide(const KernelArgs& args);

}  // namespace erythro::fluid::detail
