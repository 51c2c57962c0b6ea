// The simulation builds the cells only when the scene declares them, runs one
// immersed-boundary step per fluid step, and reports each cell's shape.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "geometry/shapes.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"
#include "simulation/fields_recorder.hpp"
#include "simulation/series_recorder.hpp"
#include "simulation/simulation.hpp"

namespace erythro::sim {
namespace {

// Ellipse with semi-axes a, b: D = (a − b)/(a + b) exactly for the smooth curve;
// a 256-gon inscribed in it is within 1e-3.
double taylor_deformation(const geometry::Polygon& p) {
  double D = 0.0, theta = 0.0;
  geometry::taylor_deformation(p, D, theta);
  return D;
}

TEST(CellDiagnostics, TaylorDeformationOfAnEllipse) {
  EXPECT_NEAR(taylor_deformation(geometry::ellipse(256, 6.0, 3.0)), 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(taylor_deformation(geometry::transformed(geometry::ellipse(256, 6.0, 3.0), 2.0, 0.7, 5.0, -3.0)),
              1.0 / 3.0, 1e-3);
  EXPECT_NEAR(taylor_deformation(geometry::circle(64, 4.0)), 0.0, 1e-12);
}

struct Collect : SeriesRecorder {
  int cell_frames = 0;
  void on_cells(long step, const membrane::ImmersedCells& cells) override {
    SeriesRecorder::on_cells(step, cells);
    ++cell_frames;
  }
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
  ASSERT_EQ(c.samples(), 3u);
  const auto& D = c.series("cell_0_taylor_deformation");
  EXPECT_NEAR(D[0], 0.0, 1e-12);
  EXPECT_GT(D[1], 0.0);
  EXPECT_GT(D[2], D[1]);
  EXPECT_LT(std::abs(c.series("cell_0_area_change").back()), 1e-3);
  EXPECT_FALSE(c.has("cell_1_taylor_deformation"));
}

// A cell at its rest shape in still fluid: its forces vanish, nothing moves
// (cells_max_marker_speed_um_s tracked after every step is 0). The same circle pre-stressed
// by cells.prestretch = 1.05 starts with the area change 1.05² − 1 over its rest shape,
// pulls inward (its markers move), and the FieldsRecorder keeps the initial and final
// fields in lattice units: the pressure inside exceeds the pressure far outside (Laplace).
TEST(CellSimulation, RestShapeStaysAndPrestretchPullsInward) {
  const std::vector<std::string> still = {"boundaries.bottom.velocity_um_s=[0.0, 0.0]",
                                          "boundaries.top.velocity_um_s=[0.0, 0.0]", "initial.type=\"rest\"",
                                          "run.steps=400", "output.extremes_interval_steps=1"};
  const std::string file = std::string(ERYTHRO_SCENES_DIR) + "/capsule_shear.toml";
  {
    const scene::Scene s = scene::load_scene(file, still);
    Simulation sim(s, scene::derive_lattice(s));
    SeriesRecorder c;
    EXPECT_EQ(sim.run(c).status, RunStatus::completed);
    EXPECT_EQ(c.series("cells_max_marker_speed_um_s").back(), 0.0);
  }
  std::vector<std::string> inflated = still;
  inflated.push_back("cells[0].prestretch=1.05");
  const scene::Scene s = scene::load_scene(file, inflated);
  Simulation sim(s, scene::derive_lattice(s));
  SeriesRecorder c;
  FieldsRecorder f;
  ObserverList both;
  both.add(c);
  both.add(f);
  EXPECT_EQ(sim.run(both).status, RunStatus::completed);
  EXPECT_NEAR(c.series("cell_0_area_change").front(), 1.05 * 1.05 - 1.0, 1e-12);
  EXPECT_GT(c.series("cells_max_marker_speed_um_s").back(), 0.0);
  ASSERT_EQ(f.snapshots().size(), 2u);  // steps 0 and 400
  EXPECT_EQ(f.last().step, 400);
  const Grid& g = sim.setup().grid;
  const auto& rho = f.last().moments.rho;
  EXPECT_GT(rho[g.index(g.nx / 2, g.ny / 2)], rho[g.index(0, 0)]);
}

// Interior viscosity 5× the plasma's by flood fill: the index field exists, the lattice's
// τ field holds τ_ex far outside and τ_in at the centre (eq 27), and the run completes.
TEST(CellSimulation, InteriorViscosityByFloodFill) {
  const scene::Scene s = scene::load_scene(std::string(ERYTHRO_SCENES_DIR) + "/capsule_shear.toml",
                                           {"run.steps=200", "membrane.interior_viscosity_cP=5.0",
                                            "output.fields_interval_steps=0"});
  const scene::LatticeSetup L = scene::derive_lattice(s);
  Simulation sim(s, L);
  ASSERT_NE(sim.index_field(), nullptr);
  const Grid& g = L.grid;
  const auto tau = sim.fluid()->tau_field();
  ASSERT_EQ(tau.size(), g.size());
  double cx = 0, cy = 0;
  geometry::centroid(sim.cells()->polygon(0), cx, cy);
  const double ratio = *s.membrane->interior_viscosity_cP / s.fluid.viscosity_cP;
  EXPECT_NEAR(tau[g.index(static_cast<int>(cx), static_cast<int>(cy))], 0.5 + ratio * (L.collision.tau - 0.5), 1e-12);
  EXPECT_NEAR(tau[g.index(0, g.ny / 2)], L.collision.tau, 1e-12);
  Collect c;
  EXPECT_EQ(sim.run(c).status, RunStatus::completed);
}

}  // namespace
}  // namespace erythro::sim

namespace erythro::sim {
namespace {

// Two capsules a little beyond the Morse range apart in still fluid, with aggregation:
// the simulation builds the aggregation and the pair attracts (their gap shrinks).
TEST(CellSimulation, AggregatingPairAttracts) {
  const std::string text =
      "[domain]\nsize_um = [20, 10]\nspacing_um = 0.25\n[time]\ntau = 1.0\n"
      "[fluid]\ndensity_kg_m3 = 1000\nviscosity_cP = 1.0\n"
      "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n[run]\nsteps = 400\n"
      "[output]\nfields_interval_steps = 0\n"
      "[membrane]\nshear_modulus_dyn_cm = 6e-3\n"
      "[aggregation]\npair_density_Pa = 500\n"
      "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [7.6, 5]\nmarkers = 64\n"
      "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [12.4, 5]\nmarkers = 64\n";
  const scene::Scene s = scene::parse_scene(text, "pair.toml");
  Simulation sim(s, scene::derive_lattice(s));
  ASSERT_NE(sim.cells(), nullptr);
  const auto gap = [&] {
    double cx0 = 0, cy0 = 0, cx1 = 0, cy1 = 0;
    geometry::centroid(sim.cells()->polygon(0), cx0, cy0);
    geometry::centroid(sim.cells()->polygon(1), cx1, cy1);
    return cx1 - cx0;
  };
  const double before = gap();
  Collect c;
  EXPECT_EQ(sim.run(c).status, RunStatus::completed);
  EXPECT_LT(gap(), before);
}

// The pair probe (simulation/probes/pair_probe.hpp) of a doublet across the periodic x side:
// cells centred at x = 2.3 and 17.7 µm are 4.6 µm apart through the side, so the line of
// centres points from cell 0 to the LEFT (180°, continued there while the cells attract),
// the gap is 4.6 − 2·2 = 0.6 µm (markers 0 and 32 of the 64-gons face each other), within
// r_c = 1.79 µm (not dissociated); no contact before the first step, contact on both cells
// after it; the pair's equivalent ellipse of two discs R apart 2d: √(1 + 4d²/R²).
TEST(CellSimulation, PairProbeMeasuresADoubletAcrossThePeriodicSide) {
  const std::string text =
      "[domain]\nsize_um = [20, 10]\nspacing_um = 0.25\n[time]\ntau = 1.0\n"
      "[fluid]\ndensity_kg_m3 = 1000\nviscosity_cP = 1.0\n"
      "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n[run]\nsteps = 400\n"
      "[output]\nfields_interval_steps = 0\ndiagnostics_interval_steps = 100\n"
      "[membrane]\nshear_modulus_dyn_cm = 6e-3\n"
      "[aggregation]\npair_density_Pa = 500\n"
      "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [2.3, 5]\nmarkers = 64\n"
      "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [17.7, 5]\nmarkers = 64\n";
  const scene::Scene s = scene::parse_scene(text, "pair.toml");
  Simulation sim(s, scene::derive_lattice(s));
  Collect c;
  EXPECT_EQ(sim.run(c).status, RunStatus::completed);
  ASSERT_EQ(c.samples(), 5u);
  const auto& angle = c.series("pair_angle_deg");
  EXPECT_NEAR(std::abs(angle[0]), 180.0, 1e-9);
  for (double a : angle) EXPECT_NEAR(a, angle[0], 1.0);  // continued, never wrapped to the other side
  EXPECT_NEAR(c.series("pair_separation_um")[0], 4.6, 1e-9);
  EXPECT_NEAR(c.series("pair_gap_um")[0], 0.6, 1e-9);
  EXPECT_EQ(c.series("pair_dissociated")[0], 0.0);
  EXPECT_EQ(c.series("cell_0_contact_area")[0], 0.0);
  EXPECT_GT(c.series("cell_0_contact_area").back(), 0.0);
  EXPECT_GT(c.series("cell_1_contact_area").back(), 0.0);
  EXPECT_LT(c.series("pair_separation_um").back(), 4.6);  // they attract
  EXPECT_NEAR(c.series("pair_aspect_ratio")[0], std::sqrt(1.0 + 4.0 * 2.3 * 2.3 / 4.0), 1e-2);
  EXPECT_TRUE(c.has("pair_contact_sigmoid_um"));
  EXPECT_TRUE(c.has("pair_contact_bow_um"));
}

// Cells farther apart than r_c: dissociated from the start; a stop rule on the series ends
// the run after_steps later; a scene with one cell (or without [aggregation]) has no pair series.
TEST(CellSimulation, PairProbeDissociationEndsARunByStopRule) {
  const std::string text =
      "[domain]\nsize_um = [20, 10]\nspacing_um = 0.25\n[time]\ntau = 1.0\n"
      "[fluid]\ndensity_kg_m3 = 1000\nviscosity_cP = 1.0\n"
      "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n[run]\nsteps = 400\n"
      "[output]\nfields_interval_steps = 0\ndiagnostics_interval_steps = 50\n"
      "[membrane]\nshear_modulus_dyn_cm = 6e-3\n"
      "[aggregation]\nsurface_energy_J_m2 = 0.0\n"
      "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [5, 5]\nmarkers = 64\n"
      "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [12, 5]\nmarkers = 64\n"
      "[[stop_when]]\nseries = \"pair_dissociated\"\nabove = 0.5\nafter_steps = 100\n";
  const scene::Scene s = scene::parse_scene(text, "pair.toml");
  Simulation sim(s, scene::derive_lattice(s));
  Collect c;
  const RunSummary r = sim.run(c);
  EXPECT_EQ(r.status, RunStatus::stopped);
  EXPECT_EQ(r.steps, 100);
  EXPECT_EQ(c.series("pair_dissociated")[0], 1.0);
  EXPECT_NEAR(c.series("pair_gap_um")[0], 3.0, 1e-9);

  const scene::Scene one = scene::load_scene(std::string(ERYTHRO_SCENES_DIR) + "/capsule_shear.toml",
                                             {"run.steps=10"});
  Simulation single(one, scene::derive_lattice(one));
  Collect d;
  single.run(d);
  EXPECT_FALSE(d.has("pair_angle_deg"));
}

}  // namespace
}  // namespace erythro::sim

namespace erythro::sim {
namespace {

#if defined(_OPENMP)
// Requirement (sim::CellPhysics::register_stages): on two threads the index field's rebuild and
// the force stage are one stage, and the rebuild runs beside the forces or before them (each on
// all threads), pinned or chosen by measurement; every arrangement gives the same bits as one
// thread, where it runs before them — the two are independent (positions read, τ and marker
// forces written). An aggregating pair with a flood-fill interior at 5× viscosity, 60 steps
// (k = 1: 59 rebuilds): marker positions and τ compared bit for bit (tolerance 0: the same
// operations in the same order).
TEST(CellSimulation, IndexFieldArrangementsGiveTheSameBits) {
  const std::string text =
      "[domain]\nsize_um = [20, 10]\nspacing_um = 0.25\n[time]\ntau = 1.0\n"
      "[fluid]\ndensity_kg_m3 = 1000\nviscosity_cP = 1.0\n"
      "[boundaries.bottom]\ntype = \"moving_wall\"\nvelocity_um_s = [-200.0, 0.0]\n"
      "[boundaries.top]\ntype = \"moving_wall\"\nvelocity_um_s = [200.0, 0.0]\n[run]\nsteps = 60\n"
      "[output]\nfields_interval_steps = 0\n"
      "[membrane]\nshear_modulus_dyn_cm = 6e-3\ninterior_viscosity_cP = 5.0\ninterior_method = \"flood_fill\"\n"
      "[aggregation]\npair_density_Pa = 500\n"
      "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [7.6, 5]\nmarkers = 64\n"
      "[[cells]]\nshape = \"circle\"\nradius_um = 2.0\ncenter_um = [12.4, 5]\nmarkers = 64\n";
  const scene::Scene s = scene::parse_scene(text, "pair.toml");
  using Arrangement = CellPhysics::IndexArrangement;
  struct Result {
    std::vector<double> x, y, tau;
    bool together = false;
    long beside = 0, before = 0;
    double index_s = 0.0, exposed_s = 0.0;
  };
  const int threads_before = omp_get_max_threads();
  auto run_with = [&](int threads, Arrangement arrangement) {
    omp_set_num_threads(threads);
    Simulation sim(s, scene::derive_lattice(s));
    sim.cell_physics()->set_index_arrangement(arrangement);
    Collect c;
    const RunSummary summary = sim.run(c);
    EXPECT_EQ(summary.status, RunStatus::completed);
    Result r;
    for (int cell = 0; cell < sim.cells()->cell_count(); ++cell) {
      r.x.insert(r.x.end(), sim.cells()->x(cell).begin(), sim.cells()->x(cell).end());
      r.y.insert(r.y.end(), sim.cells()->y(cell).begin(), sim.cells()->y(cell).end());
    }
    const auto tau = sim.fluid()->tau_field();
    r.tau.assign(tau.begin(), tau.end());
    r.together = sim.cell_physics()->index_with_forces();
    r.beside = sim.cell_physics()->rebuilds_beside_forces();
    r.before = sim.cell_physics()->rebuilds_before_forces();
    r.index_s = summary.index_field_time_s;
    r.exposed_s = summary.index_field_exposed_time_s;
    return r;
  };
  const Result one = run_with(1, Arrangement::measured);
  const Result beside = run_with(2, Arrangement::beside_forces);
  const Result before = run_with(2, Arrangement::before_forces);
  const Result measured = run_with(2, Arrangement::measured);
  omp_set_num_threads(threads_before);
  EXPECT_FALSE(one.together);
  EXPECT_EQ(one.beside, 0);
  EXPECT_EQ(one.before, 59);
  EXPECT_TRUE(beside.together);
  EXPECT_EQ(beside.beside, 59);
  EXPECT_EQ(before.before, 59);
  // Measured: each arrangement runs at least once (the first two rebuilds); the rest by their times.
  EXPECT_EQ(measured.beside + measured.before, 59);
  EXPECT_GE(measured.beside, 1);
  EXPECT_GE(measured.before, 1);
  for (const Result* r : {&beside, &before, &measured}) {
    EXPECT_EQ(one.x, r->x);
    EXPECT_EQ(one.y, r->y);
    EXPECT_EQ(one.tau, r->tau);
  }
  // Before the forces the step waits for all of the rebuild. (Beside them it waits for the part
  // that outlasts the forces, a difference of wall times that no bound holds on a shared host:
  // not asserted.)
  EXPECT_GT(one.index_s, 0.0);
  EXPECT_EQ(one.exposed_s, one.index_s);
  EXPECT_EQ(before.exposed_s, before.index_s);
}
#endif

}  // namespace
}  // namespace erythro::sim
