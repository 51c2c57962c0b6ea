#include "scene_file.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
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

double exact_preimage(const std::function<double(double)>& to_lattice, double target, double rough) {
  // Two secant steps from `rough` (the conversions are affine up to rounding): the second
  // spans `rough` to the first estimate, so its slope is exact to round-off even when
  // `rough` was far off.
  const double x1 = rough == 0.0 ? 1.0 : rough, x2 = x1 * (1.0 + 1e-6);
  const double y1 = to_lattice(x1);
  if (y1 == target) return x1;
  const double y2 = to_lattice(x2);
  const bool increasing = y2 >= y1;
  double x = y2 == y1 ? x1 : x1 + (target - y1) * (x2 - x1) / (y2 - y1);
  double y = to_lattice(x);
  if (y == target) return x;
  if (y != y1) {
    x = x1 + (target - y1) * (x - x1) / (y - y1);
    y = to_lattice(x);
    if (y == target) return x;
  }
  // Walk one ulp at a time towards the target until its image reaches or passes it.
  const double toward = (target > y) == increasing ? std::numeric_limits<double>::infinity()
                                                   : -std::numeric_limits<double>::infinity();
  double best = x, best_miss = std::abs(y - target);
  for (int k = 0; k < 4096; ++k) {
    const bool below = y < target;
    x = std::nextafter(x, toward);
    y = to_lattice(x);
    if (y == target) return x;
    if (std::abs(y - target) < best_miss) best = x, best_miss = std::abs(y - target);
    if ((y < target) != below) break;  // passed it: no double maps onto the target
  }
  return best;
}

std::vector<std::string> with(std::vector<std::string> overrides, const std::string& more) {
  overrides.push_back(more);
  return overrides;
}

}  // namespace erythro::vv
