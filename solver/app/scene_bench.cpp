#include "app/scene_bench.hpp"

#include <omp.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "app/coupled_timing.hpp"
#include "app/thread_alternation.hpp"
#include "common/error.hpp"
#include "interior/index_field.hpp"
#include "io/result_record.hpp"
#include "scene/scene_parser.hpp"

namespace erythro::app {
namespace {

// The scene text with the bench's run length and output: `steps` steps, no field snapshots, the
// diagnostics and the health check once, at the last step, no stop conditions, no checkpoints.
// With cells: the index-field interval k the scene derives for its own run written out (a derived
// k depends on the speed the run reaches, so on its length). Without cells: also without the tables
// that make, move and fill them (the cells' haemoglobin), and with the time mapping's cell radius
// written out (it was the largest cell's), so that both derive the same lattice.
// k = 0: the scene has no index field (no interior viscosity), nothing to write out.
std::string bench_text(const toml::table& scene, long steps, bool cells, long k, double mapping_radius_um) {
  toml::table t = scene;
  if (toml::table* membrane = t["membrane"].as_table(); cells && membrane && k > 0)
    membrane->insert_or_assign("index_update_interval", k);
  t.insert_or_assign("run", toml::table{{"steps", steps}});
  t.insert_or_assign("output", toml::table{{"fields_interval_steps", 0}, {"diagnostics_interval_steps", steps}});
  toml::table monitor = t["monitor"].as_table() ? *t["monitor"].as_table() : toml::table{};
  monitor.insert_or_assign("interval_steps", steps);
  t.insert_or_assign("monitor", std::move(monitor));
  t.erase("stop_when");
  if (!cells) {
    for (const char* key : {"membrane", "cells", "cell_populations", "repulsion", "aggregation", "hemoglobin"})
      t.erase(key);
    if (toml::table* mapping = t["time_mapping"].as_table(); mapping && !mapping->contains("radius_um"))
      mapping->insert_or_assign("radius_um", mapping_radius_um);
  }
  std::ostringstream s;
  s << t;
  return s.str();
}

}  // namespace

void run_scene_bench(const std::string& path, const CoupledBenchOptions& o, io::ResultRecord& record) {
  // The scene as the user runs it (read and checked by load_scene: its errors name the file's own
  // keys) gives k and the cells.
  PreparedScene probe{scene::load_scene(path), {}};
  probe.setup = scene::derive_lattice(probe.scene);
  const toml::table scene = toml::parse(probe.scene.source_text, path);
  if (!probe.setup.has_fluid)
    throw InputError(path + ": `erythro bench --scene` times cells in a fluid; this scene has no fluid");
  if (!probe.setup.membrane || probe.setup.membrane->cells.empty())
    throw InputError(path + ": `erythro bench --scene` needs a scene with cells ([[cells]] or [[cell_populations]])");
  const bool index_field = probe.setup.membrane->indicator != interior::Method::indexless;
  const long k = index_field ? std::max(1L, probe.setup.membrane->index_update_interval) : 1;
  const int cells = static_cast<int>(probe.setup.membrane->cells.size());
  // --alternate-threads: one run, one thread and T threads in turn (thread_alternation.hpp), in
  // blocks of whole intervals; otherwise pairs of runs of `steps` steps with and without the cells.
  const int alternated = o.alternate_threads ? alternation_threads(o.threads) : 0;  // T
  const AlternationPlan plan = plan_alternation(k, o.steps);
  const long steps = o.alternate_threads ? plan.run_steps() : whole_interval_steps(k, o.steps);
  const double radius_um = probe.setup.time_mapping ? probe.setup.time_mapping->radius_m * 1e6 : 0.0;
  const std::string coupled_text = bench_text(scene, steps, true, index_field ? k : 0, radius_um);
  const PreparedScene coupled = prepare_scene(coupled_text, path);
  if (index_field && coupled.setup.membrane->index_update_interval != k)
    throw InputError(path + ": the bench's copy of the scene derives another index-field interval than " +
                     std::to_string(k));
  if (o.alternate_threads) {
    record.set_parameter("coupled_scene", path);
    print_alternation_heading(alternated, path);
    const auto& g = coupled.setup.grid;
    const AlternatedThreads a = alternate_threads(coupled, alternated, plan.block_steps, plan.blocks_each);
    report_alternation(record, a, cells, std::to_string(g.nx) + "x" + std::to_string(g.ny), k,
                       "scene_t" + std::to_string(alternated),
                       {{"cells", static_cast<double>(cells)},
                        {"grid_nx", static_cast<double>(g.nx)},
                        {"grid_ny", static_cast<double>(g.ny)}},
                       coupled_text);
    return;
  }
  const PreparedScene fluid_only =
      prepare_scene(bench_text(scene, steps, false, 0, radius_um), path + " (without its cells)");
  const auto& grid = coupled.setup.grid;
  if (fluid_only.setup.grid.nx != grid.nx || fluid_only.setup.grid.ny != grid.ny ||
      fluid_only.setup.collision.tau != coupled.setup.collision.tau)
    throw InputError(path + ": without its cells the scene derives another lattice (grid or tau): no fluid-only twin");
  record.set_parameter("coupled_scene", path);
  record.set_parameter("coupled_steps_per_run", static_cast<double>(steps));
  record.set_parameter("coupled_pairs", static_cast<double>(o.pairs));
  std::printf(
      "\ncoupled step of %s: %d cells on a %dx%d grid, %s; %ld steps per run, %d pair(s) (the scene without "
      "its cells, then with them), medians\n",
      path.c_str(), cells, grid.nx, grid.ny,
      index_field ? ("index field every " + std::to_string(k) + " steps").c_str() : "no index field", steps, o.pairs);
  std::printf("%5s %3s %12s %12s %14s %14s %9s\n", "cells", "thr", "fluid-only", "coupled", "fluid w/ cells",
              "extra/cell", "grid ovh");
  std::printf("%5s %3s %12s %12s %14s %14s %9s\n", "", "", "us/step", "us/step", "us/step", "us/(cell step)", "");
  std::vector<std::string> stage_lines;
  for (int threads : o.threads) {
    omp_set_num_threads(threads);
    const CoupledMeasurement m = measure_coupled(coupled, fluid_only, cells, steps, o.pairs);
    std::printf("%5d %3d %12.1f %12.1f %14.1f %14.2f %9.3f\n", cells, threads, m.fluid_only_us, m.coupled_us,
                m.fluid_with_cells_us, m.extra_per_cell_us, m.grid_overhead);
    std::fflush(stdout);
    const CoupledRow row{
        std::to_string(cells) + " cells, " + std::to_string(threads) + " thr, k = " + std::to_string(k),
        "scene_t" + std::to_string(threads),
        {{"cells", static_cast<double>(cells)},
         {"grid_nx", static_cast<double>(grid.nx)},
         {"grid_ny", static_cast<double>(grid.ny)},
         {"threads", static_cast<double>(threads)},
         {"index_update_interval", static_cast<double>(k)},
         {"steps", static_cast<double>(steps)}},
        coupled_text};
    stage_lines.push_back(record_coupled(record, row, m, cells));
  }
  print_stage_lines(stage_lines);
}

}  // namespace erythro::app
