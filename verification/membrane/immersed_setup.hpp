#pragma once
// Shared set-up of the membrane-in-fluid cases: a periodic box with one cell,
// the IB cycle of membrane/immersed_cells.hpp, and a divergence guard.
#include <functional>
#include <memory>

#include "fluid/fluid_lattice.hpp"
#include "membrane/immersed_cells.hpp"

namespace erythro::vv {

struct ImmersedBox {
  std::unique_ptr<fluid::FluidLattice> lattice;
  std::unique_ptr<membrane::ImmersedCells> cells;
};

// Periodic L × L box of fluid at rest (BGK, τ), IB cells with the given kernel.
ImmersedBox make_periodic_box(int L, double tau, ib::KernelType kernel);

struct AdvanceResult {
  long steps_done = 0;
  bool diverged = false;  // non-finite marker, or perimeter of cell 0 off by > 5 %
  double wall_time_s = 0.0;
};

// Runs `steps` IB steps; calls `each(step)` after every step if given; stops early
// when the run diverges.
AdvanceResult advance(ImmersedBox& box, long steps, const std::function<void(long)>& each = {});

}  // namespace erythro::vv
