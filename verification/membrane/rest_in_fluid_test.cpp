// Case verification.membrane_rest_in_fluid (issue 4 §5).
//
// Requirement: a cell at its rest shape in still fluid stays at rest: the marker
// speed stays ≤ 1e-12 (lattice) over 10⁴ steps, for every kernel.
// Reference: zero internal force at the rest shape (membrane_energy.hpp) and zero
// initial flow imply u ≡ 0; only round-off of the rest-shape recomputation after
// placement (~1e-16 relative in lengths and angles) can drive motion.
// Set-up: 32² periodic box, τ = 1, Evans–Fung biconcave cell (a = 9, 64 markers),
// rotated 0.3 rad, centred off the lattice symmetry at (15.3, 16.7); neo-Hookean
// E_s = 0.005, E_B = 0.02, k_A = 0.01 (lattice), rest curvature of the biconcave shape.
#include <gtest/gtest.h>

#include <cmath>

#include "common/case_support.hpp"
#include "geometry/shapes.hpp"
#include "immersed_setup.hpp"

using namespace erythro;
using namespace erythro::membrane;
using namespace erythro::geometry;

TEST(RestInFluid, CellAtRestStaysAtRest) {
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
  const Polygon shape = biconcave(64, 9.0);
  const RestShape rest = RestShape::from_polygon(shape);
  const MembraneModel model{{TensionLawType::neo_hookean, 0.005}, 0.02, 0.01};
  for (ib::KernelType k : ib::kAllKernels) {
    auto box = vv::make_periodic_box(32, 1.0, k);
    const Polygon placed = transformed(shape, 1.0, 0.3, 15.3, 16.7);
    box.cells->add_cell(placed, rest, model);
    double max_speed = 0.0;
    const auto r = vv::advance(box, 10000, [&](long) { max_speed = std::max(max_speed, box.cells->max_marker_speed()); });
    double max_disp = 0.0;
    for (std::size_t i = 0; i < placed.size(); ++i)
      max_disp = std::max(max_disp, std::hypot(box.cells->x(0)[i] - placed.x[i], box.cells->y(0)[i] - placed.y[i]));
    const std::string name(ib::to_string(k));
    record.add_run({{"kernel", name}, {"steps", double(r.steps_done)}, {"max_marker_speed", max_speed},
                    {"max_displacement", max_disp}, {"wall_time_s", r.wall_time_s}});
    EXPECT_TRUE(record.add_metric({"speed " + name, "largest marker speed over 1e4 steps", "lattice", max_speed,
                                   1e-12, 0.0, io::Comparison::at_most,
                                   "issue 4 item 5's bound; forces from round-off (~1e-17) give speeds ~1e-16"}))
        << name << " " << max_speed;
    EXPECT_TRUE(record.add_metric({"displacement " + name, "largest marker displacement after 1e4 steps", "lattice",
                                   max_disp, 1e-10, 0.0, io::Comparison::at_most,
                                   "1e4 steps at <= 1e-14 speed; a drift mechanism would exceed it"}))
        << name << " " << max_disp;
    EXPECT_FALSE(r.diverged);
  }
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}
