#pragma once
// The key reference of docs/scenes.md: one Markdown table per scene table (key, type, unit,
// default, allowed values, meaning), generated from the scene schema (scene_keys.cpp) by
// `erythro schema` (docs/cli.md).
#include <string>

namespace erythro::scene {

// The section's text, ending in a newline.
std::string key_reference_markdown();

}  // namespace erythro::scene
