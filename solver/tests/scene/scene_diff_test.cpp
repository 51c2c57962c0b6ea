// What a restart may change of a scene (scene/scene_diff.hpp): the changed keys are named
// by their dotted path, entries of [[cells]] by index; only run length and output
// intervals are safe.
#include <gtest/gtest.h>

#include "scene/scene_diff.hpp"

using namespace erythro;

namespace {
const std::string kScene = R"([fluid]
viscosity_cP = 1.2
[run]
duration_s = 1e-4
[[cells]]
radius_um = 2.0
[[cells]]
radius_um = 3.0
)";
}  // namespace

TEST(SceneDiff, NamesChangedAddedAndRemovedKeys) {
  EXPECT_TRUE(scene::changed_keys(kScene, kScene).empty());
  std::string changed = kScene;
  changed.replace(changed.find("3.0"), 3, "3.5");
  changed.replace(changed.find("duration_s = 1e-4"), 17, "steps = 400");
  changed += "[output]\nfields_interval_steps = 10\n";
  EXPECT_EQ(scene::changed_keys(kScene, changed),
            (std::vector<std::string>{"cells[1].radius_um", "output.fields_interval_steps", "run.duration_s", "run.steps"}));
}

TEST(SceneDiff, OnlyRunLengthAndOutputIntervalsAreSafe) {
  for (const char* key : {"run.duration_s", "run.steps", "output.fields_interval_steps",
                          "output.diagnostics_interval_steps", "output.checkpoint_interval_steps",
                          "output.checkpoint_interval_s"})
    EXPECT_TRUE(scene::restart_may_change(key)) << key;
  for (const char* key : {"fluid.viscosity_cP", "cells[1].radius_um", "output.fields", "run.steady_state.tolerance"})
    EXPECT_FALSE(scene::restart_may_change(key)) << key;
}
