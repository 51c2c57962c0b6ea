// scene_parser: TOML → Scene, error messages (file, line, key, value, allowed range)
// and --set overrides.
#include "scene/scene_parser.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include "common/error.hpp"
#include "input_error_matchers.hpp"

namespace erythro::scene {
namespace {

using testing::error_of;

// Smallest valid scene: 4 lines of required keys.
const std::string minimal = R"(
[domain]
size_um = [2.0, 4.0]
spacing_um = 0.25
[time]
tau = 1.0
[run]
steps = 100
)";

std::string parse_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return error_of([&] { parse_scene(text, "scenes/x.toml", overrides); });
}

TEST(SceneParser, MinimalSceneGetsDefaults) {
  const Scene s = parse_scene(minimal, "scenes/x.toml");
  EXPECT_EQ(s.name, "x");  // defaults to the file's stem
  EXPECT_EQ(s.source_path, "scenes/x.toml");
  EXPECT_EQ(s.domain.size_um[1], 4.0);
  EXPECT_EQ(s.time.tau, 1.0);
  EXPECT_FALSE(s.time.step_s);
  EXPECT_EQ(s.fluid.viscosity_cP, 1.2);
  EXPECT_EQ(s.fluid.density_kg_m3, 1025.0);
  EXPECT_EQ(s.fluid.collision, "bgk");
  EXPECT_EQ(s.boundaries.top.type, "periodic");
  EXPECT_FALSE(s.body_force);
  EXPECT_FALSE(s.run.steady_state);
  EXPECT_EQ(s.run.steps, 100L);
  EXPECT_EQ(s.output.fields, (std::vector<std::string>{"density", "velocity"}));
  EXPECT_EQ(s.limits.min_nodes_across_channel, 4);
}

TEST(SceneParser, EveryKeyRoundTripsIntoTheStruct) {
  const std::string text = R"(
[scene]
name = "full"
description = "every key"
[domain]
size_um = [4, 8]          # integers are accepted where floats are expected
spacing_um = 0.5
[time]
step_s = 1e-8
[fluid]
density_kg_m3 = 1000.0
viscosity_cP = 1.5
collision = "trt"
trt_magic = 0.25
[boundaries.left]
type = "periodic"
[boundaries.right]
type = "periodic"
[boundaries.bottom]
type = "wall"
[boundaries.top]
type = "moving_wall"
velocity_um_s = [100.0, 0.0]
[body_force]
density_N_m3 = [1e4, -2]
frequency_Hz = 50
phase_rad = 0.5
[initial]
type = "uniform"
velocity_um_s = [10.0, 1.0]
[run]
duration_s = 1e-4
[run.steady_state]
tolerance = 1e-8
check_interval_steps = 50
[monitor]
interval_steps = 20
max_mach = 0.2
[output]
fields_interval_steps = 500
diagnostics_interval_steps = 10
fields = ["velocity"]
[limits]
min_tau_margin = 0.01
max_mach = 0.05
min_nodes_across_channel = 8
)";
  const Scene s = parse_scene(text, "full.toml");
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.description, "every key");
  EXPECT_EQ(s.domain.size_um, (std::array<double, 2>{4.0, 8.0}));
  EXPECT_EQ(s.domain.spacing_um, 0.5);
  EXPECT_EQ(s.time.step_s, 1e-8);
  EXPECT_FALSE(s.time.tau);
  EXPECT_EQ(s.fluid.density_kg_m3, 1000.0);
  EXPECT_EQ(s.fluid.viscosity_cP, 1.5);
  EXPECT_EQ(s.fluid.collision, "trt");
  EXPECT_EQ(s.fluid.trt_magic, 0.25);
  EXPECT_EQ(s.boundaries.left.type, "periodic");
  EXPECT_EQ(s.boundaries.bottom.type, "wall");
  EXPECT_EQ(s.boundaries.top.type, "moving_wall");
  EXPECT_EQ(s.boundaries.top.velocity_um_s, (std::array<double, 2>{100.0, 0.0}));
  ASSERT_TRUE(s.body_force);
  EXPECT_EQ(s.body_force->density_N_m3, (std::array<double, 2>{1e4, -2.0}));
  EXPECT_EQ(s.body_force->frequency_Hz, 50.0);
  EXPECT_EQ(s.body_force->phase_rad, 0.5);
  EXPECT_EQ(s.initial.type, "uniform");
  EXPECT_EQ(s.initial.velocity_um_s, (std::array<double, 2>{10.0, 1.0}));
  EXPECT_FALSE(s.run.steps);
  EXPECT_EQ(s.run.duration_s, 1e-4);
  ASSERT_TRUE(s.run.steady_state);
  EXPECT_EQ(s.run.steady_state->tolerance, 1e-8);
  EXPECT_EQ(s.run.steady_state->check_interval_steps, 50);
  EXPECT_EQ(s.monitor.interval_steps, 20);
  EXPECT_EQ(s.monitor.max_mach, 0.2);
  EXPECT_EQ(s.output.fields_interval_steps, 500);
  EXPECT_EQ(s.output.diagnostics_interval_steps, 10);
  EXPECT_EQ(s.output.fields, std::vector<std::string>{"velocity"});
  EXPECT_EQ(s.limits.min_tau_margin, 0.01);
  EXPECT_EQ(s.limits.max_mach, 0.05);
  EXPECT_EQ(s.limits.min_nodes_across_channel, 8);

  // The recorded text is TOML that reproduces the same scene.
  const Scene again = parse_scene(s.source_text, "full.toml");
  EXPECT_EQ(again.source_text, s.source_text);
  EXPECT_EQ(again.body_force->density_N_m3, s.body_force->density_N_m3);
  EXPECT_EQ(again.time.step_s, s.time.step_s);
}

TEST(SceneParser, EmptyBodyForceTableEngagesAZeroForce) {
  const Scene s = parse_scene(minimal + "[body_force]\n", "x.toml");
  ASSERT_TRUE(s.body_force);
  EXPECT_EQ(s.body_force->density_N_m3, (std::array<double, 2>{0.0, 0.0}));
}

TEST(SceneParser, MalformedTomlNamesFileLineAndColumn) {
  const std::string m = parse_error("[domain]\nsize_um = [2.0, 4.0\nspacing_um = 1\n");
  EXPECT_CONTAINS(m, "scenes/x.toml:");
  EXPECT_CONTAINS(m, "malformed TOML");
  const std::string m2 = parse_error("[domain]\nspacing_um = = 1\n");
  EXPECT_CONTAINS(m2, "scenes/x.toml:2:");
  EXPECT_CONTAINS(m2, "malformed TOML:");
}

TEST(SceneParser, UnknownKeySuggestsTheClosestKnownKey) {
  const std::string m = parse_error(minimal + "[fluid]\nviscosty_cP = 1.2\n");
  EXPECT_CONTAINS(m, "scenes/x.toml:10:");
  EXPECT_CONTAINS(m, "unknown key 'fluid.viscosty_cP'");
  EXPECT_CONTAINS(m, "(did you mean 'fluid.viscosity_cP'?)");
}

TEST(SceneParser, UnknownTableAndMisplacedKey) {
  EXPECT_CONTAINS(parse_error(minimal + "[fluids]\nviscosity_cP = 1.2\n"), "unknown table 'fluids' (did you mean 'fluid'?)");
  // A known key in the wrong table: suggested by its name.
  EXPECT_CONTAINS(parse_error(minimal + "[monitor]\nmin_tau_margin = 0.1\n"),
                  "unknown key 'monitor.min_tau_margin' (did you mean 'limits.min_tau_margin'?)");
  // A quoted dotted key is a different key.
  EXPECT_CONTAINS(parse_error("\"fluid.viscosity_cP\" = 2\n" + minimal), "scenes/x.toml:1: unknown key 'fluid.viscosity_cP'");
  // Nothing close: no suggestion.
  const std::string m = parse_error(minimal + "[adhesion]\nwell_depth = 6e-3\n");
  EXPECT_CONTAINS(m, "unknown table 'adhesion'");
  EXPECT_EQ(m.find("did you mean"), std::string::npos) << m;
}

TEST(SceneParser, WrongTypesAreErrors) {
  const std::string m = parse_error(minimal + "[fluid]\nviscosity_cP = \"high\"\n");
  EXPECT_CONTAINS(m, "scenes/x.toml:10: key 'fluid.viscosity_cP' = \"high\" has the wrong type (a string)");
  EXPECT_CONTAINS(m, "expected a number; must be in [1e-30, 1e+30] (cP)");
  // A float where a count is expected.
  const std::string steps = parse_error("[domain]\nsize_um = [2, 4]\nspacing_um = 0.25\n[time]\ntau = 1\n[run]\nsteps = 10.5\n");
  EXPECT_CONTAINS(steps, "scenes/x.toml:7: key 'run.steps' = 10.5 has the wrong type (a float): expected an integer");
  EXPECT_CONTAINS(parse_error("fluid = 3\n" + minimal), "key 'fluid' = 3 has the wrong type (an integer): expected a table");
  // After [run], a bare key belongs to [run].
  EXPECT_CONTAINS(parse_error(minimal + "fluid = 3\n"), "unknown key 'run.fluid' (did you mean 'fluid'?)");
  EXPECT_CONTAINS(parse_error(minimal + "[body_force]\ndensity_N_m3 = [1, 2, 3]\n"),
                  "key 'body_force.density_N_m3' = [1, 2, 3] has the wrong type (an array): expected an array of 2 numbers");
  EXPECT_CONTAINS(parse_error(minimal + "[output]\nfields = \"density\"\n"), "expected an array of strings");
}

TEST(SceneParser, OutOfRangeValuesNameKeyValueAndRange) {
  // The example message of docs/scenes.md, verbatim.
  const std::string text = "[domain]\nsize_um = [2, 4]\nspacing_um = 0.25\n[time]\ntau = 1\n[fluid]\nviscosity_cP = -1\n[run]\nsteps = 1\n";
  EXPECT_EQ(parse_error(text), "scenes/x.toml:7: key 'fluid.viscosity_cP' = -1 is out of range: must be in [1e-30, 1e+30] (cP)");

  EXPECT_CONTAINS(parse_error(minimal + "[fluid]\ncollision = \"mrt\"\n"),
                  "key 'fluid.collision' = \"mrt\" is out of range: must be one of \"bgk\", \"trt\"");
  EXPECT_CONTAINS(parse_error(minimal + "[boundaries.top]\ntype = \"wal\"\n"),
                  "must be one of \"periodic\", \"wall\", \"moving_wall\"");
  EXPECT_CONTAINS(parse_error(minimal + "[initial]\ntype = \"poiseuille\"\n"),
                  "must be one of \"rest\", \"uniform\", \"shear\", \"taylor_green\"");
  EXPECT_CONTAINS(parse_error(minimal + "[output]\nfields = [\"pressure\"]\n"),
                  "contains \"pressure\": each entry must be one of \"density\", \"velocity\"");
  EXPECT_CONTAINS(parse_error(minimal + "[output]\nfields_interval_steps = -1\n"), "must be in [0, 1e+12] (steps)");
  EXPECT_CONTAINS(parse_error(minimal + "[monitor]\ninterval_steps = 0\n"), "must be in [1, 1e+12] (steps)");
  EXPECT_CONTAINS(parse_error(minimal + "[limits]\nmax_mach = 0\n"), "key 'limits.max_mach' = 0 is out of range: must be in [1e-30, 1e+30]");
  EXPECT_CONTAINS(parse_error(minimal + "[limits]\nmin_nodes_across_channel = 0\n"), "must be in [1, 1e+06] (nodes)");
  EXPECT_CONTAINS(parse_error(minimal + "[limits]\nmembrane_stability = \"off\"\n"),
                  "key 'limits.membrane_stability' = \"off\" is out of range: must be one of \"reject\", \"warn\"");
  EXPECT_CONTAINS(parse_error(minimal + "[fluid]\ndensity_kg_m3 = nan\n"), "must be in [1e-30, 1e+30] (kg/m³)");
  EXPECT_CONTAINS(parse_error("[domain]\nsize_um = [2, -4]\nspacing_um = 0.25\n[time]\ntau = 1\n[run]\nsteps = 1\n"),
                  "scenes/x.toml:2: key 'domain.size_um' = [2, -4] is out of range: each component must be in [1e-30, 1e+30] (µm)");
  EXPECT_CONTAINS(parse_error("[domain]\nsize_um = [2, 4]\nspacing_um = 0.25\n[time]\ntau = 0.5\n[run]\nsteps = 1\n"),
                  "scenes/x.toml:5: key 'time.tau' = 0.5 is out of range: must be in (0.5, 1e+30]");
  EXPECT_CONTAINS(parse_error("[domain]\nsize_um = [2, 4]\nspacing_um = 0.25\n[time]\ntau = 1\n[run]\nsteps = 0\n"),
                  "key 'run.steps' = 0 is out of range: must be in [1, 1e+12]");
  EXPECT_CONTAINS(parse_error(minimal + "[run.steady_state]\ntolerance = 0\n"), "must be in [1e-30, 1e+30]");
  EXPECT_CONTAINS(parse_error(minimal + "[aggregation]\nde_star = -0.5\n"),
                  "key 'aggregation.de_star' = -0.5 is out of range: must be in [0, 1e+30]");
  EXPECT_CONTAINS(parse_error(minimal + "[limits]\nmax_marker_spacing = 0\n"),
                  "key 'limits.max_marker_spacing' = 0 is out of range: must be in [1e-30, 1e+30] (h)");
  EXPECT_CONTAINS(parse_error(minimal + "[limits]\nmin_cell_gap = -1\n"),
                  "key 'limits.min_cell_gap' = -1 is out of range: must be in [0, 1e+30] (h)");
}

TEST(SceneParser, VelocityOnlyWhereItMeansSomething) {
  EXPECT_CONTAINS(parse_error(minimal + "[boundaries.top]\ntype = \"wall\"\nvelocity_um_s = [1, 0]\n"),
                  "key 'boundaries.top.velocity_um_s' = [1, 0] is not allowed here");
  EXPECT_CONTAINS(parse_error(minimal + "[initial]\nvelocity_um_s = [1, 0]\n"),
                  "not allowed with initial.type = \"rest\"");
  EXPECT_CONTAINS(parse_error(minimal + "[initial]\ntype = \"taylor_green\"\nvelocity_um_s = [1, 1]\n"), "[U, 0]");
}

TEST(SceneParser, ExactlyOneOfTauAndStepAndOfStepsAndDuration) {
  const std::string both = "[domain]\nsize_um = [2, 4]\nspacing_um = 0.25\n[time]\ntau = 1\nstep_s = 1e-8\n[run]\nsteps = 1\n";
  const std::string m = parse_error(both);
  EXPECT_CONTAINS(m, "scenes/x.toml:6: key 'time.step_s' = 1e-08 conflicts with 'time.tau' = 1");
  EXPECT_CONTAINS(m, "give exactly one");
  EXPECT_CONTAINS(m, "> 0.5");

  const std::string neither = "[domain]\nsize_um = [2, 4]\nspacing_um = 0.25\n[time]\n[run]\nsteps = 1\n";
  const std::string n = parse_error(neither);
  EXPECT_CONTAINS(n, "scenes/x.toml:4: missing key: give exactly one of 'time.step_s' or 'time.tau'");
  EXPECT_CONTAINS(parse_error("[domain]\nsize_um = [2, 4]\nspacing_um = 0.25\n[run]\nsteps = 1\n"),
                  "scenes/x.toml: missing key: give exactly one of 'time.step_s' or 'time.tau'");

  EXPECT_CONTAINS(parse_error(minimal + "[run]\nduration_s = 1e-3\n"), "malformed TOML");  // [run] twice
  EXPECT_CONTAINS(parse_error(minimal, {"run.duration_s=1e-3", "run.steps=5"}),
                  "key 'run.duration_s' = 0.001 conflicts with 'run.steps' = 5 (scenes/x.toml: --set run.steps=5)");
  EXPECT_CONTAINS(parse_error("[domain]\nsize_um = [2, 4]\nspacing_um = 0.25\n[time]\ntau = 1\n"),
                  "missing key: give exactly one of 'run.steps' or 'run.duration_s'");
  EXPECT_CONTAINS(parse_error("[time]\ntau = 1\n[run]\nsteps = 1\n"), "missing key 'domain.size_um'");
}

TEST(SceneParser, MissingFile) {
  const std::string m = error_of([] { load_scene("/nonexistent/scene.toml"); });
  EXPECT_CONTAINS(m, "cannot read scene file '/nonexistent/scene.toml': no such file");
}

TEST(SceneParser, LoadFromFileNamesThePath) {
  const auto path = std::filesystem::temp_directory_path() / "erythro_unit_scene_load.toml";
  {
    std::ofstream out(path);
    out << minimal << "[fluid]\nviscosity_cP = 0\n";
  }
  const std::string m = error_of([&] { load_scene(path.string()); });
  EXPECT_CONTAINS(m, path.string() + ":10: key 'fluid.viscosity_cP' = 0 is out of range");
  {
    std::ofstream out(path);
    out << minimal;
  }
  const Scene s = load_scene(path.string(), {"fluid.viscosity_cP=2"});
  EXPECT_EQ(s.source_path, path.string());
  EXPECT_EQ(s.name, "erythro_unit_scene_load");
  EXPECT_EQ(s.fluid.viscosity_cP, 2.0);
  std::filesystem::remove(path);
}

TEST(SceneOverrides, NumberStringBareWordAndArray) {
  const Scene s = parse_scene(minimal, "x.toml",
                              {"fluid.viscosity_cP=2", "scene.name=\"quoted name\"", "fluid.collision=trt",
                               "domain.size_um=[4, 8]", "time.tau = 0.75", "scene.description=a bare sentence"});
  EXPECT_EQ(s.fluid.viscosity_cP, 2.0);
  EXPECT_EQ(s.name, "quoted name");
  EXPECT_EQ(s.fluid.collision, "trt");
  EXPECT_EQ(s.domain.size_um, (std::array<double, 2>{4.0, 8.0}));
  EXPECT_EQ(s.time.tau, 0.75);
  EXPECT_EQ(s.description, "a bare sentence");
  // The recorded text is what ran.
  EXPECT_CONTAINS(s.source_text, "collision = 'trt'");
  EXPECT_CONTAINS(s.source_text, "tau = 0.75");
  const Scene again = parse_scene(s.source_text, "x.toml");
  EXPECT_EQ(again.fluid.collision, "trt");
  EXPECT_EQ(again.domain.size_um, s.domain.size_um);
}

TEST(SceneOverrides, OneOfAnExclusivePairReplacesTheOther) {
  const Scene s = parse_scene(minimal, "x.toml", {"time.step_s=1e-8", "run.duration_s=1e-3"});
  EXPECT_FALSE(s.time.tau);
  EXPECT_EQ(s.time.step_s, 1e-8);
  EXPECT_FALSE(s.run.steps);
  EXPECT_EQ(s.run.duration_s, 1e-3);
  EXPECT_EQ(s.source_text.find("tau"), std::string::npos) << s.source_text;
}

TEST(SceneOverrides, CreatesMissingTables) {
  const Scene s = parse_scene(minimal, "x.toml", {"body_force.density_N_m3=[1e3, 0]", "boundaries.top.type=wall",
                                                  "boundaries.bottom.type=wall", "run.steady_state.tolerance=1e-6"});
  ASSERT_TRUE(s.body_force);
  EXPECT_EQ(s.body_force->density_N_m3[0], 1e3);
  EXPECT_EQ(s.boundaries.top.type, "wall");
  ASSERT_TRUE(s.run.steady_state);
  EXPECT_EQ(s.run.steady_state->tolerance, 1e-6);
  EXPECT_EQ(s.run.steady_state->check_interval_steps, 100);
}

TEST(SceneOverrides, ErrorsSayTheyCameFromSet) {
  const std::string unknown = parse_error(minimal, {"fluid.viscosty_cP=1"});
  EXPECT_CONTAINS(unknown, "scenes/x.toml: --set fluid.viscosty_cP=1: unknown key 'fluid.viscosty_cP'");
  EXPECT_CONTAINS(unknown, "(did you mean 'fluid.viscosity_cP'?)");

  EXPECT_EQ(parse_error(minimal, {"fluid.viscosity_cP=-1"}),
            "scenes/x.toml: --set fluid.viscosity_cP=-1: key 'fluid.viscosity_cP' = -1 is out of range: must be in [1e-30, 1e+30] (cP)");
  EXPECT_CONTAINS(parse_error(minimal, {"fluid.collision=mrt"}), "--set fluid.collision=mrt: key 'fluid.collision' = \"mrt\"");
  EXPECT_CONTAINS(parse_error(minimal, {"run.steps=1.5"}), "--set run.steps=1.5: key 'run.steps' = 1.5 has the wrong type");
  EXPECT_CONTAINS(parse_error(minimal, {"fluid.viscosity_cP"}), "malformed --set 'fluid.viscosity_cP': expected KEY=VALUE");
  EXPECT_CONTAINS(parse_error(minimal, {"=3"}), "malformed --set");
  EXPECT_CONTAINS(parse_error(minimal, {"run.steps=1\nx = 2"}), "must be a single TOML value");
}

}  // namespace
}  // namespace erythro::scene
