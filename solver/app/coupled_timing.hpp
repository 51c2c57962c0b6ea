#pragma once
// Timing a scene with cells beside the same grid without them: the measurement shared by the
// coupled-step sections of `erythro bench` (coupled_bench.hpp: shear boxes; scene_bench.hpp:
// a user's scene). Each run goes the product's way, scene text → scene::parse_scene →
// derive_lattice → sim::Simulation, without an output file, and the time loop's own stage
// timings (RunSummary::stages) give each stage's cost.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace erythro::io {
class ResultRecord;
}

namespace erythro::app {

// Steps of a timed run: a whole number m ≥ 4 of index-field intervals k, at least `at_least`,
// plus one (steps 0 … m k; the rebuilds before steps k, 2k, … m k are m, one per k steps; the
// one at set-up is not timed).
long whole_interval_steps(long k, long at_least);

// Whether a stage of the time loop scales with the grid rather than with the cells: the fluid
// step and the force field's reset (reported per step; the others per cell and step).
bool grid_stage(const std::string& name);

// Prints the stage lines of record_coupled under their heading.
void print_stage_lines(const std::vector<std::string>& lines);

// A scene ready to be simulated (parsed, seeded, derived once: seeding many cells takes a while).
struct PreparedScene {
  scene::Scene scene;
  scene::LatticeSetup setup;
};
PreparedScene prepare_scene(const std::string& text, const std::string& name);

// The work a coupled run did beside its time: what the cost per cell depends on besides the code
// (the same in every run of one scene: the runs are deterministic).
struct CoupledWork {
  long steps = 0;
  std::size_t markers = 0;
  std::size_t listed_pairs_swept = 0;  // the contact sweep's pairs over all steps (CellContacts)
  std::size_t pair_list_builds = 0;
  long index_field_rebuilds = 0;  // during the run (the one at set-up not counted)
};

// Medians over `pairs` pairs of runs (fluid only, then coupled, one after the other).
struct CoupledMeasurement {
  // Per step.
  double fluid_only_us = 0.0, coupled_us = 0.0, fluid_with_cells_us = 0.0;
  // (coupled − fluid-only step) / cells.
  double extra_per_cell_us = 0.0;
  // Fluid step with cells / fluid-only fluid step.
  double grid_overhead = 0.0;
  // Each stage per step, the mean over all coupled runs, in the loop's order.
  std::vector<std::pair<std::string, double>> stage_us;
  CoupledWork work;
};
CoupledMeasurement measure_coupled(const PreparedScene& coupled, const PreparedScene& fluid_only, int cells, long steps,
                                   int pairs);

// What identifies a measurement in the record and on the stage line.
struct CoupledRow {
  std::string label;                                    // e.g. "32 cells, 1 thr, k = 63"
  std::string tag;                                      // metric suffix, e.g. "32_t1"
  std::vector<std::pair<std::string, double>> columns;  // the run row's own columns (cells, threads, …)
  std::string scene_text;                               // the coupled run's scene, kept in the record's /scenes
};
// Adds the run row (with its scene and its work) and its two informative metrics to the record;
// returns the stage line (cell stages per cell and step, the grid stages per step) and, below it,
// the work line: pairs per marker and step, the rebuilds, and the cost per unit of work where a
// stage holds one kind of work (on one thread: the contact forces per pair, the index field per cell
// and rebuild; spreading and marker advection per marker).
std::string record_coupled(io::ResultRecord& record, const CoupledRow& row, const CoupledMeasurement& m, int cells);

}  // namespace erythro::app
