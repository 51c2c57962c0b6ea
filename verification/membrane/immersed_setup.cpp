#include "immersed_setup.hpp"

#include <cmath>
#include <stdexcept>

#include "common/case_support.hpp"
#include "geometry/polygon.hpp"

namespace erythro::vv {

ImmersedBox make_periodic_box(int L, double tau, ib::KernelType kernel) {
  ImmersedBox box;
  box.lattice = std::make_unique<fluid::FluidLattice>(Grid{L, L}, fluid::CollisionConfig{fluid::CollisionModel::bgk, tau, 3.0 / 16.0},
                                                      fluid::BoundaryConfig{});
  box.cells = std::make_unique<membrane::ImmersedCells>(kernel, *box.lattice);
  return box;
}

AdvanceResult advance(ImmersedBox& box, long steps, const std::function<void(long)>& each) {
  Stopwatch sw;
  AdvanceResult r;
  const double p0 = geometry::perimeter(box.cells->polygon(0));
  for (long s = 0; s < steps; ++s) {
    try {
      box.cells->advance(*box.lattice);
    } catch (const std::domain_error&) {
      r.diverged = true;
      break;
    }
    r.steps_done = s + 1;
    if (each) each(s);
    if (s % 100 == 0) {
      const double p = geometry::perimeter(box.cells->polygon(0));
      if (!(std::abs(p / p0 - 1.0) < 0.05)) {
        r.diverged = true;
        break;
      }
    }
  }
  r.wall_time_s = sw.seconds();
  return r;
}

}  // namespace erythro::vv
