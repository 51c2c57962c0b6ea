// [transport], [[species]], [hemoglobin]: parsing, conversion to transport lattice
// units, the refusals, and runs through the simulation (still medium: no fluid is
// built; sub-cycling: the transport advances every k fluid steps).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "input_error_matchers.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"
#include "simulation/series_recorder.hpp"
#include "simulation/simulation.hpp"
#include "simulation/transport_physics.hpp"
#include "transport/hb_kinetics.hpp"
#include "transport/reactions.hpp"

namespace erythro::sim {
namespace {

using scene::testing::error_of;

// 10 µm box, h = 0.5 µm (20 × 20 nodes), walls; O2 with D = 2800 µm²/s, Δt_T = 1e-5 s
// → D_lat = 2800e-5 / 0.25 = 0.112; a biconcave cell (a = 3 µm) starting at 100 Torr.
std::string still_scene(const std::string& side = "zero_flux", const std::string& extra = "") {
  std::string s =
      "[domain]\nsize_um = [10, 10]\nspacing_um = 0.5\n"
      "[boundaries.left]\ntype = \"wall\"\n[boundaries.right]\ntype = \"wall\"\n"
      "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n"
      "[transport]\ncoupling = \"none\"\ntime_step_s = 1e-5\n"
      "[[species]]\nname = \"O2\"\ndiffusivity_um2_s = 2800\ncell_diffusivity_um2_s = 950\ninitial_uM = 20\n"
      "cell_initial_uM = 130\n";
  for (const char* k : {"left", "right", "bottom", "top"}) {
    s += std::string(k) + " = \"" + side + "\"\n";
    if (side == "fixed_concentration") s += std::string(k) + "_value = 20\n";
  }
  return s + extra +
         "[hemoglobin]\nspecies = \"O2\"\n"
         "[[cells]]\nshape = \"biconcave\"\nradius_um = 3.0\ncenter_um = [5, 5]\nmarkers = 40\n"
         "[run]\nsteps = 400\n[output]\ndiagnostics_interval_steps = 50\n";
}

scene::LatticeSetup derive(const std::string& text) {
  return scene::derive_lattice(scene::parse_scene(text, "t.toml"));
}

TEST(TransportScene, StillMediumBuildsNoFluid) {
  const scene::LatticeSetup L = derive(still_scene("fixed_concentration"));
  EXPECT_FALSE(L.has_fluid);
  ASSERT_TRUE(L.transport.has_value());
  EXPECT_EQ(L.transport->coupling, "none");
  EXPECT_DOUBLE_EQ(L.scales.time_s, 1e-5);
  EXPECT_EQ(L.total_steps, 400);
  ASSERT_EQ(L.transport->species.size(), 1u);
  EXPECT_NEAR(L.transport->species[0].diffusivity, 0.112, 1e-12);
  EXPECT_NEAR(L.transport->species[0].cell_diffusivity, 0.038, 1e-12);
  EXPECT_EQ(L.transport->species[0].boundaries.left.kind, transport::SideKind::fixed_concentration);
  EXPECT_DOUBLE_EQ(L.transport->species[0].boundaries.top.value, 20.0);
  EXPECT_EQ(L.transport->hemoglobin_species, 0);
  const scene::Scene s = scene::parse_scene(still_scene(), "t.toml");
  Simulation sim(s, scene::derive_lattice(s));
  EXPECT_EQ(sim.fluid(), nullptr);
  ASSERT_NE(sim.transport(), nullptr);
}

TEST(TransportScene, RefusesWhatCannotRun) {
  EXPECT_CONTAINS(error_of([] { derive("[time]\ntau = 1\n" + still_scene()); }), "builds no fluid");
  EXPECT_CONTAINS(error_of([] { derive(still_scene("periodic")); }), "does not match [boundaries.left]");
  EXPECT_CONTAINS(error_of([] {
                    std::string t = still_scene();
                    t.replace(t.find("time_step_s = 1e-5"), 18, "time_step_s = 1e-3");  // D_lat = 11.2
                    derive(t);
                  }),
                  "species[0].diffusivity_um2_s");
  EXPECT_CONTAINS(error_of([] {
                    std::string t = still_scene();
                    t.replace(t.find("[[cells]]"), 9, "[[cellz]]");
                    derive(t);
                  }),
                  "cellz");
  EXPECT_CONTAINS(error_of([] {
                    derive("[domain]\nsize_um = [10, 10]\nspacing_um = 0.5\n[time]\ntau = 1\n[transport]\n"
                           "coupling = \"subcycle\"\n[[species]]\nname = \"NO\"\ndiffusivity_um2_s = 3300\n"
                           "[run]\nsteps = 10\n");
                  }),
                  "fluid_steps_per_step");
  EXPECT_CONTAINS(error_of([] {
                    derive("[domain]\nsize_um = [10, 10]\nspacing_um = 0.5\n[transport]\ntime_step_s = 1e-5\n"
                           "[run]\nsteps = 10\n");
                  }),
                  "at least one [[species]]");
}

// domain.geometry = "axisymmetric" (docs/model.md §7b): a cylinder of radius 10 µm, 4 µm long,
// NO held at 1 µM on the wall, consumed at 1 /s; the axis at the bottom.
std::string cylinder_scene(const std::string& domain_extra = "", const std::string& transport_extra = "",
                           const std::string& species_extra = "bottom = \"zero_flux\"\n") {
  return "[domain]\nsize_um = [4, 10]\nspacing_um = 0.5\ngeometry = \"axisymmetric\"\n" + domain_extra +
         "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n"
         "[transport]\ncoupling = \"none\"\ntime_step_s = 1e-5\ncollision = \"trt\"\n" +
         transport_extra +
         "[[species]]\nname = \"NO\"\ndiffusivity_um2_s = 3300\ndecay_per_s = 1.0\ninitial_uM = 0\n"
         "top = \"fixed_concentration\"\ntop_value = 1.0\n" +
         species_extra + "[run]\nsteps = 200\n[output]\ndiagnostics_interval_steps = 50\n";
}

TEST(TransportScene, AxisymmetricRefusesWhatItCannotRun) {
  EXPECT_CONTAINS(error_of([] { derive(cylinder_scene("", "stencil = \"d2q9\"\n")); }), "only \"d2q5\"");
  EXPECT_CONTAINS(error_of([] {
                    derive(cylinder_scene("", "", "bottom = \"fixed_concentration\"\nbottom_value = 1\n"));
                  }),
                  "species[0].bottom");
  EXPECT_CONTAINS(error_of([] { derive(cylinder_scene("", "velocity_um_s = [10, 1]\n")); }), "radial");
  EXPECT_CONTAINS(error_of([] {
                    std::string t = still_scene();
                    t.replace(t.find("spacing_um = 0.5"), 16, "spacing_um = 0.5\ninner_radius_um = 2");
                    derive(t);
                  }),
                  "needs domain.geometry = \"axisymmetric\"");
  EXPECT_CONTAINS(error_of([] {
                    std::string t = still_scene();
                    t.replace(t.find("spacing_um = 0.5"), 16, "spacing_um = 0.5\ngeometry = \"axisymmetric\"");
                    derive(t);
                  }),
                  "cells[0].center_um");
  EXPECT_CONTAINS(error_of([] {
                    derive("[domain]\nsize_um = [10, 10]\nspacing_um = 0.5\ngeometry = \"axisymmetric\"\n"
                           "[time]\ntau = 1\n[run]\nsteps = 10\n");
                  }),
                  "transport.coupling = \"none\"");
}

// A still biconcave cell of revolution on the axis of a 10 µm long, 5 µm wide cylinder held at
// 20 µM (h = 0.5 µm), O2 with Hb kinetics; `hb` adds [hemoglobin] keys, `cell` [[cells]] keys.
std::string cell_of_revolution(const std::string& hb = "", const std::string& cell = "angle_deg = 90\n",
                               const std::string& domain_extra = "",
                               const std::string& interface = "interface = \"face_tensor\"\n") {
  std::string s = "[domain]\nsize_um = [10, 5]\nspacing_um = 0.5\ngeometry = \"axisymmetric\"\n" + domain_extra +
                  "[boundaries.left]\ntype = \"wall\"\n[boundaries.right]\ntype = \"wall\"\n"
                  "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n"
                  "[transport]\ncoupling = \"none\"\ntime_step_s = 1e-5\ncollision = \"trt\"\n"
                  "cell_representation = \"area_fraction\"\n" + interface +
                  "[[species]]\nname = \"O2\"\ndiffusivity_um2_s = 2800\ncell_diffusivity_um2_s = 950\n"
                  "initial_uM = 20\ncell_initial_uM = 130\nbottom = \"zero_flux\"\n";
  for (const char* k : {"left", "right", "top"})
    s += std::string(k) + " = \"fixed_concentration\"\n" + k + "_value = 20\n";
  return s + "[hemoglobin]\nspecies = \"O2\"\n" + hb +
         "[[cells]]\nshape = \"biconcave\"\nradius_um = 3.0\ncenter_um = [5, 0]\nmarkers = 400\n" + cell +
         "[run]\nsteps = 400\n[output]\ndiagnostics_interval_steps = 50\n";
}

TEST(TransportScene, AxisymmetricCellsAreBodiesOfRevolution) {
  EXPECT_CONTAINS(error_of([] { derive(cell_of_revolution("", "angle_deg = 45\n")); }), "cells[0].angle_deg");
  EXPECT_CONTAINS(error_of([] { derive(cell_of_revolution("", "angle_deg = 90\n", "inner_radius_um = 1\n")); }),
                  "domain.inner_radius_um = 0");
  EXPECT_CONTAINS(error_of([] { derive(cell_of_revolution("", "angle_deg = 90\n", "", "interface = \"node_tensor\"\n")); }),
                  "node_tensor");
  EXPECT_CONTAINS(error_of([] {
                    derive(cell_of_revolution("kinetics = \"local\"\ncoupling = \"cell_implicit_outflow\"\n"));
                  }),
                  "hemoglobin.coupling = \"cell_implicit_outflow\"");
  EXPECT_CONTAINS(error_of([] { derive(cell_of_revolution("kinetics = \"local\"\nheme_weights = \"first_moment\"\n")); }),
                  "hemoglobin.heme_weights");
  EXPECT_CONTAINS(error_of([] { derive(cell_of_revolution("kinetics = \"cellwise\"\n")); }), "hemoglobin.kinetics");
}

TEST(TransportScene, CellOfRevolutionReleasesWithTheRWeightedBalance) {
  // Both kinetics: S falls, the cell's volume is the solid of revolution's (2π Σ φ r h³ within
  // 2 % of the Evans–Fung cell scaled to a = 3 µm: 94.09 (3/3.91)³ µm³), and the released O2 (per
  // radian) is what the lattice gained minus what left through the sides, to round-off.
  for (const std::string kinetics : {"cell_mean", "local"}) {
    const scene::Scene s = scene::parse_scene(cell_of_revolution("kinetics = \"" + kinetics + "\"\n"), "t.toml");
    const scene::LatticeSetup L = scene::derive_lattice(s);
    Simulation sim(s, L);
    SeriesRecorder rec;
    ASSERT_EQ(sim.run(rec).status, RunStatus::completed) << kinetics;
    const auto S = rec.series("cell_0_saturation");
    EXPECT_LT(S.back(), S.front()) << kinetics;
    const double released = rec.series("cell_0_released_uM_um3").back();
    EXPECT_GT(released, 0.0);
    const double change = rec.series("O2_amount_change_uM_um3").back(), inflow = rec.series("O2_boundary_inflow_uM_um3").back();
    EXPECT_NEAR(change - inflow, released, 1e-10 * released) << kinetics;
    // released = C_heme (S0 − S) V / 2π per radian for the lumped cell
    if (kinetics == "cell_mean") {
      const double V = 2.0 * M_PI * released / (20300.0 * (S.front() - S.back()));
      EXPECT_NEAR(V, 94.09 * std::pow(3.0 / 3.91, 3), 0.02 * 94.09 * std::pow(3.0 / 3.91, 3));
    }
  }
}

TEST(TransportScene, AxisymmetricRunBalancesTheRWeightedAmount) {
  // The wall feeds NO in; the r-weighted amount (µM·µm³ per radian) balances the inflow and the
  // sink to round-off; an annulus (inner radius 3 µm) runs too and records its geometry.
  for (const std::string inner : {"", "inner_radius_um = 3\n"}) {
    const scene::Scene s = scene::parse_scene(cylinder_scene(inner), "t.toml");
    const scene::LatticeSetup L = scene::derive_lattice(s);
    ASSERT_TRUE(L.transport->axisymmetric_inner_radius.has_value());
    EXPECT_DOUBLE_EQ(*L.transport->axisymmetric_inner_radius, inner.empty() ? 0.0 : 6.0);
    Simulation sim(s, L);
    SeriesRecorder rec;
    EXPECT_EQ(sim.run(rec).status, RunStatus::completed);
    EXPECT_LT(rec.series("NO_max_mass_balance_residual").back(), 1e-13);
    EXPECT_GT(rec.series("NO_amount_change_uM_um3").back(), 0.0);  // NO entered through the wall
    EXPECT_NEAR(rec.series("NO_amount_change_uM_um3").back(), rec.series("NO_boundary_inflow_uM_um3").back(),
                0.01 * rec.series("NO_boundary_inflow_uM_um3").back());  // the sink (1 /s) over 2 ms: 0.2 %
    EXPECT_GT(rec.series("NO_mean_uM").back(), 0.0);
    EXPECT_LT(rec.series("NO_mean_uM").back(), 1.0);
  }
}

// [no_o2] (docs/model.md §7c) on a 2-node-wide planar stack.
std::string no_o2_scene(const std::string& species_extra = "", const std::string& layers_extra = "") {
  return "[domain]\nsize_um = [1, 20]\nspacing_um = 0.5\n"
         "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n"
         "[transport]\ncoupling = \"none\"\ntime_step_s = 1e-5\n"
         "[[species]]\nname = \"NO\"\ndiffusivity_um2_s = 3300\n" + species_extra +
         "[[species]]\nname = \"O2\"\ndiffusivity_um2_s = 2800\ninitial_uM = 91\n"
         "[no_o2]\n[[no_o2.layers]]\ncompartment = \"core\"\ny_um = [0, 8]\n"
         "[[no_o2.layers]]\ncompartment = \"plasma\"\ny_um = [8, 10]\n"
         "[[no_o2.layers]]\ncompartment = \"endothelium\"\ny_um = [10, 11]\n"
         "[[no_o2.layers]]\ncompartment = \"tissue\"\ny_um = [11, 20]\n" +
         layers_extra + "[run]\nsteps = 100\n";
}

TEST(TransportScene, NoO2BuildsTheCompartmentModel) {
  const scene::LatticeSetup L = derive(no_o2_scene());
  ASSERT_TRUE(L.transport->no_o2.has_value());
  const scene::NoO2Setup& n = *L.transport->no_o2;
  EXPECT_EQ(n.no_species, 0);
  EXPECT_EQ(n.o2_species, 1);
  EXPECT_DOUBLE_EQ(n.cell_free_layer_um, 2.0);  // the plasma band above the core
  EXPECT_DOUBLE_EQ(n.core_radius_um, 10.0);
  EXPECT_NEAR(n.model[transport::Compartment::core].no_decay, transport::no_core_scavenging_rate(382.5, 10.0, 2.0),
              1e-12);
  EXPECT_DOUBLE_EQ(n.model[transport::Compartment::core].o2_held_torr, 70.0);
  // A run: the EC makes NO, the core takes it up, the mass balance closes.
  const scene::Scene s = scene::parse_scene(no_o2_scene(), "t.toml");
  Simulation sim(s, scene::derive_lattice(s));
  SeriesRecorder rec;
  EXPECT_EQ(sim.run(rec).status, RunStatus::completed);
  EXPECT_GT(rec.series("NO_mean_uM").back(), 0.0);
  EXPECT_LT(rec.series("NO_max_mass_balance_residual").back(), 1e-13);
  EXPECT_LT(rec.series("O2_max_mass_balance_residual").back(), 1e-13);
}

TEST(TransportScene, NoO2RefusesWhatItWouldOverride) {
  EXPECT_CONTAINS(error_of([] { derive(no_o2_scene("decay_per_s = 1\n")); }), "[no_o2] sets its reactions");
  EXPECT_CONTAINS(error_of([] {
                    derive(no_o2_scene("", "[[no_o2.layers]]\ncompartment = \"tissue\"\ny_um = [15, 25]\n"));
                  }),
                  "inside [0, 20]");
  EXPECT_CONTAINS(error_of([] {
                    derive(no_o2_scene("", "[[no_o2.layers]]\ncompartment = \"core\"\ny_um = [12, 13]\n"));
                  }),
                  "overlaps");
  EXPECT_CONTAINS(error_of([] {
                    std::string t = no_o2_scene();
                    t.replace(t.find("[no_o2]\n"), 8, "[no_o2]\no2_species = \"O3\"\n");
                    derive(t);
                  }),
                  "names no [[species]] entry");
  EXPECT_CONTAINS(error_of([] {  // a node takes the compartment at its centre: edges must lie on faces
                    std::string t = no_o2_scene();
                    t.replace(t.find("y_um = [10, 11]"), 15, "y_um = [10, 10.75]");
                    derive(t);
                  }),
                  "not a multiple of domain.spacing_um");
}

struct Record : SeriesRecorder {
  int field_frames = 0;
  void on_transport_fields(long, const TransportFields&) override { ++field_frames; }
};

// Closed box (zero flux everywhere): O2 only moves between haemoglobin and solution,
// so free + bound O2, Σ C + C_heme S N_cell, is conserved to round-off while the cell
// releases O2 (S falls monotonically towards equilibrium with the medium).
TEST(TransportScene, ClosedBoxConservesFreePlusBoundOxygen) {
  const scene::Scene s = scene::parse_scene(still_scene("zero_flux"), "t.toml");
  const scene::LatticeSetup L = scene::derive_lattice(s);
  Simulation sim(s, L);
  const auto total_o2 = [&] { return sim.transport()->lattice(0).stored_amount(); };
  const double free0 = total_o2();
  Record rec;
  const RunSummary r = sim.run(rec);
  EXPECT_EQ(r.status, RunStatus::completed);
  ASSERT_GE(rec.samples(), 3u);
  const auto& S = rec.series("cell_0_saturation");
  const auto& residual = rec.series("O2_mass_balance_residual");
  for (std::size_t k = 1; k < rec.samples(); ++k) {
    EXPECT_LT(S[k], S[k - 1]);
    EXPECT_LT(std::abs(residual[k]), 1e-13);
  }
  EXPECT_LT(rec.series("O2_max_mass_balance_residual").back(), 1e-13);
  // Bound O2 released = C_heme (S0 − S) per interior node; the free O2 gained must match.
  const double S0 = S.front(), S1 = S.back();
  const double gained = total_o2() - free0;
  const double released_per_node = L.transport->hemoglobin->C_heme * (S0 - S1);
  EXPECT_GT(gained, 0.0);
  const double nodes_inside = gained / released_per_node;  // must be the cell's interior node count
  EXPECT_NEAR(nodes_inside, std::round(nodes_inside), 1e-9 * nodes_inside);
  EXPECT_EQ(rec.field_frames, 2);  // initial and final
}

// The health check: healthy after an ordinary step; amount created outside the step (a
// population changed between steps) breaks eq T5 far above round-off and is caught.
TEST(TransportScene, HealthCatchesAMassBalanceThatDoesNotClose) {
  const scene::Scene s = scene::parse_scene(still_scene("zero_flux"), "t.toml");
  Simulation sim(s, scene::derive_lattice(s));
  TransportPhysics& T = *sim.transport();
  T.step({}, {});
  EXPECT_TRUE(T.check_health().healthy);
  T.lattice(0).populations()[5] += 1.0;  // 1 µM·node from nowhere, against ~2e4 stored
  T.step({}, {});
  const HealthReport h = T.check_health();
  EXPECT_FALSE(h.healthy);
  EXPECT_EQ(h.quantity, "O2 mass-balance residual");
  EXPECT_GT(h.value, TransportPhysics::kMaxRelativeResidual);
}

// Held at 20 µM on every side: the cell loses O2 to the boundary; every transport
// sample has a round-off mass-balance residual, and the saturation heads towards
// the Hill value at the medium's PO2 without passing it.
TEST(TransportScene, HeldMediumDeoxygenatesTheCell) {
  const scene::Scene s = scene::parse_scene(still_scene("fixed_concentration"), "t.toml");
  Simulation sim(s, scene::derive_lattice(s));
  Record rec;
  EXPECT_EQ(sim.run(rec).status, RunStatus::completed);
  const double S_eq = transport::hill_saturation(20.0 / 1.3);
  const auto& S = rec.series("cell_0_saturation");
  EXPECT_LT(S.back(), S.front());
  EXPECT_GT(S.back(), S_eq);
  for (double r : rec.series("O2_mass_balance_residual")) EXPECT_LT(std::abs(r), 1e-13);
}

// Sub-cycling: a passive tracer in the example capsule scene advances once every
// 20 fluid steps with the fluid's velocity; Δt_T = 20 Δt_F.
TEST(TransportScene, SubcyclingFollowsTheFluid) {
  // [[species]] cannot be set from the command line: append it to the scene's text.
  const std::string text = "[transport]\ncoupling = \"subcycle\"\nfluid_steps_per_step = 20\n"
                     "[[species]]\nname = \"tracer\"\ndiffusivity_um2_s = 2800.0\ninitial_uM = 1.0\n";
  const scene::Scene base = scene::load_scene(std::string(ERYTHRO_SCENES_DIR) + "/capsule_shear.toml",
                                              {"run.steps=100", "output.diagnostics_interval_steps=50"});
  const scene::Scene t = scene::parse_scene(base.source_text + text, "t.toml");
  const scene::LatticeSetup L = scene::derive_lattice(t);
  ASSERT_TRUE(L.transport.has_value());
  EXPECT_EQ(L.transport->fluid_steps_per_step, 20);
  EXPECT_DOUBLE_EQ(L.transport->time_step_s, 20 * L.scales.time_s);
  Simulation sim(t, L);
  ASSERT_NE(sim.fluid(), nullptr);
  Record rec;
  EXPECT_EQ(sim.run(rec).status, RunStatus::completed);
  EXPECT_EQ(sim.transport()->lattice(0).steps_done(), 5);
  // The last transport step (after fluid step 100) advected with u_T = 20 u_F of that step.
  const fluid::Moments m = sim.fluid()->moments();
  const auto ux = sim.transport()->lattice(0).velocity_x(), uy = sim.transport()->lattice(0).velocity_y();
  ASSERT_EQ(ux.size(), m.ux.size());
  double largest = 0.0;
  for (std::size_t n = 0; n < m.ux.size(); ++n) {
    ASSERT_EQ(ux[n], 20.0 * m.ux[n]) << "node " << n;
    ASSERT_EQ(uy[n], 20.0 * m.uy[n]) << "node " << n;
    largest = std::max(largest, std::abs(ux[n]));
  }
  EXPECT_GT(largest, 0.0);  // the capsule scene is sheared: the check is not 0 = 0
  // A uniform tracer in a divergence-free flow with zero-flux walls stays uniform.
  for (double mean : rec.series("tracer_mean_uM")) EXPECT_NEAR(mean, 1.0, 1e-12);
}

}  // namespace
}  // namespace erythro::sim
