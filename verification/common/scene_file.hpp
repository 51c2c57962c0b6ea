#pragma once
// A case's scene file read once, then parsed with overrides as often as a study needs
// (vv::case_scene reads the file each time; a study searching exact inputs,
// common/lattice_inputs.hpp, parses the scene many times per run).
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/units.hpp"

namespace erythro::vv {

class SceneFile {
 public:
  // `relative_path` from the source tree ($ERYTHRO_SOURCE_DIR), as vv::case_scene.
  explicit SceneFile(const std::string& relative_path);
  // Parsed with the overrides (vv::set), as `erythro run FILE --set ...` reads it.
  scene::Scene scene(const std::vector<std::string>& overrides = {}) const;
  // Derived to lattice units (InputError for an impossible set-up).
  scene::LatticeSetup setup(const std::vector<std::string>& overrides = {}) const;

 private:
  std::string path_, text_;
};

// `overrides` plus one more.
std::vector<std::string> with(std::vector<std::string> overrides, const std::string& more);

}  // namespace erythro::vv
