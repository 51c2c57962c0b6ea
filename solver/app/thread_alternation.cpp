#include "app/thread_alternation.hpp"

#include <omp.h>

#include <map>
#include <stdexcept>

#include "simulation/simulation.hpp"

namespace erythro::app {
namespace {

class Silent : public sim::RunObserver {};

bool grid_stage(const std::string& name) { return name == "fluid_step" || name == "force_field_reset"; }

// Each stage's seconds so far, without the observation phase.
std::map<std::string, double> seconds_so_far(const sim::TimeLoop& loop) {
  std::map<std::string, double> s;
  for (const sim::StageTiming& t : loop.timings())
    if (t.phase != sim::Phase::observe) s[t.name] = t.seconds;
  return s;
}

}  // namespace

AlternatedThreads alternate_threads(const PreparedScene& scene, int threads, long block_steps, long blocks_each) {
  if (threads < 2) throw std::invalid_argument("alternate_threads: needs two threads or more");
  AlternatedThreads a;
  a.threads = threads;
  a.block_steps = block_steps;
  a.blocks_each = blocks_each;
  omp_set_num_threads(threads);  // built on T threads: every per-thread buffer sized for T
  sim::Simulation simulation(scene.scene, scene.setup);
  std::map<std::string, double> one, many, before;
  std::vector<double> cells_one;  // each one-thread block's cell work (s), to pair with the next
  long block = 0;                 // the block that has just ended
  const long last_block = 2 * blocks_each;
  // Block b is steps b B … (b + 1) B − 1: with B a multiple of k, each timed block holds B/k
  // index-field rebuilds (at steps that are multiples of k, from k on). At the end of every block
  // (the last stage of its last step): its stage times to the count it ran on, then the other
  // count. Block 0 (T threads) is the warm-up; odd blocks run on one thread, even ones on T.
  simulation.add_stage(
      sim::Phase::observe, "thread_alternation",
      [&](long) {
        std::map<std::string, double> now = seconds_so_far(simulation.time_loop());
        if (block >= 1 && block <= last_block) {
          const bool on_one = block % 2 == 1;
          double cells = 0.0;
          for (const auto& [name, s] : now) {
            const double ds = s - before[name];
            (on_one ? one : many)[name] += ds;
            if (!grid_stage(name)) cells += ds;
          }
          if (on_one) {
            cells_one.push_back(cells);
          } else if (cells > 0.0) {
            a.pair_ratios.push_back(cells_one.back() / cells);
          }
        }
        before = std::move(now);
        ++block;
        omp_set_num_threads(block % 2 == 1 ? 1 : threads);
      },
      block_steps, block_steps - 1);
  Silent silent;
  const sim::RunSummary summary = simulation.run(silent);
  omp_set_num_threads(threads);
  if (summary.status != sim::RunStatus::completed)
    throw std::runtime_error("bench: the alternating run ended early (" + sim::to_string(summary.status) +
                             "): " + summary.diagnosis);
  if (block <= last_block)
    throw std::runtime_error("bench: the alternating run ended after " + std::to_string(block) + " blocks, before " +
                             std::to_string(last_block + 1));
  if (a.pair_ratios.size() != static_cast<std::size_t>(blocks_each))
    throw std::runtime_error("bench: the alternating run measured no cell work in some of its blocks");
  const double steps = static_cast<double>(blocks_each * block_steps);
  for (const sim::StageTiming& t : summary.stages) {
    if (t.phase == sim::Phase::observe) continue;
    const AlternatedStage s{t.name, 1e6 * one[t.name] / steps, 1e6 * many[t.name] / steps};
    a.stages.push_back(s);
    if (t.name == "fluid_step") {
      a.fluid_one_us = s.us_one;
      a.fluid_many_us = s.us_many;
    } else if (!grid_stage(t.name)) {
      a.cell_work_one_us += s.us_one;
      a.cell_work_many_us += s.us_many;
    }
  }
  return a;
}

}  // namespace erythro::app
