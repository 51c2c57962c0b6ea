// The resource estimate of `erythro check` and `erythro run` (scene/resource_estimate.hpp):
// the counts it is built from, on a plain channel.
#include <gtest/gtest.h>

#include "scene/resource_estimate.hpp"
#include "scene_fixtures.hpp"

namespace erythro::scene {
namespace {

using testing::channel_scene;

TEST(ResourceEstimate, CountsTheFluidArraysAndTheSnapshots) {
  // 16 × 8 nodes, 10 steps, fields every 3 steps: written at 0, 3, 6, 9 and the last, 10.
  const Scene s = parse_scene(channel_scene("8.0, 4.0", "0.5", "0.8", "10"), "test.toml",
                              {"output.fields_interval_steps=3", "output.diagnostics_interval_steps=5"});
  const ResourceEstimate e = estimate_resources(s, derive_lattice(s));
  const double nodes = 16.0 * 8.0;
  ASSERT_EQ(e.memory.size(), 2u);  // populations and moments: no cells, layers or transport
  EXPECT_DOUBLE_EQ(e.memory[0].bytes, 9.0 * nodes * 8.0);
  EXPECT_DOUBLE_EQ(e.memory[1].bytes, 3.0 * nodes * 8.0);
  EXPECT_DOUBLE_EQ(e.field_snapshots, 5.0);
  EXPECT_DOUBLE_EQ(e.diagnostics_samples, 3.0);  // 0, 5, 10
  // Density (1) and velocity (3) per node per snapshot.
  EXPECT_DOUBLE_EQ(e.output[0].bytes, 5.0 * 4.0 * nodes * 8.0);
}

TEST(ResourceEstimate, ReportSaysItIsAnEstimate) {
  const Scene s = parse_scene(channel_scene("8.0, 4.0", "0.5", "0.8", "10"), "test.toml");
  const std::string text = format_resource_report(estimate_resources(s, derive_lattice(s)));
  EXPECT_NE(text.find("memory (estimate)"), std::string::npos) << text;
  EXPECT_NE(text.find("output run.h5 (estimate)"), std::string::npos) << text;
  EXPECT_EQ(format_bytes(2.5e9), "2.5 GB");
  EXPECT_EQ(format_bytes(999.0), "999 B");
}

}  // namespace
}  // namespace erythro::scene
