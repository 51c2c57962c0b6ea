// Transport step speed per species relative to the fluid step (issue 7 item 11;
// docs/transport.md §8). Times FluidLattice::step() (D2Q9 BGK, periodic) and
// TransportLattice::step() for D2Q5 / D2Q9, pure diffusion and the full configuration
// of a scene species (per-node D, velocity, source + sink), and the axisymmetric lattice against
// the planar one in the same configuration (D2Q5 TRT, axial velocity; docs/model.md §7b), at
// 256² and 1024², with
// the threads OpenMP gives (OMP_NUM_THREADS). Median of `repeats` timings after a
// warm-up; prints a table. Speed is reported, never asserted (label `benchmark`).
//   transport_benchmark [repeats=5]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

#include "fluid/fluid_lattice.hpp"
#include "transport/transport_lattice.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

using namespace erythro;
using Clock = std::chrono::steady_clock;

namespace {
// Median MLUPS of `step` over `repeats` timings of `steps` steps each.
double mlups(const std::function<void()>& step, std::size_t nodes, int steps, int repeats) {
  for (int s = 0; s < steps / 4 + 1; ++s) step();  // warm-up
  std::vector<double> rates;
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    for (int s = 0; s < steps; ++s) step();
    const double t = std::chrono::duration<double>(Clock::now() - start).count();
    rates.push_back(double(nodes) * steps / t * 1e-6);
  }
  std::sort(rates.begin(), rates.end());
  return rates[rates.size() / 2];
}

void full_configuration(transport::TransportLattice& lat) {
  const std::size_t N = lat.grid().size();
  std::vector<double> ux(N, 0.01), uy(N, -0.005);
  lat.set_velocity(ux, uy);
  for (auto& d : lat.diffusivity()) d = 0.2;
  for (auto& q : lat.source()) q = 1e-4;
  for (auto& k : lat.decay_rate()) k = 1e-3;
}
// The configuration of an arteriole species: per-node D, an axial velocity, a source and a sink
// (no radial velocity: the axisymmetric lattice takes none).
void axial_configuration(transport::TransportLattice& lat) {
  const std::size_t N = lat.grid().size();
  std::vector<double> ux(N, 0.01), uy(N, 0.0);
  lat.set_velocity(ux, uy);
  for (auto& d : lat.diffusivity()) d = 0.2;
  for (auto& q : lat.source()) q = 1e-4;
  for (auto& k : lat.decay_rate()) k = 1e-3;
}
}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  int threads = 1;
#if defined(_OPENMP)
  threads = omp_get_max_threads();
#endif
  std::printf("transport benchmark: %d thread(s), median of %d\n", threads, repeats);
  std::printf("%-6s %-34s %10s %14s\n", "grid", "kernel", "MLUPS", "fluid/transport");
  for (int n : {256, 1024}) {
    const Grid g{n, n};
    const int steps = n == 256 ? 400 : 40;
    fluid::FluidLattice fluid(g, {fluid::CollisionModel::bgk, 0.8, 0.25}, {});
    const double fluid_rate = mlups([&] { fluid.step(); }, g.size(), steps, repeats);
    std::printf("%4d^2 %-34s %10.1f %14s\n", n, "fluid D2Q9 BGK", fluid_rate, "1.00");
    for (auto st : {transport::Stencil::d2q5, transport::Stencil::d2q9}) {
      for (bool full : {false, true}) {
        transport::TransportLattice lat(g, st, {});
        lat.set_uniform_diffusivity(0.2);
        lat.initialize_uniform(1.0);
        if (full) full_configuration(lat);
        const double rate = mlups([&] { lat.step(); }, g.size(), steps, repeats);
        char name[64];
        std::snprintf(name, sizeof name, "transport %s %s", st == transport::Stencil::d2q5 ? "D2Q5" : "D2Q9",
                      full ? "D(x),u,q,k" : "diffusion");
        std::printf("%4d^2 %-34s %10.1f %14.2f\n", n, name, rate, fluid_rate / rate);
      }
    }
    // Planar and axisymmetric side by side (the drift D/r, the source r q, C = φ/r per step).
    const transport::Side zero{transport::SideKind::zero_flux, 0.0}, held{transport::SideKind::fixed_concentration, 1.0};
    for (bool axisymmetric : {false, true}) {
      transport::TransportLattice lat(g, transport::Stencil::d2q5, {{}, {}, zero, held});
      if (axisymmetric) lat.set_axisymmetric(0.0);
      lat.set_collision({transport::Collision::trt, 0.25});
      axial_configuration(lat);
      lat.initialize_uniform(1.0);
      const double rate = mlups([&] { lat.step(); }, g.size(), steps, repeats);
      std::printf("%4d^2 %-34s %10.1f %14.2f\n", n,
                  axisymmetric ? "transport D2Q5 TRT axisym., D,u,q,k" : "transport D2Q5 TRT planar, D,u,q,k", rate,
                  fluid_rate / rate);
    }
  }
  return 0;
}
