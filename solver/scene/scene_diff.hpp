#pragma once
// Which keys differ between two versions of a scene, and which of them a restart may
// change (docs/cli.md "Checkpoints and restart"): `erythro run --restart` refuses a scene
// that differs from the checkpoint's except in run length and output intervals.
#include <string>
#include <vector>

namespace erythro::scene {

// The keys whose values differ between two scene texts (TOML, as Scene::source_text holds
// them), as dotted paths ("fluid.viscosity_cP", "cells[1].center_um"); a key set in one text
// only counts as changed. Sorted.
std::vector<std::string> changed_keys(const std::string& before, const std::string& after);

// Whether a restart may change `key`: run.duration_s, run.steps and the output intervals
// (output.fields_interval_steps, output.diagnostics_interval_steps,
// output.checkpoint_interval_steps, output.checkpoint_interval_s).
bool restart_may_change(const std::string& key);

}  // namespace erythro::scene
