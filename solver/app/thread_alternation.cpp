#include "app/thread_alternation.hpp"

#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "app/bench_metric.hpp"
#include "common/error.hpp"
#include "io/result_record.hpp"
#include "simulation/simulation.hpp"

namespace erythro::app {
namespace {

// Each stage's seconds so far, without the observation phase.
std::map<std::string, double> seconds_so_far(const sim::TimeLoop& loop) {
  std::map<std::string, double> s;
  for (const sim::StageTiming& t : loop.timings())
    if (t.phase != sim::Phase::observe) s[t.name] = t.seconds;
  return s;
}

constexpr long kBlockSteps = 60;

}  // namespace

AlternationPlan plan_alternation(long k, long steps) {
  AlternationPlan p;
  p.block_steps = k * std::max(1L, (kBlockSteps + k / 2) / k);
  p.blocks_each = std::max(3L, (steps + 2 * p.block_steps - 1) / (2 * p.block_steps));
  return p;
}

int alternation_threads(const std::vector<int>& threads) {
  const int T = threads.empty() ? 0 : *std::max_element(threads.begin(), threads.end());
  if (T < 2) throw InputError("bench: --alternate-threads needs a count of 2 or more in --threads");
  return T;
}

void print_alternation_heading(int threads, const std::string& what) {
  std::printf(
      "\ncoupled step, one thread against %d in one run: %s; blocks of whole index-field intervals, one thread "
      "and %d in turn after a warm-up block; cell work = every stage but the fluid step and the force field's "
      "reset, us per cell and step\n",
      threads, what.c_str(), threads);
  std::printf("%5s %9s %4s %6s %7s %12s %12s %8s %18s %11s\n", "cells", "grid", "k", "block", "blocks", "cells 1 thr",
              "cells T thr", "ratio", "pairs: median, range", "fluid ratio");
}

void report_alternation(io::ResultRecord& record, const AlternatedThreads& a, int cells, const std::string& grid,
                        long k, const std::string& tag, const std::vector<std::pair<std::string, double>>& columns,
                        const std::string& scene_text) {
  const Stats pairs = stats_of(a.pair_ratios);
  const double ratio = a.cell_work_one_us / a.cell_work_many_us, fluid = a.fluid_one_us / a.fluid_many_us;
  std::printf("%5d %9s %4ld %6ld %7ld %12.2f %12.2f %8.3f %6.2f %5.2f-%-5.2f %11.3f\n", cells, grid.c_str(), k,
              a.block_steps, a.blocks_each, a.cell_work_one_us / cells, a.cell_work_many_us / cells, ratio,
              pairs.median, pairs.min, pairs.max, fluid);
  for (const AlternatedStage& st : a.stages)
    std::printf("      %-24s %10.3f %10.3f %8.3f%s\n", st.name.c_str(), st.us_one / cells, st.us_many / cells,
                st.us_many > 0.0 ? st.us_one / st.us_many : 0.0, grid_stage(st.name) ? "  (grid, us per cell)" : "");
  std::fflush(stdout);
  std::map<std::string, io::Value> run{{"kind", std::string("threads alternated")}};
  for (const auto& [name, value] : columns) run[name] = value;
  run["threads"] = static_cast<double>(a.threads);
  run["index_update_interval"] = static_cast<double>(k);
  run["block_steps"] = static_cast<double>(a.block_steps);
  run["blocks_each"] = static_cast<double>(a.blocks_each);
  run["cell_work_us_per_cell_step_t1"] = a.cell_work_one_us / cells;
  run["cell_work_us_per_cell_step_tT"] = a.cell_work_many_us / cells;
  run["cell_work_ratio"] = ratio;
  run["cell_work_ratio_pair_median"] = pairs.median;
  run["cell_work_ratio_pair_min"] = pairs.min;
  run["cell_work_ratio_pair_max"] = pairs.max;
  run["fluid_step_ratio"] = fluid;
  for (const AlternatedStage& st : a.stages) {
    run[st.name + "_us_per_step_t1"] = st.us_one;
    run[st.name + "_us_per_step_tT"] = st.us_many;
  }
  record.add_run(run, scene_text);
  record.add_metric(informative("cell_work_speedup_" + tag,
                                "cell work on one thread / on T threads, blocks of one run in turn", "", ratio));
}

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
  sim::RunObserver silent;  // every callback a no-op
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
