// The scene schema (scene_keys.cpp) is the one source of the keys' defaults: a scene that
// leaves a key out gets the schema's default literal, key by key, and so do the struct
// initialisers of scene.hpp (programmatic scenes). Every key is documented in the generated
// key reference of docs/scenes.md.
#include <gtest/gtest.h>

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "scene/key_reference.hpp"
#include "scene/scene_parser.hpp"
#include "scene/scene_schema.hpp"

namespace erythro::scene {
namespace {

using detail::Kind;
using detail::KeySpec;
using Value = std::variant<double, long, bool, std::string, std::array<double, 2>, std::vector<std::string>>;

// A scene with every table that has keys with literal defaults, and only the keys that are
// required or have no literal default.
const std::string every_table = R"(
[domain]
size_um = [20.0, 20.0]
spacing_um = 0.5
[time]
tau = 1.0
[run]
steps = 10
[run.steady_state]
[body_force]
[[fluid.layers]]
y_um = [0.0, 5.0]
viscosity_cP = 6.0
[[stop_when]]
series = "step"
below = 1.0
[membrane]
[[cells]]
radius_um = 3.0
center_um = [10.0, 10.0]
[[cell_populations]]
radius_um = 2.0
count = 1
[aggregation]
de_star = 1.0
[repulsion]
[transport]
[[species]]
name = "O2"
diffusivity_um2_s = 2800.0
[[transport.layers]]
species = "O2"
y_um = [0.0, 5.0]
[[species]]
name = "NO"
diffusivity_um2_s = 3300.0
[no_o2]
[[no_o2.layers]]
compartment = "core"
y_um = [0.0, 5.0]
[hemoglobin]
)";

// Where each key with a literal default lands in a Scene (its first entry, for [[arrays]]).
using Accessor = std::function<Value(const Scene&)>;
const std::map<std::string, Accessor>& accessors() {
  static const std::map<std::string, Accessor> a = [] {
    std::map<std::string, Accessor> m = {
        {"scene.description", [](const Scene& s) -> Value { return s.description; }},
        {"membrane.area_correction", [](const Scene& s) -> Value { return s.membrane->area_correction; }},
        {"fluid.density_kg_m3", [](const Scene& s) -> Value { return s.fluid.density_kg_m3; }},
        {"fluid.viscosity_cP", [](const Scene& s) -> Value { return s.fluid.viscosity_cP; }},
        {"domain.geometry", [](const Scene& s) -> Value { return s.domain.geometry; }},
        {"domain.inner_radius_um", [](const Scene& s) -> Value { return s.domain.inner_radius_um; }},
        {"fluid.collision", [](const Scene& s) -> Value { return s.fluid.collision; }},
        {"fluid.trt_magic", [](const Scene& s) -> Value { return s.fluid.trt_magic; }},
        {"body_force.density_N_m3", [](const Scene& s) -> Value { return s.body_force->density_N_m3; }},
        {"body_force.frequency_Hz", [](const Scene& s) -> Value { return s.body_force->frequency_Hz; }},
        {"body_force.phase_rad", [](const Scene& s) -> Value { return s.body_force->phase_rad; }},
        {"initial.type", [](const Scene& s) -> Value { return s.initial.type; }},
        {"cell_populations.shape", [](const Scene& s) -> Value { return s.cell_populations[0].shape; }},
        {"cell_populations.seed", [](const Scene& s) -> Value { return s.cell_populations[0].seed; }},
        {"cell_populations.attempts_per_cell",
         [](const Scene& s) -> Value { return s.cell_populations[0].attempts_per_cell; }},
        {"initial.velocity_um_s", [](const Scene& s) -> Value { return s.initial.velocity_um_s; }},
        {"initial.non_equilibrium", [](const Scene& s) -> Value { return s.initial.non_equilibrium; }},
        {"run.steady_state.tolerance", [](const Scene& s) -> Value { return s.run.steady_state->tolerance; }},
        {"run.steady_state.check_interval_steps",
         [](const Scene& s) -> Value { return s.run.steady_state->check_interval_steps; }},
        {"monitor.interval_steps", [](const Scene& s) -> Value { return s.monitor.interval_steps; }},
        {"monitor.max_mach", [](const Scene& s) -> Value { return s.monitor.max_mach; }},
        {"monitor.max_area_change", [](const Scene& s) -> Value { return s.monitor.max_area_change; }},
        {"monitor.max_edge_strain", [](const Scene& s) -> Value { return s.monitor.max_edge_strain; }},
        {"output.fields_interval_steps", [](const Scene& s) -> Value { return s.output.fields_interval_steps; }},
        {"output.diagnostics_interval_steps",
         [](const Scene& s) -> Value { return s.output.diagnostics_interval_steps; }},
        {"output.fields", [](const Scene& s) -> Value { return s.output.fields; }},
        {"output.extremes_interval_steps", [](const Scene& s) -> Value { return s.output.extremes_interval_steps; }},
        {"output.dense_diagnostics_steps", [](const Scene& s) -> Value { return s.output.dense_diagnostics_steps; }},
        {"output.checkpoint_interval_steps", [](const Scene& s) -> Value { return s.output.checkpoint_interval_steps; }},
        {"output.checkpoint_interval_s", [](const Scene& s) -> Value { return s.output.checkpoint_interval_s; }},
        {"stop_when.compare",
         [](const Scene& s) -> Value {
           return std::string(s.stop_when.at(0).compare_window_means ? "window_means" : "samples");
         }},
        {"stop_when.min_steps", [](const Scene& s) -> Value { return s.stop_when.at(0).min_steps; }},
        {"stop_when.after_steps", [](const Scene& s) -> Value { return s.stop_when.at(0).after_steps; }},
        {"limits.min_tau_margin", [](const Scene& s) -> Value { return s.limits.min_tau_margin; }},
        {"limits.max_tau", [](const Scene& s) -> Value { return s.limits.max_tau; }},
        {"limits.max_mach", [](const Scene& s) -> Value { return s.limits.max_mach; }},
        {"limits.min_nodes_across_channel",
         [](const Scene& s) -> Value { return static_cast<long>(s.limits.min_nodes_across_channel); }},
        {"limits.membrane_stability", [](const Scene& s) -> Value { return s.limits.membrane_stability; }},
        {"limits.max_marker_spacing", [](const Scene& s) -> Value { return s.limits.max_marker_spacing; }},
        {"limits.min_cell_gap", [](const Scene& s) -> Value { return s.limits.min_cell_gap; }},
        {"membrane.law", [](const Scene& s) -> Value { return s.membrane->law; }},
        {"membrane.shear_modulus_dyn_cm", [](const Scene& s) -> Value { return s.membrane->shear_modulus_dyn_cm; }},
        {"membrane.bending_modulus_dyn_cm", [](const Scene& s) -> Value { return s.membrane->bending_modulus_dyn_cm; }},
        {"membrane.area_modulus_Pa", [](const Scene& s) -> Value { return s.membrane->area_modulus_Pa; }},
        {"membrane.skalak_c", [](const Scene& s) -> Value { return s.membrane->skalak_c; }},
        {"membrane.kernel", [](const Scene& s) -> Value { return s.membrane->kernel; }},
        {"membrane.interior_method", [](const Scene& s) -> Value { return s.membrane->interior_method; }},
        {"membrane.index_update_interval", [](const Scene& s) -> Value { return s.membrane->index_update_interval; }},
        {"cells.shape", [](const Scene& s) -> Value { return s.cells.at(0).shape; }},
        {"cells.angle_deg", [](const Scene& s) -> Value { return s.cells.at(0).angle_deg; }},
        {"cells.scale", [](const Scene& s) -> Value { return s.cells.at(0).scale; }},
        {"cells.prestretch", [](const Scene& s) -> Value { return s.cells.at(0).prestretch; }},
        {"aggregation.zero_force_distance_um",
         [](const Scene& s) -> Value { return s.aggregation->zero_force_distance_um; }},
        {"aggregation.decay_per_um", [](const Scene& s) -> Value { return s.aggregation->decay_per_um; }},
        {"repulsion.pressure_Pa", [](const Scene& s) -> Value { return s.repulsion->pressure_Pa; }},
        {"repulsion.walls", [](const Scene& s) -> Value { return s.repulsion->walls; }},
        {"transport.coupling", [](const Scene& s) -> Value { return s.transport->coupling; }},
        {"transport.stencil", [](const Scene& s) -> Value { return s.transport->stencil; }},
        {"transport.collision", [](const Scene& s) -> Value { return s.transport->collision; }},
        {"transport.trt_magic", [](const Scene& s) -> Value { return s.transport->trt_magic; }},
        {"transport.cell_representation", [](const Scene& s) -> Value { return s.transport->cell_representation; }},
        {"transport.interface", [](const Scene& s) -> Value { return s.transport->interface; }},
        {"transport.layer_mean", [](const Scene& s) -> Value { return s.transport->layer_mean; }},
        {"transport.readout", [](const Scene& s) -> Value { return s.transport->readout; }},
        {"species.initial_uM", [](const Scene& s) -> Value { return s.species.at(0).initial_uM; }},
        {"species.source_uM_per_s", [](const Scene& s) -> Value { return s.species.at(0).source_uM_per_s; }},
        {"species.decay_per_s", [](const Scene& s) -> Value { return s.species.at(0).decay_per_s; }},
        {"no_o2.no_species", [](const Scene& s) -> Value { return s.no_o2->no_species; }},
        {"no_o2.o2_species", [](const Scene& s) -> Value { return s.no_o2->o2_species; }},
        {"no_o2.wall_shear_stress_Pa", [](const Scene& s) -> Value { return s.no_o2->wall_shear_stress_Pa; }},
        {"no_o2.blood_no_scavenging_per_s",
         [](const Scene& s) -> Value { return s.no_o2->blood_no_scavenging_per_s; }},
        {"no_o2.core_po2_torr", [](const Scene& s) -> Value { return s.no_o2->core_po2_torr; }},
        {"no_o2.core_o2_exchange_per_s", [](const Scene& s) -> Value { return s.no_o2->core_o2_exchange_per_s; }},
        {"no_o2.no_consumption_per_s", [](const Scene& s) -> Value { return s.no_o2->no_consumption_per_s; }},
        {"no_o2.sm_o2_max_consumption_uM_s",
         [](const Scene& s) -> Value { return s.no_o2->sm_o2_max_consumption_uM_s; }},
        {"no_o2.tissue_o2_max_consumption_uM_s",
         [](const Scene& s) -> Value { return s.no_o2->tissue_o2_max_consumption_uM_s; }},
        {"hemoglobin.species", [](const Scene& s) -> Value { return s.hemoglobin->species; }},
        {"hemoglobin.k_off_per_s", [](const Scene& s) -> Value { return s.hemoglobin->k_off_per_s; }},
        {"hemoglobin.heme_uM", [](const Scene& s) -> Value { return s.hemoglobin->heme_uM; }},
        {"hemoglobin.solubility_uM_per_torr",
         [](const Scene& s) -> Value { return s.hemoglobin->solubility_uM_per_torr; }},
        {"hemoglobin.p50_torr", [](const Scene& s) -> Value { return s.hemoglobin->p50_torr; }},
        {"hemoglobin.hill_n", [](const Scene& s) -> Value { return s.hemoglobin->hill_n; }},
        {"hemoglobin.rate_modifier", [](const Scene& s) -> Value { return s.hemoglobin->rate_modifier; }},
        {"hemoglobin.kinetics", [](const Scene& s) -> Value { return s.hemoglobin->kinetics; }},
        {"hemoglobin.coupling", [](const Scene& s) -> Value { return s.hemoglobin->coupling; }},
        {"hemoglobin.mean_pressure", [](const Scene& s) -> Value { return s.hemoglobin->mean_pressure; }},
        {"hemoglobin.heme_weights", [](const Scene& s) -> Value { return s.hemoglobin->heme_weights; }},
    };
    const std::array<SideSpec BoundarySpec::*, 4> sides{&BoundarySpec::left, &BoundarySpec::right,
                                                        &BoundarySpec::bottom, &BoundarySpec::top};
    const std::array<const char*, 4> names{"left", "right", "bottom", "top"};
    for (std::size_t i = 0; i < 4; ++i) {
      const auto side = sides[i];
      const std::string p = std::string("boundaries.") + names[i] + ".";
      m[p + "type"] = [side](const Scene& s) -> Value { return (s.boundaries.*side).type; };
      m[p + "velocity_um_s"] = [side](const Scene& s) -> Value { return (s.boundaries.*side).velocity_um_s; };
    }
    return m;
  }();
  return a;
}

// The schema's default literal of `k` as a value of its kind.
Value literal_value(const KeySpec& k) {
  const toml::table t = toml::parse(std::string_view("v = " + k.when_absent.text));
  const toml::node& n = *t.get("v");
  const auto number = [](const toml::node& e) {
    if (!e.is_number()) throw std::runtime_error("not a number");
    return e.is_integer() ? static_cast<double>(e.as_integer()->get()) : e.as_floating_point()->get();
  };
  const auto wrong = [&] {
    return std::runtime_error(k.path + ": the default " + k.when_absent.text + " is not of the key's type");
  };
  switch (k.kind) {
    case Kind::number: return number(n);
    case Kind::integer:
      if (!n.is_integer()) throw wrong();
      return static_cast<long>(n.as_integer()->get());
    case Kind::boolean:
      if (!n.is_boolean()) throw wrong();
      return n.as_boolean()->get();
    case Kind::string:
      if (!n.is_string()) throw wrong();
      return std::string(n.as_string()->get());
    case Kind::vec2:
      if (!n.is_array() || n.as_array()->size() != 2) throw wrong();
      return std::array<double, 2>{number(*n.as_array()->get(0)), number(*n.as_array()->get(1))};
    case Kind::string_list: {
      if (!n.is_array()) throw wrong();
      std::vector<std::string> out;
      for (const toml::node& e : *n.as_array()) {
        if (!e.is_string()) throw wrong();
        out.emplace_back(e.as_string()->get());
      }
      return out;
    }
  }
  throw wrong();
}

std::vector<const KeySpec*> keys_with_literal_defaults() {
  std::vector<const KeySpec*> out;
  for (const KeySpec& k : detail::known_keys())
    if (k.when_absent.is_literal) out.push_back(&k);
  return out;
}

TEST(SceneSchema, EveryLiteralDefaultIsAnAllowedValueOfItsKind) {
  for (const KeySpec* k : keys_with_literal_defaults()) {
    SCOPED_TRACE(k->path + " = " + k->when_absent.text);
    Value v;
    ASSERT_NO_THROW(v = literal_value(*k));  // TOML, of the key's kind
    const auto allowed = [&](const std::string& s) {
      return k->choices.empty() || std::find(k->choices.begin(), k->choices.end(), s) != k->choices.end();
    };
    if (const auto* d = std::get_if<double>(&v)) {
      EXPECT_TRUE(k->bound.contains(*d));
    } else if (const auto* i = std::get_if<long>(&v)) {
      EXPECT_TRUE(k->bound.contains(static_cast<double>(*i)));
    } else if (const auto* a = std::get_if<std::array<double, 2>>(&v)) {
      EXPECT_TRUE(k->bound.contains((*a)[0]) && k->bound.contains((*a)[1]));
    } else if (const auto* s = std::get_if<std::string>(&v)) {
      EXPECT_TRUE(allowed(*s));
    } else if (const auto* l = std::get_if<std::vector<std::string>>(&v)) {
      for (const std::string& e : *l) EXPECT_TRUE(allowed(e)) << e;
    }
  }
}

TEST(SceneSchema, AParsedSceneGetsTheSchemasDefaultsKeyByKey) {
  const Scene parsed = parse_scene(every_table, "scenes/defaults.toml");
  for (const KeySpec* k : keys_with_literal_defaults()) {
    const auto a = accessors().find(k->path);
    ASSERT_NE(a, accessors().end()) << k->path << " has a literal default but no accessor in this test: add one";
    EXPECT_EQ(a->second(parsed), literal_value(*k)) << k->path << " = " << k->when_absent.text;
  }
  for (const auto& [path, accessor] : accessors()) {
    const KeySpec* k = detail::find_key(path);
    ASSERT_NE(k, nullptr) << path;
    EXPECT_TRUE(k->when_absent.is_literal) << path << " has no literal default in the schema";
  }
}

TEST(SceneSchema, TheStructInitialisersAgreeWithTheSchema) {
  Scene s;  // what a programmatic scene starts from, every module engaged
  s.body_force.emplace();
  s.run.steady_state.emplace();
  s.stop_when.emplace_back();
  s.membrane.emplace();
  s.cells.emplace_back();
  s.cell_populations.emplace_back();
  s.aggregation.emplace();
  s.repulsion.emplace();
  s.transport.emplace();
  s.species.emplace_back();
  s.hemoglobin.emplace();
  s.no_o2.emplace();
  for (const KeySpec* k : keys_with_literal_defaults())
    EXPECT_EQ(accessors().at(k->path)(s), literal_value(*k)) << k->path << " = " << k->when_absent.text;
}

TEST(SceneSchema, EveryKeyHasAMeaningATableAndARowInTheKeyReference) {
  const std::string reference = key_reference_markdown();
  for (const KeySpec& k : detail::known_keys()) {
    SCOPED_TRACE(k.path);
    EXPECT_FALSE(k.meaning.empty());
    EXPECT_FALSE(k.when_absent.text.empty() && !k.when_absent.is_literal);
    const std::string_view table = detail::table_of(k.path);
    const auto& tables = detail::known_tables();
    EXPECT_TRUE(std::any_of(tables.begin(), tables.end(), [&](const auto& t) { return t.path == table; }));
    const std::string row = "| `" + k.path.substr(table.size() + 1) + "` |";
    EXPECT_NE(reference.find(row), std::string::npos) << row;
  }
  for (const auto& t : detail::known_tables()) EXPECT_FALSE(t.meaning.empty()) << t.path;
}

}  // namespace
}  // namespace erythro::scene
