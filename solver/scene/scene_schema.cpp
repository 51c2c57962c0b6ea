// The scene-file schema (scene_schema.hpp): keys, tables, ranges and their messages.
// Keys, units and ranges are documented in docs/scenes.md.
#include "scene/scene_schema.hpp"

#include <algorithm>
#include <charconv>

namespace erythro::scene::detail {
namespace {

const std::vector<std::string>& known_tables() {
  static const std::vector<std::string> tables = {
      "scene", "domain", "time", "fluid", "boundaries", "boundaries.left", "boundaries.right",
      "boundaries.bottom", "boundaries.top", "body_force", "initial", "run", "run.steady_state",
      "monitor", "output", "limits", "membrane", "aggregation", "transport", "hemoglobin"};
  return tables;
}

const std::vector<KeySpec>& known_keys() {
  static const std::vector<KeySpec> keys = [] {
    const Bound any{};
    const Bound positive{0.0, true};
    const Bound non_negative{0.0, false};
    const Bound at_least_one{1.0, false};
    std::vector<KeySpec> k = {
        {"scene.name", Kind::string, "", any, {}},
        {"scene.description", Kind::string, "", any, {}},
        {"domain.size_um", Kind::vec2, "µm", positive, {}},
        {"domain.spacing_um", Kind::number, "µm", positive, {}},
        {"time.step_s", Kind::number, "s", positive, {}},
        {"time.tau", Kind::number, "", Bound{0.5, true}, {}},
        {"fluid.density_kg_m3", Kind::number, "kg/m³", positive, {}},
        {"fluid.viscosity_cP", Kind::number, "cP", positive, {}},
        {"fluid.collision", Kind::string, "", any, {"bgk", "trt", "regularized"}},
        {"fluid.trt_magic", Kind::number, "", positive, {}},
        {"body_force.density_N_m3", Kind::vec2, "N/m³", any, {}},
        {"body_force.frequency_Hz", Kind::number, "Hz", non_negative, {}},
        {"body_force.phase_rad", Kind::number, "rad", any, {}},
        {"initial.type", Kind::string, "", any, {"rest", "uniform", "shear", "taylor_green", "double_shear_layer"}},
        {"initial.velocity_um_s", Kind::vec2, "µm/s", any, {}},
        {"initial.non_equilibrium", Kind::boolean, "", any, {}},
        // [[fluid.layers]] entries: the schema path drops the index.
        {"fluid.layers.y_um", Kind::vec2, "µm", any, {}},
        {"fluid.layers.x_um", Kind::vec2, "µm", any, {}},
        {"fluid.layers.viscosity_cP", Kind::number, "cP", positive, {}},
        {"run.steps", Kind::integer, "steps", at_least_one, {}},
        {"run.duration_s", Kind::number, "s", positive, {}},
        {"run.steady_state.tolerance", Kind::number, "", positive, {}},
        {"run.steady_state.check_interval_steps", Kind::integer, "steps", at_least_one, {}},
        {"monitor.interval_steps", Kind::integer, "steps", at_least_one, {}},
        {"monitor.max_mach", Kind::number, "", positive, {}},
        {"monitor.max_area_change", Kind::number, "", positive, {}},
        {"monitor.max_edge_strain", Kind::number, "", positive, {}},
        {"monitor.concentration_range_uM", Kind::vec2, "µM", any, {}},
        {"output.fields_interval_steps", Kind::integer, "steps", non_negative, {}},
        {"output.diagnostics_interval_steps", Kind::integer, "steps", non_negative, {}},
        {"output.fields", Kind::string_list, "", any, {"density", "velocity"}},
        {"output.extremes_interval_steps", Kind::integer, "steps", non_negative, {}},
        {"output.dense_diagnostics_steps", Kind::integer, "steps", non_negative, {}},
        // [[stop_when]] entries: the schema path drops the index.
        {"stop_when.series", Kind::string, "", any, {}},
        {"stop_when.below", Kind::number, "", any, {}},
        {"stop_when.above", Kind::number, "", any, {}},
        {"stop_when.change_below", Kind::number, "", positive, {}},
        {"stop_when.window_steps", Kind::integer, "steps", at_least_one, {}},
        {"stop_when.min_steps", Kind::integer, "steps", non_negative, {}},
        {"stop_when.after_steps", Kind::integer, "steps", non_negative, {}},
        {"limits.min_tau_margin", Kind::number, "", non_negative, {}},
        {"limits.max_mach", Kind::number, "", positive, {}},
        {"limits.min_nodes_across_channel", Kind::integer, "nodes", Bound{1.0, false, 1e6, false}, {}},
        {"limits.membrane_stability", Kind::string, "", any, {"reject", "warn"}},
        {"limits.max_marker_spacing", Kind::number, "h", positive, {}},
        {"limits.min_cell_gap", Kind::number, "h", non_negative, {}},
        {"membrane.law", Kind::string, "", any, {"neo_hookean", "skalak", "hookean"}},
        {"membrane.shear_modulus_dyn_cm", Kind::number, "dyn/cm", non_negative, {}},
        {"membrane.bending_modulus_dyn_cm", Kind::number, "dyn·cm", non_negative, {}},
        {"membrane.area_modulus_Pa", Kind::number, "Pa", non_negative, {}},
        {"membrane.skalak_c", Kind::number, "", non_negative, {}},
        {"membrane.kernel", Kind::string, "", any, {"cosine4", "peskin4", "roma3", "linear2"}},
        {"membrane.interior_viscosity_cP", Kind::number, "cP", positive, {}},
        {"membrane.interior_method", Kind::string, "", any, {"flood_fill", "ray_casting", "band_only", "indexless"}},
        {"membrane.index_update_interval", Kind::integer, "steps", Bound{1.0, false, 1e9, false}, {}},
        // [[cells]] entries: the schema path drops the index (cells[2].radius_um → cells.radius_um).
        {"cells.shape", Kind::string, "", any, {"circle", "ellipse", "biconcave"}},
        {"cells.radius_um", Kind::number, "µm", positive, {}},
        {"cells.semi_axes_um", Kind::vec2, "µm", positive, {}},
        {"cells.center_um", Kind::vec2, "µm", any, {}},
        {"cells.angle_deg", Kind::number, "degrees", any, {}},
        {"cells.scale", Kind::number, "", positive, {}},
        {"cells.markers", Kind::integer, "markers", Bound{8.0, false, 1e6, false}, {}},
        {"cells.shear_modulus_dyn_cm", Kind::number, "dyn/cm", non_negative, {}},
        {"cells.prestretch", Kind::number, "", Bound{1.0, false, 2.0, false}, {}},
        {"aggregation.de_star", Kind::number, "", non_negative, {}},  // 0: no adhesion, pair probe kept
        {"aggregation.surface_energy_J_m2", Kind::number, "J/m²", positive, {}},
        {"aggregation.pair_density_Pa", Kind::number, "Pa", positive, {}},
        {"aggregation.zero_force_distance_um", Kind::number, "µm", positive, {}},
        {"aggregation.decay_per_um", Kind::number, "1/µm", positive, {}},
        {"aggregation.cutoff_um", Kind::number, "µm", positive, {}},
        {"transport.coupling", Kind::string, "", any, {"none", "subcycle"}},
        {"transport.time_step_s", Kind::number, "s", positive, {}},
        {"transport.fluid_steps_per_step", Kind::integer, "steps", Bound{1.0, false, 1e9, false}, {}},
        {"transport.stencil", Kind::string, "", any, {"d2q5", "d2q9"}},
        {"transport.collision", Kind::string, "", any, {"bgk", "trt"}},
        {"transport.trt_magic", Kind::number, "", positive, {}},
        {"transport.velocity_um_s", Kind::vec2, "µm/s", any, {}},
        {"transport.cell_representation", Kind::string, "", any, {"ray_cast", "area_fraction"}},
        {"transport.interface", Kind::string, "", any, {"series", "node_tensor", "face_tensor"}},
        {"transport.layer_mean", Kind::string, "", any, {"harmonic", "arithmetic"}},
        {"transport.readout", Kind::string, "", any, {"concentration", "source_corrected"}},
        {"species.name", Kind::string, "", any, {}},
        {"species.diffusivity_um2_s", Kind::number, "µm²/s", positive, {}},
        {"species.cell_diffusivity_um2_s", Kind::number, "µm²/s", positive, {}},
        {"species.initial_uM", Kind::number, "µM", non_negative, {}},
        {"species.cell_initial_uM", Kind::number, "µM", non_negative, {}},
        {"species.source_uM_per_s", Kind::number, "µM/s", any, {}},
        {"species.decay_per_s", Kind::number, "1/s", non_negative, {}},
        // [[transport.layers]] entries: the schema path drops the index.
        {"transport.layers.species", Kind::string, "", any, {}},
        {"transport.layers.y_um", Kind::vec2, "µm", any, {}},
        {"transport.layers.x_um", Kind::vec2, "µm", any, {}},
        {"transport.layers.diffusivity_um2_s", Kind::number, "µm²/s", positive, {}},
        {"transport.layers.decay_per_s", Kind::number, "1/s", non_negative, {}},
        {"transport.layers.source_uM_per_s", Kind::number, "µM/s", any, {}},
        {"hemoglobin.species", Kind::string, "", any, {}},
        {"hemoglobin.k_off_per_s", Kind::number, "1/s", positive, {}},
        {"hemoglobin.heme_uM", Kind::number, "µM", positive, {}},
        {"hemoglobin.solubility_uM_per_torr", Kind::number, "µM/Torr", positive, {}},
        {"hemoglobin.p50_torr", Kind::number, "Torr", positive, {}},
        {"hemoglobin.hill_n", Kind::number, "", positive, {}},
        {"hemoglobin.rate_modifier", Kind::number, "", positive, {}},
        {"hemoglobin.initial_saturation", Kind::number, "", Bound{0.0, false, 1.0, false}, {}},
        {"hemoglobin.coupling", Kind::string, "", any, {"explicit", "cell_implicit", "cell_implicit_outflow"}},
        {"hemoglobin.mean_pressure", Kind::string, "", any, {"concentration", "source_corrected"}},
        {"hemoglobin.heme_weights", Kind::string, "", any, {"area_fraction", "first_moment", "first_moment_sampling"}},
    };
    for (const char* side : {"left", "right", "bottom", "top"}) {
      const std::string p = std::string("species.") + side;
      k.push_back({p, Kind::string, "", any, {"periodic", "fixed_concentration", "fixed_flux", "zero_flux"}});
      k.push_back({p + "_value", Kind::number, "µM or µM·µm/s", any, {}});
    }
    for (const char* side : {"left", "right", "bottom", "top"}) {
      const std::string p = std::string("boundaries.") + side + ".";
      k.push_back({p + "type", Kind::string, "", any, {"periodic", "wall", "moving_wall"}});
      k.push_back({p + "velocity_um_s", Kind::vec2, "µm/s", any, {}});
    }
    return k;
  }();
  return keys;
}

// "cells[3].radius_um" → "cells.radius_um" (the schema path of an array-of-tables entry).
std::string schema_path(std::string_view path) {
  std::string out;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '[') {
      const auto close = path.find(']', i);
      if (close == std::string_view::npos) return std::string(path);
      i = close;
      continue;
    }
    out += path[i];
  }
  return out;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string format_number(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof(buf), v);  // shortest round-trip form
  return std::string(buf, res.ptr);
}

// "must be > 0 (cP)", "must be in (0, 1]", "must be one of "bgk", "trt"".
std::string range_text(const KeySpec& k) {
  std::string s;
  if (!k.choices.empty()) {
    s = "must be one of";
    for (std::size_t i = 0; i < k.choices.size(); ++i) s += (i ? ", \"" : " \"") + k.choices[i] + "\"";
    return s;
  }
  if (k.kind == Kind::string) return "must be a string";
  if (k.kind == Kind::boolean) return "must be true or false";
  const Bound& b = k.bound;
  const bool has_lo = std::isfinite(b.lo), has_hi = std::isfinite(b.hi);
  if (has_lo && has_hi) {
    s = "must be in " + std::string(b.lo_open ? "(" : "[") + format_number(b.lo) + ", " +
        format_number(b.hi) + (b.hi_open ? ")" : "]");
  } else if (has_lo) {
    s = std::string("must be ") + (b.lo_open ? "> " : ">= ") + format_number(b.lo);
  } else if (has_hi) {
    s = std::string("must be ") + (b.hi_open ? "< " : "<= ") + format_number(b.hi);
  } else {
    s = "must be finite";
  }
  if (k.kind == Kind::vec2) s = "each component " + s;
  if (!k.unit.empty()) s += " (" + k.unit + ")";
  return s;
}

std::string type_text(Kind kind) {
  switch (kind) {
    case Kind::string: return "a string";
    case Kind::number: return "a number";
    case Kind::integer: return "an integer";
    case Kind::vec2: return "an array of 2 numbers";
    case Kind::string_list: return "an array of strings";
    case Kind::boolean: return "true or false";
  }
  return "?";
}

const KeySpec* find_key(std::string_view path) {
  const std::string p = schema_path(path);
  for (const KeySpec& k : known_keys())
    if (k.path == p) return &k;
  return nullptr;
}

bool is_known_table(std::string_view path) {
  const auto& t = known_tables();
  return std::find(t.begin(), t.end(), path) != t.end();
}

std::string_view leaf(std::string_view path) {
  const auto dot = path.rfind('.');
  return dot == std::string_view::npos ? path : path.substr(dot + 1);
}

// " (did you mean 'x'?)" for the closest known key or table, or "" if none is close:
// a small edit distance on the full dotted key, else the same leaf in another table.
std::string suggestion(std::string_view bad) {
  std::vector<std::string> candidates = known_tables();
  for (const KeySpec& k : known_keys()) candidates.push_back(k.path);
  std::string best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(bad, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  if (best_d <= std::max<std::size_t>(2, bad.size() / 4)) return " (did you mean '" + best + "'?)";
  for (const std::string& c : candidates)
    if (leaf(c) == leaf(bad)) return " (did you mean '" + c + "'?)";
  return "";
}

}  // namespace erythro::scene::detail
