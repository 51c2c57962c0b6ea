#pragma once
// Reads a TOML scene file into a Scene. Unknown keys, wrong types and out-of-range
// values are errors (InputError naming file, line, key and the allowed range).
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace erythro::scene {

// `overrides` are "dotted.key=value" strings from --set; the value is TOML
// (numbers, strings in quotes or bare words, arrays). They are applied before
// validation, so an override of an unknown key is an error too.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Same, from text (tests; `origin` names the text in messages).
Scene parse_scene(const std::string& text, const std::string& origin,
                  const std::vector<std::string>& overrides = {});

}  // namespace erythro::scene
