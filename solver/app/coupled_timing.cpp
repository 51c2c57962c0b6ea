#include "app/coupled_timing.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "app/bench_metric.hpp"
#include "io/result_record.hpp"
#include "scene/scene_parser.hpp"
#include "simulation/simulation.hpp"

namespace erythro::app {
namespace {

// Seconds of each stage of one run, without the observe phase (progress, observation).
struct Timed {
  std::vector<std::pair<std::string, double>> stages;  // in the loop's order
  double step_seconds = 0.0;                           // their sum / steps
  double fluid_step_seconds = 0.0;
  CoupledWork work;
};

Timed time_run(const PreparedScene& p, long steps) {
  sim::Simulation simulation(p.scene, p.setup);
  sim::RunObserver silent;  // every callback a no-op
  const sim::RunSummary summary = simulation.run(silent);
  if (summary.status != sim::RunStatus::completed)
    throw std::runtime_error("bench: the coupled-step run ended early (" + sim::to_string(summary.status) +
                             "): " + summary.diagnosis);
  Timed t;
  for (const sim::StageTiming& stage : summary.stages) {
    if (stage.phase == sim::Phase::observe) continue;
    t.stages.emplace_back(stage.name, stage.seconds);
    t.step_seconds += stage.seconds / static_cast<double>(steps);
    if (stage.name == "fluid_step") t.fluid_step_seconds = stage.seconds / static_cast<double>(steps);
  }
  t.work.steps = summary.steps;
  t.work.index_field_rebuilds = summary.index_field_rebuilds;
  if (const membrane::ImmersedCells* cells = simulation.cells()) t.work.markers = cells->marker_count();
  if (const sim::CellPhysics* physics = simulation.cell_physics(); physics && physics->contacts()) {
    t.work.listed_pairs_swept = physics->contacts()->listed_pairs_swept();
    t.work.pair_list_builds = physics->contacts()->pair_list_builds();
  }
  return t;
}

double median(std::vector<double> v) { return stats_of(std::move(v)).median; }

// The stage's µs per step, or nothing when the loop has no such stage (on two threads the forces
// and the index field are one stage, and neither single one is there).
std::optional<double> stage_us(const CoupledMeasurement& m, const std::string& name) {
  for (const auto& [stage, us] : m.stage_us)
    if (stage == name) return us;
  return std::nullopt;
}

// value with `digits` decimals.
std::string fixed(double value, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << std::fixed << value;
  return s.str();
}

// The work line of record_coupled, its figures also put into the run row.
std::string work_line(const CoupledMeasurement& m, int cells, std::map<std::string, io::Value>& run) {
  const CoupledWork& w = m.work;
  const double steps = static_cast<double>(std::max(w.steps, 1L));
  const double markers = static_cast<double>(std::max<std::size_t>(w.markers, 1));
  std::string line = "    work: " + std::to_string(w.markers) + " markers";
  auto put = [&](const std::string& key, double value, const std::string& text) {
    run[key] = value;
    line += ", " + text;
  };
  if (w.listed_pairs_swept > 0) {
    const double pairs_per_step = static_cast<double>(w.listed_pairs_swept) / steps;
    put("listed_pairs_per_marker_step", pairs_per_step / markers,
        fixed(pairs_per_step / markers, 2) + " listed pairs per marker");
    put("pair_list_builds", static_cast<double>(w.pair_list_builds),
        std::to_string(w.pair_list_builds) + " list builds");
    if (const auto us = stage_us(m, "contact_forces"))
      put("contact_forces_ns_per_pair", 1e3 * *us / pairs_per_step,
          "contact " + fixed(1e3 * *us / pairs_per_step, 2) + " ns/pair");
  }
  if (w.index_field_rebuilds > 0) {
    put("index_field_rebuilds", static_cast<double>(w.index_field_rebuilds),
        std::to_string(w.index_field_rebuilds) + " index-field rebuilds");
    if (const auto us = stage_us(m, "index_field")) {
      const double per = *us * steps / static_cast<double>(w.index_field_rebuilds) / cells;
      put("index_field_us_per_cell_rebuild", per, "index field " + fixed(per, 2) + " us/(cell rebuild)");
    }
  }
  for (const std::string name : {"spreading", "marker_advection"})
    if (const auto us = stage_us(m, name))
      put(name + "_ns_per_marker", 1e3 * *us / markers, name + " " + fixed(1e3 * *us / markers, 1) + " ns/marker");
  return line;
}

}  // namespace

bool grid_stage(const std::string& name) { return name == "fluid_step" || name == "force_field_reset"; }

long whole_interval_steps(long k, long at_least) { return std::max(4 * k, (at_least + k - 1) / k * k) + 1; }

void print_stage_lines(const std::vector<std::string>& lines) {
  std::printf(
      "stages (mean over all runs; cell stages per cell and step, fluid_step and force_field_reset per step):\n");
  for (const std::string& l : lines) std::printf("%s\n", l.c_str());
}

PreparedScene prepare_scene(const std::string& text, const std::string& name) {
  scene::Scene s = scene::parse_scene(text, name);
  scene::LatticeSetup setup = scene::derive_lattice(s);
  return {std::move(s), std::move(setup)};
}

CoupledMeasurement measure_coupled(const PreparedScene& coupled, const PreparedScene& fluid_only, int cells, long steps,
                                   int pairs) {
  std::vector<double> fluid_only_us, coupled_us, with_cells_us, extra, overhead;
  std::map<std::string, double> stage_seconds;
  CoupledMeasurement m;
  for (int pair = 0; pair < pairs; ++pair) {
    const Timed f = time_run(fluid_only, steps);
    const Timed c = time_run(coupled, steps);
    fluid_only_us.push_back(1e6 * f.step_seconds);
    coupled_us.push_back(1e6 * c.step_seconds);
    with_cells_us.push_back(1e6 * c.fluid_step_seconds);
    extra.push_back(1e6 * (c.step_seconds - f.step_seconds) / cells);
    overhead.push_back(c.fluid_step_seconds / f.fluid_step_seconds);
    m.work = c.work;
    for (const auto& [name, seconds] : c.stages) {
      if (pair == 0) m.stage_us.emplace_back(name, 0.0);
      stage_seconds[name] += seconds;
    }
  }
  const double all_steps = static_cast<double>(steps) * pairs;
  for (auto& [name, us] : m.stage_us) us = 1e6 * stage_seconds[name] / all_steps;
  m.fluid_only_us = median(fluid_only_us);
  m.coupled_us = median(coupled_us);
  m.fluid_with_cells_us = median(with_cells_us);
  m.extra_per_cell_us = median(extra);
  m.grid_overhead = median(overhead);
  return m;
}

std::string record_coupled(io::ResultRecord& record, const CoupledRow& row, const CoupledMeasurement& m, int cells) {
  std::ostringstream line;
  line.precision(3);
  line << std::fixed << "  " << row.label << ":";
  std::map<std::string, io::Value> run{
      {"kind", std::string("coupled step")},           {"fluid_only_us_per_step", m.fluid_only_us},
      {"coupled_us_per_step", m.coupled_us},           {"fluid_step_with_cells_us_per_step", m.fluid_with_cells_us},
      {"extra_us_per_cell_step", m.extra_per_cell_us}, {"grid_overhead", m.grid_overhead}};
  for (const auto& [name, value] : row.columns) run[name] = value;
  for (const auto& [name, us] : m.stage_us) {
    // Cell stages per cell and step; the fluid step and the force field's reset per step
    // (they scale with the grid).
    const bool per_step = grid_stage(name);
    const double value = per_step ? us : us / cells;
    line << " " << name << " " << value << (per_step ? " us" : " us/cell");
    run[name + (per_step ? "_us_per_step" : "_us_per_cell_step")] = value;
  }
  line << "\n" << work_line(m, cells, run);
  record.add_run(run, row.scene_text);
  record.add_metric(informative("coupled_extra_us_per_cell_step_" + row.tag,
                                "(coupled step - fluid-only step of the same grid) / cells, median over pairs", "us",
                                m.extra_per_cell_us));
  record.add_metric(informative("coupled_grid_overhead_" + row.tag,
                                "fluid step with cells (forces, interior tau field) / fluid-only fluid step", "",
                                m.grid_overhead));
  return line.str();
}

}  // namespace erythro::app
