#include "membrane_scene.hpp"

#include <cmath>
#include <stdexcept>

#include "common/scene_case.hpp"
#include "geometry/polygon.hpp"
#include "simulation/fields_recorder.hpp"
#include "simulation/series_recorder.hpp"

namespace erythro::vv {

CellRun run_cell_scene(const scene::Scene& scene, const std::string& case_name, const std::string& label,
                       bool keep_fields) {
  sim::SeriesRecorder recorder(true);  // the cells' markers at every field output, lattice units
  sim::FieldsRecorder fields;
  CaseRunOptions options;
  options.observers.push_back(&recorder);
  if (keep_fields) options.observers.push_back(&fields);
  options.configure = [](sim::Simulation& s) {
    const membrane::ImmersedCells* cells = s.cells();
    const double p0 = geometry::perimeter(cells->polygon(0));
    s.add_stage(
        sim::Phase::observe, "perimeter_guard",
        [cells, p0](long) {
          const double p = geometry::perimeter(cells->polygon(0));
          if (!(std::abs(p / p0 - 1.0) < 0.05))
            throw std::domain_error("perimeter of cell 0 off by more than 5 % (" + std::to_string(p / p0 - 1.0) + ")");
        },
        100, 0);
  };
  const CaseRun run = run_case_scene(scene, case_name, label, options);
  CellRun r;
  r.setup = run.setup;
  r.scene_text = run.file.scene_text();
  r.diverged = !run.ok();
  r.diagnosis = run.summary.diagnosis;
  r.steps = run.summary.steps;
  r.wall_time_s = run.wall_time_s;
  const auto& snapshots = recorder.cell_snapshots();
  r.initial = snapshots.front().cells[0];
  if (r.diverged) return r;
  r.final = snapshots.back().cells[0];
  if (keep_fields) r.fields = fields.last().moments;
  r.max_marker_speed = recorder.series("cells_max_marker_speed_um_s").back() / (run.setup.scales.velocity_m_s() * 1e6);
  return r;
}

}  // namespace erythro::vv
