// The simulation builds the cells only when the scene declares them, runs one
// immersed-boundary step per fluid step, and reports each cell's shape.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "membrane/shapes.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"
#include "simulation/simulation.hpp"

namespace erythro::sim {
namespace {

// Ellipse with semi-axes a, b: D = (a − b)/(a + b) exactly for the smooth curve;
// a 256-gon inscribed in it is within 1e-3.
TEST(CellDiagnostics, TaylorDeformationOfAnEllipse) {
  EXPECT_NEAR(taylor_deformation(membrane::ellipse(256, 6.0, 3.0)), 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(taylor_deformation(membrane::transformed(membrane::ellipse(256, 6.0, 3.0), 2.0, 0.7, 5.0, -3.0)),
              1.0 / 3.0, 1e-3);
  EXPECT_NEAR(taylor_deformation(membrane::circle(64, 4.0)), 0.0, 1e-12);
}

struct Collect : RunObserver {
  std::vector<CellDiagnostics> samples;
  int cell_frames = 0;
  void on_cell_diagnostics(const CellDiagnostics& d) override { samples.push_back(d); }
  void on_cells(long, const membrane::ImmersedCells&) override { ++cell_frames; }
};

TEST(CellSimulation, FluidOnlySceneHasNoCells) {
  const scene::Scene s = scene::load_scene(std::string(ERYTHRO_SCENES_DIR) + "/couette.toml", {"run.steps=10"});
  Simulation sim(s, scene::derive_lattice(s));
  EXPECT_EQ(sim.cells(), nullptr);
}

// 2000 steps of the example capsule: strain γ̇t ≈ 0.07, so the capsule has started to
// elongate (D > 0 and growing), keeps its area (penalty-free neo-Hookean ring in a
// divergence-free flow: |A/A0 − 1| stays ~1e-5, bound 1e-3) and is written at each field output.
TEST(CellSimulation, CapsuleDeformsInShear) {
  const scene::Scene s = scene::load_scene(std::string(ERYTHRO_SCENES_DIR) + "/capsule_shear.toml",
                                           {"run.steps=2000", "output.fields_interval_steps=1000",
                                            "output.diagnostics_interval_steps=1000"});
  Simulation sim(s, scene::derive_lattice(s));
  ASSERT_NE(sim.cells(), nullptr);
  EXPECT_EQ(sim.cells()->cell_count(), 1);
  Collect c;
  const RunSummary r = sim.run(c);
  EXPECT_EQ(r.status, RunStatus::completed);
  EXPECT_EQ(r.steps, 2000);
  EXPECT_EQ(c.cell_frames, 3);  // steps 0, 1000, 2000
  ASSERT_EQ(c.samples.size(), 3u);
  ASSERT_EQ(c.samples.back().taylor_deformation.size(), 1u);
  EXPECT_NEAR(c.samples.front().taylor_deformation[0], 0.0, 1e-12);
  EXPECT_GT(c.samples[1].taylor_deformation[0], 0.0);
  EXPECT_GT(c.samples[2].taylor_deformation[0], c.samples[1].taylor_deformation[0]);
  EXPECT_LT(std::abs(c.samples.back().area_change[0]), 1e-3);
}

}  // namespace
}  // namespace erythro::sim
