#pragma once
// The runs of the membrane-in-fluid cases (verification.membrane_rest_in_fluid,
// laplace_pressure(_ci), membrane_stability): one cell in a periodic box of fluid at rest,
// a scene beside the cases (rest_in_fluid.toml, inflated_circle.toml) set by overrides and
// run as `erythro run` does (vv::run_case_scene). The set-ups are designed in lattice
// units; the scenes have h = 1 µm, so lengths are the same numbers, and the moduli and
// angles are written as the physical values whose conversion by the solver gives the
// lattice values exactly (common/lattice_inputs.hpp), so a run is the lattice set-up bit
// for bit.
#include <string>

#include "fluid/fluid_lattice.hpp"
#include "geometry/polygon.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace erythro::vv {

struct CellRun {
  scene::LatticeSetup setup;
  std::string scene_text;  // the scene as run (after overrides)
  bool diverged = false;   // health monitor, non-finite marker, or the perimeter guard
  std::string diagnosis;
  long steps = 0;
  double wall_time_s = 0.0;
  geometry::Polygon initial, final;  // cell 0 in lattice units (final: empty when diverged)
  fluid::Moments fields;             // final state, lattice units (keep_fields only)
  double max_marker_speed = 0.0;     // lattice, series cells_max_marker_speed_um_s at the end
};

// Runs `scene` into <results>/runs/<case_name>/<label> with the perimeter guard: the run
// counts as diverged when cell 0's perimeter is off by more than 5 % from its initial
// value after step 1, 101, 201, ... (a stage of the case's own; the criterion with which
// membrane/stability.hpp was calibrated), besides the solver's own health monitor.
CellRun run_cell_scene(const scene::Scene& scene, const std::string& case_name, const std::string& label,
                       bool keep_fields = false);

}  // namespace erythro::vv
