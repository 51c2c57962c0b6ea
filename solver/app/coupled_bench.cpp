// The coupled-step section of `erythro bench` (coupled_bench.hpp). For each cell count N a
// square shear box is sized so that N biconcave cells cover φ = 0.3 of it (or, with --grid, every
// count has the same box, for the overhead that scales with the grid, not with the cells), with the fluid,
// membrane and shear of scenes/rbc_suspension_shear.toml. The scene goes the product's way
// (scene text → scene::parse_scene, which seeds the cells → derive_lattice → sim::Simulation,
// as io::run_scene, without an output file), and the time loop's own stage timings
// (RunSummary::stages) give the cost of each stage (coupled_timing.hpp). Beside it, one after the other in the
// same process, the same grid without cells (fluid only): the extra cost per cell and step
// is (coupled step − fluid-only step)/N, and the grid-proportional overhead of the cells is
// the fluid step with cells (forces, per-node τ of the interior) over the fluid-only one.
// --write-scenes writes the boxes' scenes instead, for timing against another build by whole
// processes (write_box_scenes, ci/bench-against.sh).
#include "app/coupled_bench.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "aggregation/morse_units.hpp"
#include "app/coupled_timing.hpp"
#include "app/thread_alternation.hpp"
#include "common/error.hpp"
#include "geometry/polygon.hpp"
#include "io/atomic_file.hpp"
#include "io/result_record.hpp"
#include "scene/cell_seeding.hpp"
#include "scene/units.hpp"

namespace erythro::app {
namespace {

// The suspension of scenes/rbc_suspension_shear.toml (the dimensionless groups of
// validation/rbc/rbc.toml at h = 0.15 µm).
constexpr double kSpacingUm = 0.15;
constexpr double kShearRatePerS = 3828.8986444262964;
constexpr double kAreaFraction = 0.3;
constexpr double kRadiusUm = 3.91;
constexpr int kMarkers = 184;
constexpr double kDeStar = 5.0;  // the aggregation of --aggregation (thesis ch. IV)

// The area of one cell's marker polygon.
double cell_area_um2() {
  scene::CellSpec c;
  c.shape = "biconcave";
  c.radius_um = kRadiusUm;
  c.markers = kMarkers;
  return std::abs(geometry::signed_area(scene::cell_outline_um(c, kSpacingUm)));
}

// A shear box of nx × ny nodes (x along the walls).
struct Box {
  int nx = 0, ny = 0;
  std::string label() const { return std::to_string(nx) + "x" + std::to_string(ny); }
  double area_fraction(int cells) const { return cells * cell_area_um2() / (nx * kSpacingUm * ny * kSpacingUm); }
};

// The box of `cells` cells: --grid, or the square box where they cover kAreaFraction.
Box box_for(int cells, const CoupledBenchOptions& o) {
  if (!o.grid.empty()) return {o.grid[0], o.grid[1]};
  const int n = static_cast<int>(std::ceil(std::sqrt(cells * cell_area_um2() / kAreaFraction) / kSpacingUm));
  return {n, n};
}

// The box without cells: its fluid, walls, shear and step count; health checked and
// diagnostics sampled once, at the last step. The wall speed is γ̇ ny h / 2.
std::string box_text(const Box& b, long steps) {
  const double wall_speed = 0.5 * kShearRatePerS * (b.ny * kSpacingUm);
  std::ostringstream s;
  s.precision(17);
  s << "[domain]\nsize_um = [" << b.nx * kSpacingUm << ", " << b.ny * kSpacingUm << "]\nspacing_um = " << kSpacingUm
    << "\n"
    << "[time]\ntau = 1.0\n[fluid]\ndensity_kg_m3 = 1025.0\nviscosity_cP = 1.2\n"
    << "[boundaries.bottom]\ntype = \"moving_wall\"\nvelocity_um_s = [" << -wall_speed << ", 0.0]\n"
    << "[boundaries.top]\ntype = \"moving_wall\"\nvelocity_um_s = [" << wall_speed << ", 0.0]\n"
    << "[initial]\ntype = \"shear\"\n[run]\nsteps = " << steps << "\n"
    << "[monitor]\ninterval_steps = " << steps << "\n"
    << "[output]\nfields_interval_steps = 0\ndiagnostics_interval_steps = " << steps << "\n";
  return s.str();
}

// The cells' membrane and interior, the index field rebuilt every `index_interval` steps.
std::string membrane_text(long index_interval) {
  return "[membrane]\nlaw = \"neo_hookean\"\nshear_modulus_dyn_cm = 0.22973391866557774\n"
         "bending_modulus_dyn_cm = 1.3784035119934664e-10\narea_modulus_Pa = 5875.547791958511\n"
         "kernel = \"cosine4\"\ninterior_viscosity_cP = 6.0\ninterior_method = \"flood_fill\"\n"
         "index_update_interval = " +
         std::to_string(index_interval) + "\n";
}

// The scene of the box with `cells` cells (0: the fluid alone, without [membrane]).
std::string scene_text(const Box& b, int cells, long steps, const CoupledBenchOptions& o, long index_interval) {
  std::ostringstream s;
  s.precision(17);
  s << box_text(b, steps);
  if (cells > 0)
    s << membrane_text(index_interval) << "[[cell_populations]]\nshape = \"biconcave\"\nradius_um = " << kRadiusUm
      << "\nmarkers = " << kMarkers << "\ncount = " << cells << "\nseed = 1\n"
      << "[repulsion]\npressure_Pa = 1.0\n";
  if (cells > 0 && o.aggregation)  // thesis ch. IV
    s << "[aggregation]\nde_star = " << std::fixed << std::setprecision(1) << kDeStar << "\n";
  return s.str();
}

// The cells the population of scene_text placed, one [[cells]] entry each (centre and angle as the
// seeding drew them), the index field every step, no repulsion, aggregation by its surface energy:
// the same box for a binary from before [[cell_populations]], [repulsion] and `de_star` (efaf88f,
// issue 18's reference), which builds each cell's outline from the same centre and angle.
std::string explicit_cells_text(const Box& b, long steps, const scene::Scene& seeded, const CoupledBenchOptions& o) {
  std::ostringstream s;
  s.precision(17);
  s << box_text(b, steps) << membrane_text(1);
  for (const scene::CellSpec& c : seeded.cells)
    s << "[[cells]]\nshape = \"" << c.shape << "\"\nradius_um = " << c.radius_um << "\nmarkers = " << c.markers
      << "\ncenter_um = [" << c.center_um[0] << ", " << c.center_um[1] << "]\nangle_deg = " << c.angle_deg << "\n";
  if (o.aggregation)
    s << "[aggregation]\nsurface_energy_J_m2 = " << aggregation::surface_energy_for_de_star(kDeStar) << "\n";
  return s.str();
}

std::string scene_name(int cells) { return "bench_coupled_" + std::to_string(cells) + ".toml"; }

// The index-field interval of a box: --index-interval, or the largest k the validation supports
// at the box's wall speed (the fluid-only scene: k = 1).
long box_interval(const Box& b, const CoupledBenchOptions& o) {
  if (o.index_interval > 0) return o.index_interval;
  return scene::supported_index_interval(
      prepare_scene(scene_text(b, 0, 10, o, 1), scene_name(0)).setup.boundaries.top.ux);
}

// --alternate-threads: each box once, one thread and T threads in turn (thread_alternation.hpp).
void run_alternating(const CoupledBenchOptions& o, io::ResultRecord& record) {
  const int threads = alternation_threads(o.threads);
  print_alternation_heading(threads, std::string("the shear boxes above, ") +
                                         (o.aggregation ? "repulsion and Morse aggregation (De* = 5)" : "repulsion"));
  for (int cells : o.cells) {
    const Box b = box_for(cells, o);
    const long k = box_interval(b, o);
    const AlternationPlan plan = plan_alternation(k, o.steps);
    const std::string text = scene_text(b, cells, plan.run_steps(), o, k);
    const AlternatedThreads a =
        alternate_threads(prepare_scene(text, scene_name(cells)), threads, plan.block_steps, plan.blocks_each);
    report_alternation(record, a, cells, b.label(), k, std::to_string(cells) + "_t" + std::to_string(threads),
                       {{"cells", static_cast<double>(cells)},
                        {"grid_nx", static_cast<double>(b.nx)},
                        {"grid_ny", static_cast<double>(b.ny)}},
                       text);
  }
}

}  // namespace

void write_box_scenes(const CoupledBenchOptions& o, const std::string& dir) {
  io::ensure_writable_directory(dir);
  std::ostringstream boxes;
  boxes << "cells\tgrid_nx\tgrid_ny\tindex_update_interval\tproduct\tsame\tfluid\n";
  for (int cells : o.cells) {
    const Box b = box_for(cells, o);
    const long k = box_interval(b, o);
    const std::string product = scene_text(b, cells, o.steps, o, k);
    const std::string same = explicit_cells_text(b, o.steps, prepare_scene(product, scene_name(cells)).scene, o);
    boxes << cells << "\t" << b.nx << "\t" << b.ny << "\t" << k;
    for (const auto& [kind, text] :
         {std::pair{"product", product}, {"same", same}, {"fluid", scene_text(b, 0, o.steps, o, 1)}}) {
      const std::string name = "box" + std::to_string(cells) + "_" + kind + ".toml";
      io::write_text_atomically(dir + "/" + name, text);
      boxes << "\t" << name;
    }
    boxes << "\n";
  }
  io::write_text_atomically(dir + "/boxes.tsv", boxes.str());
  std::printf("scenes of %zu box(es) and their list: %s/boxes.tsv\n", o.cells.size(), dir.c_str());
}

void run_coupled_bench(const CoupledBenchOptions& o, io::ResultRecord& record) {
  if (o.alternate_threads) return run_alternating(o, record);
  record.set_parameter("coupled_scene",
                       std::string("scenes/rbc_suspension_shear.toml, ") +
                           (o.grid.empty() ? "box sized per cell count" : "one box for every cell count (--grid)"));
  if (o.grid.empty()) record.set_parameter("coupled_area_fraction", kAreaFraction);
  record.set_parameter("coupled_markers_per_cell", static_cast<double>(kMarkers));
  record.set_parameter("coupled_steps_per_run", static_cast<double>(o.steps));
  record.set_parameter("coupled_pairs", static_cast<double>(o.pairs));
  record.set_parameter("coupled_aggregation", std::string(o.aggregation ? "Morse, De* = 5" : "off"));
  record.set_parameter("coupled_index_interval",
                       o.index_interval > 0 ? std::to_string(o.index_interval)
                                            : std::string("per box: the largest k with k U <= 0.1 h"));
  char square_boxes[64];
  std::snprintf(square_boxes, sizeof square_boxes, "at area fraction %.2f in a shear box", kAreaFraction);
  const std::string boxes = o.grid.empty() ? square_boxes : "in one shear box of " + box_for(0, o).label() + " nodes";
  std::printf(
      "\ncoupled step: biconcave cells (%d markers, flood-fill interior 6 cP, index field every k steps) %s, "
      "h = %.2f um, repulsion%s; at least %ld steps per run (a multiple of k, plus one), %d pair(s) (fluid "
      "only, then coupled), medians\n",
      kMarkers, boxes.c_str(), kSpacingUm, o.aggregation ? " and Morse aggregation (De* = 5)" : "", o.steps, o.pairs);
  std::printf("%5s %9s %3s %6s %4s %12s %12s %14s %14s %9s\n", "cells", "grid", "thr", "phi", "k", "fluid-only",
              "coupled", "fluid w/ cells", "extra/cell", "grid ovh");
  std::printf("%5s %9s %3s %6s %4s %12s %12s %14s %14s %9s\n", "", "", "", "", "", "us/step", "us/step", "us/step",
              "us/(cell step)", "");
  std::vector<std::string> stage_lines;
  for (int cells : o.cells) {
    const Box b = box_for(cells, o);
    // The interval from the wall speed of this box (the fluid-only scene has no cells: k = 1).
    const long k = box_interval(b, o);
    const long steps = whole_interval_steps(k, o.steps);
    const std::string coupled_text = scene_text(b, cells, steps, o, k);
    const PreparedScene coupled = prepare_scene(coupled_text, scene_name(cells));
    const PreparedScene fluid_only = prepare_scene(scene_text(b, 0, steps, o, 1), scene_name(0));
    const double phi = b.area_fraction(cells);
    for (int threads : o.threads) {
      omp_set_num_threads(threads);
      const CoupledMeasurement m = measure_coupled(coupled, fluid_only, cells, steps, o.pairs);
      std::printf("%5d %9s %3d %6.3f %4ld %12.1f %12.1f %14.1f %14.2f %9.3f\n", cells, b.label().c_str(), threads, phi,
                  k, m.fluid_only_us, m.coupled_us, m.fluid_with_cells_us, m.extra_per_cell_us, m.grid_overhead);
      std::fflush(stdout);
      const CoupledRow row{
          std::to_string(cells) + " cells, " + std::to_string(threads) + " thr, k = " + std::to_string(k),
          std::to_string(cells) + "_t" + std::to_string(threads),
          {{"cells", static_cast<double>(cells)},
           {"grid_nx", static_cast<double>(b.nx)},
           {"grid_ny", static_cast<double>(b.ny)},
           {"threads", static_cast<double>(threads)},
           {"area_fraction", phi},
           {"index_update_interval", static_cast<double>(k)},
           {"steps", static_cast<double>(steps)},
           {"aggregation", o.aggregation ? 1.0 : 0.0}},
          coupled_text};
      stage_lines.push_back(record_coupled(record, row, m, cells));
    }
  }
  print_stage_lines(stage_lines);
}

}  // namespace erythro::app
