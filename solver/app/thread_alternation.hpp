#pragma once
// Two thread counts in one run, for the coupled-step section of `erythro bench`
// (--alternate-threads; issue 18's "two threads against one for the cell work"). The scene runs
// once; every block of steps it switches between one thread and T threads, and each block's
// stage times go to the count it ran on. A run gives the same bits on any thread count, so the
// switches do not change it; both counts see the same cells at the same moments, and the same
// fast and slow phases of a shared host, which two separate runs do not
// (docs/performance-coupled-step.md, "Two threads against one, in one run").
#include <string>
#include <utility>
#include <vector>

#include "app/coupled_timing.hpp"

namespace erythro::io {
class ResultRecord;
}

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

// The blocks of an alternating run of a scene with index-field interval k (1 without an index
// field): about 60 steps each, a whole number of intervals, so that each timed block holds the
// same rebuilds; at least three blocks on each count and `steps` steps in all.
struct AlternationPlan {
  long block_steps = 0, blocks_each = 0;
  long run_steps() const { return (2 * blocks_each + 1) * block_steps; }  // the warm-up block included
};
AlternationPlan plan_alternation(long k, long steps);

// T, the largest of the bench's thread counts; an InputError when it is below two.
int alternation_threads(const std::vector<int>& threads);

// The table's heading; `what` describes the scenes.
void print_alternation_heading(int threads, const std::string& what);

// Prints the row of `cells` cells (`grid`: "nx x ny") and its stage lines, and adds the run (its
// own `columns` first, then the measurement; `scene_text` kept in /scenes) and the metric
// cell_work_speedup_<tag> to the record.
void report_alternation(io::ResultRecord& record, const AlternatedThreads& a, int cells, const std::string& grid,
                        long k, const std::string& tag, const std::vector<std::pair<std::string, double>>& columns,
                        const std::string& scene_text);

// Runs `scene` (whose run.steps is at least (1 + 2 blocks_each) block_steps) once, T threads
// for the warm-up block, then one thread and T threads in turn. Throws std::runtime_error when
// the run ends early. Leaves OpenMP at T threads.
AlternatedThreads alternate_threads(const PreparedScene& scene, int threads, long block_steps, long blocks_each);

}  // namespace erythro::app
