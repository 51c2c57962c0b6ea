// The example scenes in scenes/ load, pass every check, and stay small enough for CI.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene_parser.hpp"
#include "scene/units.hpp"

namespace erythro::scene {
namespace {

LatticeSetup load(const std::string& name, Scene& scene) {
  scene = load_scene(std::string(ERYTHRO_SCENES_DIR) + "/" + name);
  return derive_lattice(scene);
}

// Node updates at most: the CI budget is < 3 s per scene.
constexpr double max_node_updates = 2e7;

TEST(ExampleScenes, Poiseuille) {
  Scene s;
  const LatticeSetup L = load("poiseuille.toml", s);
  EXPECT_EQ(s.name, "poiseuille");
  EXPECT_EQ(L.grid.ny, 32);
  EXPECT_LE(static_cast<double>(L.grid.size()) * static_cast<double>(L.total_steps), max_node_updates);
  // The comment header promises u_max = F H²/(8μ) = 1000 µm/s.
  EXPECT_NEAR(L.expected_max_speed * L.scales.velocity_m_s() * 1e6, 1000.0, 1e-9);
}

TEST(ExampleScenes, Couette) {
  Scene s;
  const LatticeSetup L = load("couette.toml", s);
  EXPECT_EQ(L.boundaries.top.type, fluid::SideType::moving_wall);
  EXPECT_LE(static_cast<double>(L.grid.size()) * static_cast<double>(L.total_steps), max_node_updates);
  EXPECT_NEAR(L.boundaries.top.ux * L.scales.velocity_m_s() * 1e6, 1000.0, 1e-9);
}

TEST(ExampleScenes, TaylorGreen) {
  Scene s;
  const LatticeSetup L = load("taylor_green.toml", s);
  EXPECT_EQ(L.grid.nx, 32);
  EXPECT_EQ(L.total_steps, 113);
  EXPECT_LE(static_cast<double>(L.grid.size()) * static_cast<double>(L.total_steps), max_node_updates);
  EXPECT_FALSE(format_lattice_report(s, L).empty());
}

TEST(ExampleScenes, CapsuleShear) {
  Scene s;
  const LatticeSetup L = load("capsule_shear.toml", s);
  ASSERT_TRUE(L.membrane.has_value());
  EXPECT_EQ(L.membrane->cells.size(), 1u);
  EXPECT_TRUE(L.membrane->stability.acceptable());
  EXPECT_LE(static_cast<double>(L.grid.size()) * static_cast<double>(L.total_steps), max_node_updates);
}

TEST(ExampleScenes, ContinuumArterioleInBothGeometries) {
  // The [no_o2] scenes: the same five compartments, the core's NO rate by R4 for a 3 µm
  // cell-free layer in a 25 µm lumen (docs/model.md §7c), planar and axisymmetric.
  for (const std::string name : {"arteriole_no_o2.toml", "arteriole_no_o2_axisymmetric.toml"}) {
    Scene s;
    const LatticeSetup L = load(name, s);
    ASSERT_TRUE(L.transport && L.transport->no_o2) << name;
    EXPECT_EQ(L.transport->axisymmetric_inner_radius.has_value(), name != "arteriole_no_o2.toml") << name;
    const NoO2Setup& n = *L.transport->no_o2;
    EXPECT_EQ(n.bands.size(), 5u);
    EXPECT_DOUBLE_EQ(n.cell_free_layer_um, 3.0);
    EXPECT_DOUBLE_EQ(n.core_radius_um, 25.0);
    EXPECT_NEAR(n.model[transport::Compartment::core].no_decay, 0.5 * 382.5 * (1.0 + 625.0 / 484.0), 1e-9);
    EXPECT_DOUBLE_EQ(n.model[transport::Compartment::endothelium].no_R_max, 50.0);
  }
}

}  // namespace
}  // namespace erythro::scene
