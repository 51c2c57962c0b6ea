#include "channel_flows.hpp"

#include <cmath>
#include <numbers>

#include "common/case_support.hpp"

namespace erythro::vv {

long steps_to_steady_state(int N, double nu, double residual) {
  const double pi = std::numbers::pi;
  return static_cast<long>(std::ceil(std::log(1.0 / residual) * N * N / (nu * pi * pi)));
}

ChannelResult run_channel(fluid::FluidLattice& lattice, long steps) {
  Stopwatch clock;
  for (long s = 0; s < steps; ++s) lattice.step();
  const Grid g = lattice.grid();
  const fluid::Moments m = lattice.moments();
  ChannelResult result;
  for (int y = 0; y < g.ny; ++y) result.ux.push_back(m.ux[g.index(g.nx / 2, y)]);
  result.steps = steps;
  result.wall_time_s = clock.seconds();
  return result;
}

std::vector<double> poiseuille_exact(int N, double force, double nu) {
  std::vector<double> u(static_cast<std::size_t>(N));
  for (int j = 0; j < N; ++j) {
    const double y = j + 0.5;
    u[static_cast<std::size_t>(j)] = force * y * (N - y) / (2.0 * nu);
  }
  return u;
}

}  // namespace erythro::vv
