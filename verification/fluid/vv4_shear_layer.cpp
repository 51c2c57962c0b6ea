#include "vv4_shear_layer.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "common/case_support.hpp"

namespace erythro::vv {

void initialize_double_shear_layer(fluid::FluidLattice& lattice, double U) {
  const Grid g = lattice.grid();
  const double L = g.nx, delta = L / 30.0, eps = 0.05;
  std::vector<double> rho(g.size(), 1.0), ux(g.size()), uy(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = i + 0.5, y = j + 0.5;
      const std::size_t n = g.index(i, j);
      ux[n] = y <= 0.5 * L ? U * std::tanh((y - 0.25 * L) / delta) : U * std::tanh((0.75 * L - y) / delta);
      uy[n] = eps * U * std::sin(2.0 * std::numbers::pi * (x / L + 0.25));
    }
  }
  lattice.initialize(rho, ux, uy);
}

std::string describe_health(long step, const HealthReport& r) {
  std::ostringstream out;
  out << "step " << step << ": " << r.quantity << " = " << r.value << " at node (" << r.node_x << ", " << r.node_y
      << ")";
  if (std::isnan(r.limit)) {
    out << " is not finite";
  } else if (r.quantity == "density") {
    out << " is not positive";
  } else {
    out << " exceeds max_mach " << r.limit;
  }
  return out.str();
}

ShearLayerRun run_double_shear_layer(const ShearLayerSpec& spec) {
  Stopwatch clock;
  fluid::FluidLattice lattice(Grid{spec.L, spec.L}, spec.collision, fluid::BoundaryConfig{});
  initialize_double_shear_layer(lattice, spec.U);
  ShearLayerRun run;
  run.steps_planned = static_cast<long>(std::ceil(spec.convective_times * spec.L / spec.U));
  for (long s = 1; s <= run.steps_planned; ++s) {
    lattice.step();
    if (s % spec.check_interval != 0 && s != run.steps_planned) continue;
    const HealthReport h = lattice.check_health(spec.max_mach);
    run.steps = s;
    if (!h.healthy) {
      run.stable = false;
      run.diagnosis = describe_health(s, h);
      break;
    }
  }
  run.wall_time_s = clock.seconds();
  return run;
}

}  // namespace erythro::vv
