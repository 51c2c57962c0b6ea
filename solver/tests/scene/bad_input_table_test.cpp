// Bad inputs, as a user gives them (`erythro check SCENE --set key=value`), on every example
// scene: each must end in an InputError whose message names the key, never in another
// exception, a crash, or a message about a quantity derived from it (issue 17).
//
// Two tables: every numeric key of the schema with values outside its range (NaN, ±inf,
// ±1e308, just past each end, the extreme 64-bit integers), generated from the schema so a
// new key is covered when it is declared; and values inside the keys' own ranges that a
// set-up check must reject (τ too large, TRT τ− at ½, a cell larger than the domain, ...).
#include <gtest/gtest.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "scene/scene_parser.hpp"
#include "scene/scene_schema.hpp"
#include "scene/units.hpp"

namespace erythro::scene {
namespace {

using detail::Kind;
using detail::KeySpec;

struct BadInput {
  std::string scene;                   // file name in scenes/
  std::vector<std::string> overrides;  // --set arguments
  std::string key;                     // the key the message must name
};

std::string scene_path(const std::string& name) { return std::string(ERYTHRO_SCENES_DIR) + "/" + name; }

std::vector<std::string> example_scenes() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(ERYTHRO_SCENES_DIR))
    if (e.path().extension() == ".toml") out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// The outcome of `check`: "" when an InputError names `key`, else what happened instead.
std::string outcome(const BadInput& in) {
  try {
    const Scene s = load_scene(scene_path(in.scene), in.overrides);
    derive_lattice(s);
    return "accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    return m.find(in.key) != std::string::npos ? "" : "InputError not naming the key: " + m;
  } catch (const std::exception& e) {
    return std::string("other exception: ") + e.what();
  }
}

std::string describe(const BadInput& in) {
  std::string s = in.scene;
  for (const std::string& o : in.overrides) s += " --set " + o;
  return s;
}

// Out-of-range values of a key (TOML text): past each end of its bound, and the extremes.
std::vector<std::string> out_of_range_values(const KeySpec& k) {
  const detail::Bound& b = k.bound;
  if (k.kind == Kind::integer) {
    const auto text = [](double v) { return std::to_string(static_cast<std::int64_t>(v)); };
    return {text(b.lo - 1.0), text(b.hi + 1.0), "-9223372036854775808", "9223372036854775807"};
  }
  std::vector<std::string> out = {"nan", "inf", "-inf", "1e308", "-1e308"};
  const double edges[] = {b.lo_open ? b.lo : b.lo - std::max(1.0, std::abs(b.lo)), b.hi * 10.0,
                          5e-324 /* the smallest double: below every positive bound */};
  for (const double v : edges)
    if (!b.contains(v)) out.push_back(detail::format_number(v));
  return out;
}

// Whether `--set path=...` reaches the key's own check in this scene: an [[array]] entry must
// exist (--set adds none), and [hemoglobin] and [aggregation] are read only when the scene has
// them (without them a set key creates a table that is refused as a whole first).
bool settable(const toml::table& scene, const std::string& key, std::string& path) {
  for (const char* array : {"fluid.layers", "transport.layers", "no_o2.layers", "cells", "species", "stop_when"}) {
    const std::string prefix = std::string(array) + ".";
    if (key.rfind(prefix, 0) != 0) continue;
    const toml::array* a = scene.at_path(array).as_array();
    if (!a || a->empty()) return false;
    path = std::string(array) + "[0]." + key.substr(prefix.size());
    return true;
  }
  path = key;
  for (const char* gated : {"hemoglobin", "aggregation", "no_o2"})
    if (key.rfind(std::string(gated) + ".", 0) == 0 && !scene.contains(gated)) return false;
  return true;
}

std::vector<BadInput> schema_table() {
  std::vector<BadInput> out;
  for (const std::string& name : example_scenes()) {
    const toml::table scene = toml::parse_file(scene_path(name));
    for (const KeySpec& k : detail::known_keys()) {
      if (k.kind != Kind::number && k.kind != Kind::integer && k.kind != Kind::vec2) continue;
      std::string path;
      if (!settable(scene, k.path, path)) continue;
      for (const std::string& v : out_of_range_values(k)) {
        if (k.kind != Kind::vec2) {
          out.push_back({name, {path + "=" + v}, path});
          continue;
        }
        // One bad component beside a good one, in either place.
        const std::string good = detail::format_number(std::clamp(1.0, k.bound.lo, k.bound.hi));
        out.push_back({name, {path + "=[" + v + ", " + good + "]"}, path});
        out.push_back({name, {path + "=[" + good + ", " + v + "]"}, path});
      }
    }
  }
  return out;
}

TEST(BadInputTable, EveryNumericKeyRejectsValuesOutsideItsRangeByName) {
  const std::vector<BadInput> table = schema_table();
  EXPECT_GT(table.size(), 2000u);  // every example scene, ~100 keys, 4-8 values each
  int failures = 0;
  for (const BadInput& in : table) {
    const std::string what = outcome(in);
    if (what.empty()) continue;
    ADD_FAILURE() << describe(in) << ": " << what;
    if (++failures == 20) break;  // enough to see the pattern
  }
}

// Values inside each key's own range that the set-up checks must reject, naming the key
// that is off (and not a quantity derived from it).
TEST(BadInputTable, SetUpChecksNameTheKeyThatIsOff) {
  const std::vector<BadInput> table = {
      // τ above limits.max_tau: given, from time.step_s, and in the cells' interior.
      {"couette.toml", {"time.tau=50"}, "time.tau"},
      {"couette.toml", {"time.step_s=1"}, "time.step_s"},
      {"couette.toml", {"limits.max_tau=0.9"}, "limits.max_tau"},
      {"couette.toml", {"limits.max_tau=0.5001"}, "limits.max_tau"},
      {"couette.toml", {"limits.min_tau_margin=20"}, "limits.min_tau_margin"},
      {"doublet_shear.toml", {"membrane.interior_viscosity_cP=100"}, "membrane.interior_viscosity_cP"},
      // TRT: τ− = ½ + Λ/(τ − ½) → ½ for a small Λ or a large τ.
      {"poiseuille.toml", {"fluid.collision=trt", "fluid.trt_magic=1e-6"}, "fluid.trt_magic"},
      {"poiseuille.toml", {"fluid.collision=trt", "fluid.trt_magic=1e-30"}, "fluid.trt_magic"},
      {"poiseuille.toml", {"fluid.collision=trt", "fluid.trt_magic=0.001", "time.tau=9"}, "fluid.trt_magic"},
      // Huge or tiny physical values: the message names them, not the run length or Mach.
      {"poiseuille.toml", {"fluid.viscosity_cP=1e29"}, "fluid.viscosity_cP"},
      {"poiseuille.toml", {"fluid.density_kg_m3=1e-30"}, "fluid.density_kg_m3"},
      {"couette.toml", {"fluid.viscosity_cP=1e-30"}, "fluid.viscosity_cP"},
      {"taylor_green.toml", {"domain.spacing_um=1e-30"}, "domain.spacing_um"},
      {"taylor_green.toml", {"domain.size_um=[1e30, 1e30]"}, "domain.size_um"},
      {"taylor_green.toml", {"run.duration_s=1e30"}, "run.duration_s"},
      {"couette.toml", {"boundaries.top.velocity_um_s=[1e30, 0]"}, "boundaries.top.velocity_um_s"},
      {"taylor_green.toml", {"initial.velocity_um_s=[1e30, 0]"}, "initial.velocity_um_s"},
      {"poiseuille.toml", {"body_force.density_N_m3=[1e30, 0]"}, "body_force.density_N_m3"},
      // Cells: far outside, larger than the domain, too many markers.
      {"capsule_shear.toml", {"cells[0].center_um=[1e20, 5]"}, "cells[0].center_um"},
      {"capsule_shear.toml", {"cells[0].center_um=[10, -1e20]"}, "cells[0].center_um"},
      {"capsule_shear.toml", {"cells[0].radius_um=1e20"}, "cells[0].radius_um"},
      {"capsule_shear.toml", {"cells[0].scale=1e20"}, "cells[0].radius_um"},
      {"doublet_shear.toml", {"cells[1].radius_um=1e6"}, "cells[1].radius_um"},
      {"capsule_shear.toml", {"cells[0].markers=1000000"}, "cells[0].markers"},
      {"capsule_shear.toml", {"membrane.shear_modulus_dyn_cm=1e30"}, "membrane.shear_modulus_dyn_cm"},
      {"capsule_shear.toml", {"membrane.bending_modulus_dyn_cm=1e30"}, "membrane.bending_modulus_dyn_cm"},
      // Transport: a step too small for the run, too large for the diffusivity.
      {"rbc_deoxygenation.toml", {"transport.time_step_s=1e-30"}, "transport.time_step_s"},
      {"rbc_deoxygenation.toml", {"species[0].diffusivity_um2_s=1e30"}, "species[0].diffusivity_um2_s"},
  };
  for (const BadInput& in : table) {
    const std::string what = outcome(in);
    EXPECT_TRUE(what.empty()) << describe(in) << ": " << what;
  }
}

}  // namespace
}  // namespace erythro::scene
