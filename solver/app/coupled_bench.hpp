#pragma once
// The coupled-step section of `erythro bench` (issue 18): the cost of the immersed cells in
// a suspension, per cell and step, beside the fluid step of the same grid without cells.
// Informative only. Method and figures: docs/performance-coupled-step.md "The coupled step benchmark".
#include <string>
#include <vector>

namespace erythro::io {
class ResultRecord;
}

namespace erythro::app {

struct CoupledBenchOptions {
  std::vector<int> cells{2, 8, 32, 128};  // cells per box; the box is sized for φ = 0.3
  // Empty, or {nx, ny}: one box of nx × ny nodes for every cell count instead (issue 18's
  // grid-proportional overhead: few cells in a large grid).
  std::vector<int> grid;
  std::vector<int> threads{1, 2};
  long steps = 150;  // time steps of each timed run (≈ 3 s for 128 cells on one thread)
  int pairs = 3;     // fluid-only and coupled runs, one after the other; medians reported
  // Morse aggregation between the cells at the thesis's ch. IV level (De* = 5), on top of the
  // repulsion, sharing its neighbour search.
  bool aggregation = false;
  // Index-field rebuild interval k; 0: the largest k the validation supports in each box,
  // k U ≤ 0.1 h with U the wall speed (docs/performance-coupled-step.md "The coupled step benchmark").
  long index_interval = 0;
  // A user's scene with cells instead of the shear boxes (scene_bench.hpp); cells, aggregation
  // and index_interval are then the scene's.
  std::string scene;
  // Instead of the pairs of separate runs: each box once, one thread and the largest of
  // `threads` in turn, block by block (thread_alternation.hpp).
  bool alternate_threads = false;
};

// --write-scenes: instead of measuring, writes each box's scenes into `dir` for a comparison
// with another binary by whole processes (ci/bench-against.sh): box<N>_product.toml (the
// scene this section runs), box<N>_same.toml (the same cells as [[cells]] entries, the index
// field every step, no repulsion: what a binary from before [[cell_populations]] reads),
// box<N>_fluid.toml (the box without cells), and boxes.tsv listing them with N, n and k.
void write_box_scenes(const CoupledBenchOptions& options, const std::string& dir);

// Runs the section, prints its table and adds its runs and metrics to `record`.
void run_coupled_bench(const CoupledBenchOptions& options, io::ResultRecord& record);

}  // namespace erythro::app
