#include "scene_file.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "scene/scene_parser.hpp"

namespace erythro::vv {

SceneFile::SceneFile(const std::string& relative_path) {
  const char* dir = std::getenv("ERYTHRO_SOURCE_DIR");
  if (!dir || !*dir) throw InputError("ERYTHRO_SOURCE_DIR is not set (ctest sets it; run the case through ctest)");
  path_ = (std::filesystem::path(dir) / relative_path).string();
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw InputError("cannot read scene file '" + path_ + "'");
  std::ostringstream text;
  text << in.rdbuf();
  text_ = text.str();
}

scene::Scene SceneFile::scene(const std::vector<std::string>& overrides) const {
  return scene::parse_scene(text_, path_, overrides);
}

scene::LatticeSetup SceneFile::setup(const std::vector<std::string>& overrides) const {
  return scene::derive_lattice(scene(overrides));
}

std::vector<std::string> with(std::vector<std::string> overrides, const std::string& more) {
  overrides.push_back(more);
  return overrides;
}

}  // namespace erythro::vv
