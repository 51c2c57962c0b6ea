// Cost of one index-field update per method against one fluid step (issue 5 item 10;
// docs/verification-interior.md). Label `benchmark` only: speed is measured, not asserted.
//
// Scenes: n biconcave cells (100 markers, a = 26.07 h = 3.91 µm at h = 0.15 µm) on the
// doublet grid 201² (n = 1, 2, 8) and on 401² (n = 1, 2, 8, 32; 32 cells need the larger
// grid to fit without overlap). The fluid step is the production one: BGK with the
// per-node τ field and the force field enabled (IB + interior viscosity), moving walls.
// Counter `vs_fluid_step` = update CPU time / fluid-step CPU time on the same grid. Run
// with OMP_NUM_THREADS=1 (as registered): both sides single-threaded, CPU times are robust
// on a shared machine; with T fluid threads the ratio grows by up to T (the update is serial).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>
#include <map>

#include "fluid/fluid_lattice.hpp"
#include "interior/index_field.hpp"
#include "test_shapes.hpp"

using namespace erythro;

namespace {
constexpr double kA = 3.91 / 0.15;

fluid::FluidLattice make_lattice(int n) {
  fluid::BoundaryConfig b;
  b.bottom.type = b.top.type = fluid::SideType::moving_wall;
  b.bottom.ux = -0.01;
  b.top.ux = 0.01;
  fluid::FluidLattice lat(Grid{n, n}, {fluid::CollisionModel::bgk, 0.7, 3.0 / 16.0}, b);
  lat.enable_tau_field();
  lat.enable_force_field();
  lat.initialize_uniform(1.0, 0.0, 0.0);
  return lat;
}

// CPU seconds per fluid step on an n × n grid (measured once per grid, median of 5 × 20 steps).
double fluid_step_seconds(int n) {
  static std::map<int, double> cache;
  if (auto it = cache.find(n); it != cache.end()) return it->second;
  auto lat = make_lattice(n);
  for (int s = 0; s < 20; ++s) lat.step();
  std::vector<double> t;
  for (int r = 0; r < 5; ++r) {
    const std::clock_t t0 = std::clock();
    for (int s = 0; s < 20; ++s) lat.step();
    t.push_back(double(std::clock() - t0) / CLOCKS_PER_SEC / 20);
  }
  std::sort(t.begin(), t.end());
  return cache[n] = t[2];
}

void BM_FluidStep(benchmark::State& st) {
  auto lat = make_lattice(static_cast<int>(st.range(0)));
  for (auto _ : st) lat.step();
  st.counters["nodes"] = double(lat.grid().size());
}

void BM_IndexUpdate(benchmark::State& st) {
  const auto method = static_cast<interior::Method>(st.range(0));
  const int cells = static_cast<int>(st.range(1)), n = static_cast<int>(st.range(2));
  const vv::CellScene scene = vv::biconcave_array(cells, n, n, kA);
  interior::IndexField field(scene.domain, {method, 2.0});
  std::vector<double> tau(scene.domain.grid.size());
  long interior = 0;
  for (auto _ : st) {
    interior = field.update(scene.cells).interior_nodes;
    benchmark::DoNotOptimize(field.values().data());
  }
  st.SetLabel(std::string(interior::to_string(method)));
  st.counters["interior_nodes"] = double(interior);
  st.counters["fluid_step_us"] = fluid_step_seconds(n) * 1e6;
  // (CPU time of the loop) / (iterations × fluid step) = update / fluid step.
  st.counters["vs_fluid_step"] = benchmark::Counter(double(st.iterations()) * fluid_step_seconds(n),
                                                    benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_WriteTau(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const vv::CellScene scene = vv::biconcave_array(2, n, n, kA);
  interior::IndexField field(scene.domain, {interior::Method::flood_fill, 2.0});
  field.update(scene.cells);
  std::vector<double> tau(scene.domain.grid.size());
  for (auto _ : st) {
    field.write_relaxation_times(tau, 1.0 / 3.0, 0.2 / 3.0);
    benchmark::DoNotOptimize(tau.data());
  }
}

void update_args(benchmark::internal::Benchmark* b) {
  for (int m = 0; m < 4; ++m) {
    for (int c : {1, 2, 8}) b->Args({m, c, 201});
    for (int c : {1, 2, 8, 32}) b->Args({m, c, 401});
  }
}
}  // namespace

BENCHMARK(BM_FluidStep)->Arg(201)->Arg(401)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IndexUpdate)->Apply(update_args)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WriteTau)->Arg(201)->Arg(401)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
