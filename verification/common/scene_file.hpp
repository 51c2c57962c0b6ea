#pragma once
// A case's scene file read once, then parsed with overrides as often as a study needs
// (vv::case_scene reads the file each time), and the override values that reproduce
// given lattice values bit for bit.
//
// A case states its set-up in lattice units (τ, U = 0.05·16/N, F = 8νU/N², …) and its
// scene in physical ones; units.cpp converts with a few roundings (u_lat = u Δt/h, …),
// so the nearest physical value may land an ulp or two off. exact_preimage() searches
// the doubles around it for one whose conversion is the lattice value itself, so the
// run is the one the case's reference values describe, to the last bit (when such a
// double exists; otherwise the nearest, an ulp away).
#include <functional>
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

// The double x near `rough` for which to_lattice(x) == target exactly (to_lattice
// increasing or decreasing in x, e.g. an override's lattice value): a secant step from
// `rough`, then a walk one ulp at a time across the target. When no double maps onto
// the target, the one whose image is nearest.
double exact_preimage(const std::function<double(double)>& to_lattice, double target, double rough);

// `overrides` plus one more.
std::vector<std::string> with(std::vector<std::string> overrides, const std::string& more);

}  // namespace erythro::vv
