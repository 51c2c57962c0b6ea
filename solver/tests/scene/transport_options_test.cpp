// The transport options of a scene (docs/scenes.md "[transport]", "[[transport.layers]]"): collision,
// cell representation and membrane rule, Hb coupling, uniform velocity of a still medium,
// zero-order sources and first-order sinks, [[transport.layers]] bands, the monitor's concentration range,
// dense diagnostics and the steady-state series: parsing, refusals with the key and its range,
// conversion, and what they do in a run.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "input_error_matchers.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"
#include "simulation/series_recorder.hpp"
#include "simulation/simulation.hpp"
#include "transport/subpixel_diffusivity.hpp"

namespace erythro::sim {
namespace {

using scene::testing::error_of;

// 10 µm box, h = 0.5 µm, held at 20 µM; O2 2800 / 950 µm²/s, Δt_T = 1e-5 s; a biconcave cell.
std::string cell_scene(const std::string& transport_extra = "", const std::string& hb_extra = "",
                       const std::string& extra = "") {
  std::string s =
      "[domain]\nsize_um = [10, 10]\nspacing_um = 0.5\n"
      "[boundaries.left]\ntype = \"wall\"\n[boundaries.right]\ntype = \"wall\"\n"
      "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n"
      "[transport]\ncoupling = \"none\"\ntime_step_s = 1e-5\n" + transport_extra +
      "[[species]]\nname = \"O2\"\ndiffusivity_um2_s = 2800\ncell_diffusivity_um2_s = 950\ninitial_uM = 20\n"
      "cell_initial_uM = 130\n";
  for (const char* k : {"left", "right", "bottom", "top"})
    s += std::string(k) + " = \"fixed_concentration\"\n" + k + "_value = 20\n";
  return s + "[hemoglobin]\nspecies = \"O2\"\n" + hb_extra +
         "[[cells]]\nshape = \"biconcave\"\nradius_um = 3.0\ncenter_um = [5, 5]\nmarkers = 400\n"
         "[run]\nsteps = 300\n[output]\ndiagnostics_interval_steps = 100\n" + extra;
}

// A 1 × 40 slab (h = 1 µm, Δt = 1e-4 s, D = 1000 µm²/s → D_lat = 0.1), zero flux top and bottom.
std::string slab_scene(const std::string& extra = "", const std::string& species_extra = "") {
  return "[domain]\nsize_um = [1, 40]\nspacing_um = 1\n"
         "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n"
         "[transport]\ncoupling = \"none\"\ntime_step_s = 1e-4\n"
         "[[species]]\nname = \"NO\"\ndiffusivity_um2_s = 1000\ninitial_uM = 1\nbottom = \"zero_flux\"\ntop = \"zero_flux\"\n" +
         species_extra + "[run]\nsteps = 100\n[output]\ndiagnostics_interval_steps = 10\n" + extra;
}

scene::LatticeSetup derive(const std::string& text) { return scene::derive_lattice(scene::parse_scene(text, "t.toml")); }

TEST(TransportOptions, BadValuesNameTheKeyAndItsRange) {
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("collision = \"mrt\"\n")); }), "transport.collision");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("trt_magic = -1\n")); }), "transport.trt_magic");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("cell_representation = \"voxel\"\n")); }),
                  "transport.cell_representation");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("interface = \"kottke\"\n")); }), "transport.interface");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("layer_mean = \"geometric\"\n")); }), "transport.layer_mean");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("readout = \"corrected\"\n")); }), "transport.readout");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("velocity_um_s = 3\n")); }), "transport.velocity_um_s");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("", "coupling = \"implicit\"\n")); }), "hemoglobin.coupling");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("", "mean_pressure = \"mean\"\n")); }), "hemoglobin.mean_pressure");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("", "heme_weights = \"moment\"\n")); }), "hemoglobin.heme_weights");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("", "", "[monitor]\nconcentration_range_uM = [5, 1]\n")); }),
                  "monitor.concentration_range_uM");
  EXPECT_CONTAINS(error_of([] {
                    std::string t = cell_scene();
                    t.replace(t.find("diagnostics_interval_steps"), 0, "dense_diagnostics_steps = -1\n");
                    derive(t);
                  }),
                  "output.dense_diagnostics_steps");
  EXPECT_CONTAINS(error_of([] { derive(slab_scene("", "decay_per_s = -1\n")); }), "species[0].decay_per_s");
  EXPECT_CONTAINS(error_of([] { derive(slab_scene("[[transport.layers]]\nspecies = \"NO\"\ny_um = [10, 5]\n")); }),
                  "layers[0].y_um");
  EXPECT_CONTAINS(error_of([] { derive(slab_scene("[[transport.layers]]\nspecies = \"O2\"\ny_um = [0, 5]\n")); }),
                  "layers[0].species");
  EXPECT_CONTAINS(error_of([] { derive(slab_scene("[[transport.layers]]\nspecies = \"NO\"\ny_um = [0, 5]\ndecay_per_s = -2\n")); }),
                  "layers[0].decay_per_s");
  EXPECT_CONTAINS(error_of([] { derive(slab_scene("[[transport.layers]]\nspecies = \"NO\"\ny_um = [0, 5]\ndiffusivity_um2_s = 0\n")); }),
                  "layers[0].diffusivity_um2_s");
}

TEST(TransportOptions, CombinationsThatCannotWorkAreRefused) {
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("interface = \"face_tensor\"\n")); }),
                  "needs the cut cells of transport.cell_representation");
  EXPECT_CONTAINS(error_of([] {
                    derive(cell_scene("interface = \"face_tensor\"\ncell_representation = \"area_fraction\"\n"));
                  }),
                  "needs transport.collision = \"trt\"");
  EXPECT_CONTAINS(error_of([] {
                    derive(cell_scene("interface = \"face_tensor\"\ncell_representation = \"area_fraction\"\n"
                                      "collision = \"trt\"\ntrt_magic = 0.1\n"));
                  }),
                  "trt_magic = 0.25");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("", "mean_pressure = \"source_corrected\"\n")); }),
                  "cell_implicit_outflow");
  EXPECT_CONTAINS(error_of([] { derive(cell_scene("", "heme_weights = \"first_moment\"\n")); }),
                  "cell_representation = \"area_fraction\"");
  EXPECT_CONTAINS(error_of([] {
                    derive(slab_scene("[[transport.layers]]\nspecies = \"NO\"\ny_um = [0, 20]\n[[transport.layers]]\nspecies = \"NO\"\n"
                                      "y_um = [10, 30]\n"));
                  }),
                  "overlaps");
  EXPECT_CONTAINS(error_of([] { derive(slab_scene("[[transport.layers]]\nspecies = \"NO\"\ny_um = [0, 50]\n")); }),
                  "outside the domain");
}

TEST(TransportOptions, ConvertedIntoTheSetup) {
  const scene::LatticeSetup L =
      derive(cell_scene("collision = \"trt\"\ntrt_magic = 0.25\ncell_representation = \"area_fraction\"\n"
                        "interface = \"face_tensor\"\n",
                        "coupling = \"cell_implicit_outflow\"\nmean_pressure = \"source_corrected\"\n",
                        "[monitor]\nconcentration_range_uM = [-130, 260]\n"));
  const auto& T = *L.transport;
  EXPECT_EQ(T.collision.kind, transport::Collision::trt);
  EXPECT_EQ(T.collision.magic, 0.25);
  EXPECT_EQ(T.cell_representation, "area_fraction");
  EXPECT_EQ(T.interface, "face_tensor");
  EXPECT_EQ(T.hb_coupling, "cell_implicit_outflow");
  EXPECT_EQ(T.mean_pressure, "source_corrected");
  ASSERT_TRUE(T.concentration_range.has_value());
  EXPECT_EQ((*T.concentration_range)[1], 260.0);
  EXPECT_EQ(T.units.h_um, 0.5);  // the scene's spacing itself
  const scene::LatticeSetup S = derive(slab_scene("", "source_uM_per_s = -50\ndecay_per_s = 2\n"));
  EXPECT_DOUBLE_EQ(S.transport->species[0].source, -50.0 * 1e-4);
  EXPECT_DOUBLE_EQ(S.transport->species[0].decay, 2.0 * 1e-4);
}

// Area fractions with the face subpixel tensor and the outflow coupling (the deoxygenation
// model): the released O2 is in the lattice or has left through the sides, to round-off.
TEST(TransportOptions, AreaFractionCellReleasesIntoTheLatticeExactly) {
  const scene::Scene s = scene::parse_scene(
      cell_scene("collision = \"trt\"\ncell_representation = \"area_fraction\"\ninterface = \"face_tensor\"\n",
                 "coupling = \"cell_implicit_outflow\"\nmean_pressure = \"source_corrected\"\n",
                 "[monitor]\nconcentration_range_uM = [-130, 260]\n"),
      "t.toml");
  const scene::LatticeSetup L = scene::derive_lattice(s);
  Simulation sim(s, L);
  SeriesRecorder rec;
  ASSERT_EQ(sim.run(rec).status, RunStatus::completed);
  const double released = rec.series("cell_0_released_uM_um2").back();
  const double change = rec.series("O2_amount_change_uM_um2").back();
  const double inflow = rec.series("O2_boundary_inflow_uM_um2").back();
  EXPECT_GT(released, 0.0);
  EXPECT_LT(std::abs(change - inflow - released) / released, 1e-10);
  // the heme area is the polygon's (area fractions are exact)
  const auto& cell = L.membrane->cells[0].shape;
  double area = 0.0;
  for (const auto& f : transport::area_fractions(cell, L.grid.nx, L.grid.ny)) area += f.phi;
  EXPECT_NEAR(area, std::abs(geometry::signed_area(cell)), 1e-10 * area);
}

TEST(TransportOptions, ConcentrationRangeStopsTheRun) {
  const scene::Scene s = scene::parse_scene(cell_scene("", "", "[monitor]\ninterval_steps = 10\n"
                                                               "concentration_range_uM = [0, 100]\n"),
                                            "t.toml");  // the cell starts at 130 µM
  Simulation sim(s, scene::derive_lattice(s));
  SeriesRecorder rec;
  const RunSummary r = sim.run(rec);
  EXPECT_EQ(r.status, RunStatus::diverged);
  EXPECT_CONTAINS(r.diagnosis, "O2 concentration");
}

// A band with its own sink and source: the interior of a band takes its values, a node cut by
// an edge half of each (harmonic D), and the flux across the top edge is reported.
TEST(TransportOptions, LayersSetTheirBandAndMixAtACutNode) {
  const std::string layers =
      "[[transport.layers]]\nspecies = \"NO\"\ny_um = [0, 10.5]\ndiffusivity_um2_s = 500\ndecay_per_s = 20\n"
      "[[transport.layers]]\nspecies = \"NO\"\ny_um = [10.5, 20]\nsource_uM_per_s = 10\n";
  const scene::Scene s = scene::parse_scene(slab_scene(layers), "t.toml");
  const scene::LatticeSetup L = scene::derive_lattice(s);
  Simulation sim(s, L);
  const auto& lat = sim.transport()->lattice(0);
  ASSERT_TRUE(lat.has_diffusivity_field());
  ASSERT_TRUE(lat.has_reaction());
  const double dt = 1e-4;
  EXPECT_DOUBLE_EQ(const_cast<transport::TransportLattice&>(lat).diffusivity()[3], 500 * dt);
  EXPECT_DOUBLE_EQ(const_cast<transport::TransportLattice&>(lat).decay_rate()[3], 20 * dt);
  EXPECT_NEAR(const_cast<transport::TransportLattice&>(lat).diffusivity()[10], dt / (0.5 / 500 + 0.5 / 1000), 1e-15);
  EXPECT_DOUBLE_EQ(const_cast<transport::TransportLattice&>(lat).decay_rate()[10], 10 * dt);
  EXPECT_DOUBLE_EQ(const_cast<transport::TransportLattice&>(lat).source()[10], 5 * dt);
  EXPECT_DOUBLE_EQ(const_cast<transport::TransportLattice&>(lat).source()[15], 10 * dt);
  EXPECT_DOUBLE_EQ(const_cast<transport::TransportLattice&>(lat).source()[30], 0.0);
  SeriesRecorder rec;
  ASSERT_EQ(sim.run(rec).status, RunStatus::completed);
  ASSERT_TRUE(rec.has("NO_layer_1_top_flux_uM_um_s"));
  EXPECT_GT(rec.series("NO_layer_1_top_flux_uM_um_s").back(), 0.0);  // the source band feeds the rest
}

// A rectangle (x_um given): a node's fraction is that of its square inside the rectangle.
TEST(TransportOptions, LayerRectangleMixesByAreaFraction) {
  const std::string text =
      "[domain]\nsize_um = [4, 4]\nspacing_um = 1\n[transport]\ncoupling = \"none\"\ntime_step_s = 1e-4\n"
      "[[species]]\nname = \"c\"\ndiffusivity_um2_s = 1000\n[run]\nsteps = 1\n"
      "[[transport.layers]]\nspecies = \"c\"\ny_um = [1, 2]\nx_um = [1, 2.5]\nsource_uM_per_s = 10\n";
  const scene::Scene s = scene::parse_scene(text, "t.toml");
  Simulation sim(s, scene::derive_lattice(s));
  auto q = sim.transport()->lattice(0).source();
  const Grid g{4, 4};
  EXPECT_DOUBLE_EQ(q[g.index(1, 1)], 10 * 1e-4);
  EXPECT_DOUBLE_EQ(q[g.index(2, 1)], 5 * 1e-4);
  EXPECT_DOUBLE_EQ(q[g.index(3, 1)], 0.0);
  EXPECT_DOUBLE_EQ(q[g.index(1, 2)], 0.0);
  EXPECT_CONTAINS(error_of([&] { derive(text + "[[transport.layers]]\nspecies = \"c\"\ny_um = [0, 4]\n"
                                                "x_um = [2, 3]\n"); }),
                  "overlaps");
}

// Uniform advection of a still medium; [[stop_when]] on the change series ends a steady run;
// the first dense_diagnostics_steps steps are all sampled.
TEST(TransportOptions, UniformVelocitySteadyStopAndDenseSamples) {
  EXPECT_CONTAINS(error_of([] {
                    const scene::Scene base = scene::load_scene(std::string(ERYTHRO_SCENES_DIR) + "/capsule_shear.toml",
                                                                {"run.steps=10"});
                    derive(base.source_text + "[transport]\ncoupling = \"subcycle\"\nfluid_steps_per_step = 20\n"
                                              "velocity_um_s = [1, 0]\n[[species]]\nname = \"c\"\n"
                                              "diffusivity_um2_s = 2800\n");
                  }),
                  "transport.velocity_um_s");
  const std::string steady = slab_scene("[[stop_when]]\nseries = \"NO_change_uM\"\nbelow = 1e-9\n",
                                        "source_uM_per_s = 1\ndecay_per_s = 10\n");
  std::string text = steady;
  text.replace(text.find("steps = 100"), 11, "steps = 100000");
  text.replace(text.find("diagnostics_interval_steps = 10"), 31, "diagnostics_interval_steps = 100\n"
                                                                 "dense_diagnostics_steps = 5");
  const scene::Scene s = scene::parse_scene(text, "t.toml");
  Simulation sim(s, scene::derive_lattice(s));
  SeriesRecorder rec;
  const RunSummary r = sim.run(rec);
  EXPECT_EQ(r.status, RunStatus::stopped);
  EXPECT_LT(r.steps, 100000);
  const auto& step = rec.series("step");
  ASSERT_GE(step.size(), 7u);
  for (int k = 0; k <= 5; ++k) EXPECT_EQ(step[static_cast<std::size_t>(k)], k);
  EXPECT_EQ(step[6], 100);
  EXPECT_TRUE(std::isnan(rec.series("NO_change_uM").front()));
  EXPECT_NEAR(rec.series("NO_mean_uM").back(), 0.1, 1e-6);  // q/k
  // a uniform velocity of a still medium moves a pulse
  const std::string moving =
      "[domain]\nsize_um = [20, 4]\nspacing_um = 1\n[transport]\ncoupling = \"none\"\ntime_step_s = 1e-4\n"
      "velocity_um_s = [100, 0]\n[[species]]\nname = \"c\"\ndiffusivity_um2_s = 1000\n[run]\nsteps = 100\n";
  const scene::Scene m = scene::parse_scene(moving, "t.toml");
  Simulation flow(m, scene::derive_lattice(m));
  EXPECT_DOUBLE_EQ(flow.transport()->lattice(0).velocity_x()[0], 100 * 1e-4);
}

}  // namespace
}  // namespace erythro::sim
