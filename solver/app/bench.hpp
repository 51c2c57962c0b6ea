#pragma once
// `erythro bench`: throughput of FluidLattice::step() (MLUPS) measured against the
// machine's memory-bandwidth bound, bound = copy bandwidth / 144 B per node update
// (two D2Q9 double lattices: 72 B read + 72 B written); then the coupled step of a
// suspension of cells, per cell and step (coupled_bench.hpp). Informative only: nothing
// here asserts a speed. Method and figures: docs/performance.md.
#include <string>
#include <vector>

#include "app/coupled_bench.hpp"

namespace CLI {
class App;
}

namespace erythro::app {

struct BenchOptions {
  std::string out;                         // record path; default $ERYTHRO_RESULTS_DIR/benchmark.fluid.h5
  std::vector<int> sizes{256, 1024, 2048};  // square grids n × n
  std::vector<int> threads{1, 2};
  int repeats = 7;              // timed samples per configuration (median, min, max reported)
  double sample_seconds = 0.2;  // minimum duration of one sample
  bool quick = false;           // 256² and 1024², 3 short samples: a smoke run
  bool coupled_only = false;    // only the coupled step (coupled_bench.hpp), in benchmark.coupled
  bool fluid_inputs = false;    // only the fluid step with each input of the coupled step, in benchmark.fluid_inputs
  CoupledBenchOptions coupled;  // its threads are `threads`
  std::string write_scenes;     // with coupled_only: write the boxes' scenes here instead (write_box_scenes)
};

// Declares the `bench` subcommand on `cli`, filling `options`.
CLI::App* add_bench_subcommand(CLI::App& cli, BenchOptions& options);
int bench_command(const BenchOptions& options);

}  // namespace erythro::app
