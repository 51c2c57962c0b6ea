#pragma once
// Two thread counts in one run, for the coupled-step section of `erythro bench`
// (--alternate-threads; issue 18's "two threads against one for the cell work"). The scene runs
// once; every block of steps it switches between one thread and T threads, and each block's
// stage times go to the count it ran on. A run gives the same bits on any thread count, so the
// switches do not change it; both counts see the same cells at the same moments, and the same
// fast and slow phases of a shared host, which two separate runs do not
// (docs/performance.md, "Two threads against one, in one run").
#include <string>
#include <vector>

#include "app/coupled_timing.hpp"

namespace erythro::app {

struct AlternatedStage {
  std::string name;
  double us_one = 0.0, us_many = 0.0;  // per step, on one thread and on T
};

struct AlternatedThreads {
  int threads = 2;                                 // T
  long block_steps = 0;                            // steps per block (a whole number of index-field intervals)
  long blocks_each = 0;                            // timed blocks on each count (a warm-up block before them)
  // The cell work per step, on one thread and on T: every stage but the fluid step and the
  // force field's reset (those scale with the grid).
  double cell_work_one_us = 0.0, cell_work_many_us = 0.0;
  double fluid_one_us = 0.0, fluid_many_us = 0.0;  // the fluid step, per step
  std::vector<double> pair_ratios;                 // per pair of blocks (one thread, then T): cell work on one / on T
  std::vector<AlternatedStage> stages;             // in the loop's order, without the observation phase
};

// Runs `scene` (whose run.steps is at least (1 + 2 blocks_each) block_steps) once, T threads
// for the warm-up block, then one thread and T threads in turn. Throws std::runtime_error when
// the run ends early. Leaves OpenMP at T threads.
AlternatedThreads alternate_threads(const PreparedScene& scene, int threads, long block_steps, long blocks_each);

}  // namespace erythro::app
