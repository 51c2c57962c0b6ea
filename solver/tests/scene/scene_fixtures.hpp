#pragma once
// Shared by the scene tests: the text of a water-filled channel scene, and its
// derivation to lattice units.
#include <string>
#include <vector>

#include "scene/scene_parser.hpp"
#include "scene/units.hpp"

namespace erythro::scene::testing {

// A size_um = [`size`] channel with spacing `spacing` µm, relaxation time `tau` and
// `steps` steps, filled with water (1000 kg/m³, 1 cP); walls at bottom and top,
// or periodic on every side if `walls` is false. Values are given as TOML text so
// that tests can edit the scene by finding, e.g., "tau = 0.8".
inline std::string channel_scene(const std::string& size, const std::string& spacing, const std::string& tau,
                                 const std::string& steps, bool walls = true) {
  return "\n[domain]\nsize_um = [" + size + "]\nspacing_um = " + spacing + "\n[time]\ntau = " + tau +
         "\n[fluid]\ndensity_kg_m3 = 1000\nviscosity_cP = 1.0\n" +
         (walls ? "[boundaries.bottom]\ntype = \"wall\"\n[boundaries.top]\ntype = \"wall\"\n" : "") +
         "[run]\nsteps = " + steps + "\n";
}

inline LatticeSetup derive(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return derive_lattice(parse_scene(text, "test.toml", overrides));
}

}  // namespace erythro::scene::testing
