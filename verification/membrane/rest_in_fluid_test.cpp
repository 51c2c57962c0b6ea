// Case verification.membrane_rest_in_fluid (issue 4 §5).
//
// Requirement: a cell at its rest shape in still fluid stays at rest: the marker
// speed stays ≤ 1e-12 (lattice) over 10⁴ steps, for every kernel.
// Reference: zero internal force at the rest shape (membrane_energy.hpp) and zero
// initial flow imply u ≡ 0. A scene's cell is placed at its rest shape (the rest
// shape is the placed polygon, sim::CellPhysics), so its forces vanish exactly; only
// round-off could drive motion.
// Set-up: scene rest_in_fluid.toml: 32² periodic box, τ = 1, Evans–Fung biconcave cell
// (a = 9, 64 markers), rotated 0.3 rad, centred off the lattice symmetry at (15.3, 16.7);
// neo-Hookean E_s = 0.005, E_B = 0.02, k_A = 0.01 (lattice), rest curvature of the
// biconcave shape; overrides set the kernel. The speed is the series
// cells_max_marker_speed_um_s tracked after every step (output.extremes_interval_steps = 1),
// the displacement from the markers of the initial and final states (lattice units).
#include <gtest/gtest.h>

#include <cmath>

#include "common/case_support.hpp"
#include "common/lattice_inputs.hpp"
#include "common/scene_case.hpp"
#include "membrane_scene.hpp"

using namespace erythro;

TEST(RestInFluid, CellAtRestStaysAtRest) {
  constexpr const char* kScene = "verification/membrane/rest_in_fluid.toml";
  vv::Stopwatch total;
  io::ResultRecord record("verification.membrane_rest_in_fluid", "membrane");
  record.set_requirement(
      "A biconcave cell at its rest shape in still fluid (32^2 periodic box) keeps every marker speed <= 1e-12 "
      "and every displacement <= 1e-10 (lattice units) over 1e4 IB steps, for the four kernels.");
  record.set_reference("Rest shape feels zero force (membrane_energy.hpp), so u = 0 is the exact solution.");
  record.set_parameter("box", std::string("32 x 32 periodic, BGK tau = 1"));
  record.set_parameter("cell", std::string("Evans-Fung a = 9, 64 markers, rotated 0.3 rad, at (15.3, 16.7)"));
  record.set_parameter("moduli", std::string("neo-Hookean E_s = 0.005, E_B = 0.02, k_A = 0.01 (lattice)"));
  record.set_parameter("steps", 1e4);
  const membrane::MembraneModel model{{membrane::TensionLawType::neo_hookean, 0.005}, 0.02, 0.01};
  for (ib::KernelType k : ib::kAllKernels) {
    std::vector<std::string> set_up = vv::membrane_overrides(kScene, {}, k, model);
    set_up.push_back(vv::angle_override("cells[0].angle_deg", 0.3));
    const std::string name(ib::to_string(k));
    const vv::CellRun r = vv::run_cell_scene(vv::case_scene(kScene, set_up), record.case_name(), name);
    double max_disp = 0.0;
    for (std::size_t i = 0; i < r.final.size(); ++i)
      max_disp = std::max(max_disp, std::hypot(r.final.x[i] - r.initial.x[i], r.final.y[i] - r.initial.y[i]));
    const double max_speed = r.max_marker_speed;
    record.add_run({{"kernel", name}, {"steps", double(r.steps)}, {"max_marker_speed", max_speed},
                    {"max_displacement", max_disp}, {"wall_time_s", r.wall_time_s}},
                   r.scene_text);
    EXPECT_TRUE(record.add_metric({"speed " + name, "largest marker speed over 1e4 steps", "lattice", max_speed,
                                   1e-12, 0.0, io::Comparison::at_most,
                                   "issue 4 item 5's bound; forces from round-off (~1e-17) give speeds ~1e-16"}))
        << name << " " << max_speed;
    EXPECT_TRUE(record.add_metric({"displacement " + name, "largest marker displacement after 1e4 steps", "lattice",
                                   max_disp, 1e-10, 0.0, io::Comparison::at_most,
                                   "1e4 steps at <= 1e-14 speed; a drift mechanism would exceed it"}))
        << name << " " << max_disp;
    EXPECT_FALSE(r.diverged) << r.diagnosis;
  }
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
