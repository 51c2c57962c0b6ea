// TOML scene file → Scene (physical units). Keys, units, ranges and defaults: the schema
// (scene_keys.cpp), documented in docs/scenes.md.
//
// Three passes over the parsed document:
//   1. apply --set overrides (each must name a known key or table);
//   2. walk every table and reject unknown keys/tables (with a did-you-mean);
//   3. read each known key, checking its type and single-value range; a key the scene
//      leaves out takes the schema's default (scene_keys.cpp), never one written here.
// Checks that need several values (node counts, τ margin, Mach) live in units.cpp.
#include "scene/scene_parser.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <initializer_list>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "common/error.hpp"
#include "scene/cell_seeding.hpp"
#include "scene/scene_schema.hpp"

namespace erythro::scene {
namespace {

using namespace detail;  // the schema: Kind, KeySpec, find_key, range_text, ...

// ---------------------------------------------------------------- messages

std::string in_quotes(std::string_view s) {
  std::string out(1, '"');  // built by appending: GCC 12 -Wrestrict misfires on "lit" + string&&
  out.append(s);
  return out += '"';
}

// The value as the user wrote it (numbers in shortest form, strings quoted).
std::string repr(const toml::node& n) {
  if (n.is_table()) return "(a table)";
  if (const auto* a = n.as_array()) {
    std::string s = "[";
    for (std::size_t i = 0; i < a->size(); ++i) s += (i ? ", " : "") + repr(*a->get(i));
    return s + "]";
  }
  if (const auto* s = n.as_string()) return in_quotes(s->get());
  if (const auto* d = n.as_floating_point()) return format_number(d->get());
  if (const auto* i = n.as_integer()) return std::to_string(i->get());
  if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
  std::ostringstream os;  // dates and times
  os << toml::node_view<const toml::node>(n);
  return os.str();
}

std::string kind_of(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

class Reader;
void read_transport(const Reader& r, Scene& s);
void read_stop_when(const Reader& r, Scene& s);
void read_layers(const Reader& r, Scene& s);
void read_cell_populations(const Reader& r, Scene& s);

class Reader {
 public:
  Reader(const toml::table& root, std::string origin) : root_(root), origin_(std::move(origin)) {}

  // "FILE:LINE" for values from the file, "FILE: --set k=v" for overrides, "FILE" if unknown.
  std::string where(const toml::node* n) const {
    if (n) {
      const toml::source_region& src = n->source();
      if (src.path && src.path->rfind("--set ", 0) == 0) return origin_ + ": " + *src.path;
      if (src.begin.line > 0) return origin_ + ":" + std::to_string(src.begin.line);
    }
    return origin_;
  }

  [[noreturn]] void fail(const toml::node& n, std::string_view path, const std::string& what) const {
    throw InputError(where(&n) + ": key '" + std::string(path) + "' = " + repr(n) + " " + what);
  }
  [[noreturn]] void out_of_range(const toml::node& n, const KeySpec& k) const {
    fail(n, k.path, "is out of range: " + range_text(k));
  }
  [[noreturn]] void wrong_type(const toml::node& n, const KeySpec& k) const {
    const bool plain_string = k.kind == Kind::string && k.choices.empty();
    fail(n, k.path, "has the wrong type (" + kind_of(n) + "): expected " + type_text(k.kind) +
                        (plain_string ? "" : "; " + range_text(k)));
  }

  const toml::node* find(std::string_view path) const { return root_.at_path(path).node(); }
  bool has(std::string_view path) const { return find(path) != nullptr; }

  // Walks the whole document: every key must be known, every known table a table.
  void reject_unknown(const toml::table& t, const std::string& prefix) const {
    for (const auto& [key, node] : t) {
      const std::string path = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
      // A quoted key holding a dot ("fluid.viscosity_cP" = 1) is not the nested key.
      const bool plain = key.str().find_first_of(".[") == std::string_view::npos;
      if (plain && is_array_of_tables(path)) {
        const auto* arr = node.as_array();
        if (!arr || !arr->is_array_of_tables())
          fail(node, path, "has the wrong type (" + kind_of(node) + "): expected an array of tables ([[" + path + "]])");
        for (std::size_t i = 0; i < arr->size(); ++i) {
          for (const auto& [ckey, cnode] : *arr->get(i)->as_table()) {
            const std::string cpath = path + "[" + std::to_string(i) + "]." + std::string(ckey.str());
            if (!find_key(cpath))
              throw InputError(where(&cnode) + ": unknown key '" + cpath + "'" +
                               suggestion(path + "." + std::string(ckey.str())));
          }
        }
        continue;
      }
      if (!plain) {
        throw InputError(where(&node) + ": unknown key '" + path + "' (a quoted key with '.' or '[' is never valid" +
                         " here; write the table and key unquoted)");
      } else if (is_known_table(path)) {
        const auto* sub = node.as_table();
        if (!sub) fail(node, path, "has the wrong type (" + kind_of(node) + "): expected a table");
        reject_unknown(*sub, path);
      } else if (!find_key(path)) {
        throw InputError(where(&node) + ": unknown " + (node.is_table() ? "table" : "key") + " '" + path +
                         "'" + suggestion(path));
      }
    }
  }

  // Typed readers. number(path): the scene's value, else the schema's default literal; a key
  // whose schema default is a note (required, or derived from other keys) has no value to
  // fall back on, so the caller checks has() first or passes the derived value:
  // number(path, derived). Passing one for a key the schema has a literal default for is a
  // logic_error, so a default can only be declared in the schema.
  double number(std::string_view path) const { return value(path, &Reader::number_of); }
  double number(std::string_view path, double derived) const { return value(path, derived, &Reader::number_of); }
  long integer(std::string_view path) const { return value(path, &Reader::integer_of); }
  long integer(std::string_view path, long derived) const { return value(path, derived, &Reader::integer_of); }
  std::string text(std::string_view path) const { return value(path, &Reader::text_of); }
  std::string text(std::string_view path, const std::string& derived) const {
    return value(path, derived, &Reader::text_of);
  }
  std::array<double, 2> vec2(std::string_view path) const { return value(path, &Reader::vec2_of); }
  std::array<double, 2> vec2(std::string_view path, const std::array<double, 2>& derived) const {
    return value(path, derived, &Reader::vec2_of);
  }
  bool flag(std::string_view path) const { return value(path, &Reader::flag_of); }
  std::vector<std::string> string_list(std::string_view path) const { return value(path, &Reader::string_list_of); }

  // The table's line (for messages about keys missing from it), or the bare origin.
  std::string where_table(std::string_view table) const { return where(find(table)); }

 private:
  template <class T>
  using Convert = T (Reader::*)(const toml::node&, const KeySpec&) const;

  // The value of `path` in the scene, else the schema's default literal read like a value.
  template <class T>
  T value(std::string_view path, Convert<T> convert) const {
    const KeySpec k = spec(path);
    if (const toml::node* n = find(path)) return (this->*convert)(*n, k);
    const toml::table fallback = schema_default(k);
    return (this->*convert)(*fallback.get("v"), k);
  }
  // The value of `path` in the scene, else `derived`, for a key without a literal default.
  template <class T>
  T value(std::string_view path, const T& derived, Convert<T> convert) const {
    const KeySpec k = spec(path);
    if (k.when_absent.is_literal)
      throw std::logic_error("scene_parser: key '" + k.path + "' has the schema default " + k.when_absent.text +
                             ": read it without a fallback");
    const toml::node* n = find(path);
    return n ? (this->*convert)(*n, k) : derived;
  }
  // The schema's default of a key as the TOML table {v = <literal>}.
  static toml::table schema_default(const KeySpec& k) {
    if (!k.when_absent.is_literal)
      throw std::logic_error("scene_parser: key '" + k.path + "' has no default value in the schema (" +
                             k.when_absent.text + "): check has() first or pass the derived value");
    try {
      const std::string source = "the schema default of " + k.path;
      return toml::parse(std::string_view("v = " + k.when_absent.text), std::string_view(source));
    } catch (const toml::parse_error&) {
      throw std::logic_error("scene_parser: the schema default of '" + k.path + "' is not TOML: " + k.when_absent.text);
    }
  }

  // The schema entry, named by the path as written (cells[2].radius_um, not cells.radius_um).
  static KeySpec spec(std::string_view path) {
    const KeySpec* k = find_key(path);
    if (!k) throw std::logic_error("scene_parser: key not in schema: " + std::string(path));
    KeySpec named = *k;
    named.path = std::string(path);
    return named;
  }
  static bool allowed(const KeySpec& k, const std::string& v) {
    return k.choices.empty() || std::find(k.choices.begin(), k.choices.end(), v) != k.choices.end();
  }

  // One converter per Kind: the node's value, checked against the key's type and range.
  // Integers are accepted where floats are expected (2 → 2.0).
  double number_of(const toml::node& n, const KeySpec& k) const { return element_of(n, k, n); }
  // `whole`: the node shown in messages (the array holding n, for a vec2 element).
  double element_of(const toml::node& n, const KeySpec& k, const toml::node& whole) const {
    double v = 0.0;
    if (const auto* i = n.as_integer()) v = static_cast<double>(i->get());
    else if (const auto* d = n.as_floating_point()) v = d->get();
    else wrong_type(whole, k);
    if (!k.bound.contains(v)) out_of_range(whole, k);
    return v;
  }
  long integer_of(const toml::node& n, const KeySpec& k) const {
    if (!n.is_integer()) wrong_type(n, k);  // 10.5 or 10.0 where a count is expected
    const auto v = n.as_integer()->get();
    if (!k.bound.contains(static_cast<double>(v))) out_of_range(n, k);
    return static_cast<long>(v);
  }
  std::string text_of(const toml::node& n, const KeySpec& k) const {
    if (!n.is_string()) wrong_type(n, k);
    const std::string v = n.as_string()->get();
    if (!allowed(k, v)) out_of_range(n, k);
    return v;
  }
  std::array<double, 2> vec2_of(const toml::node& n, const KeySpec& k) const {
    const auto* a = n.as_array();
    if (!a || a->size() != 2) wrong_type(n, k);
    return {element_of(*a->get(0), k, n), element_of(*a->get(1), k, n)};
  }
  bool flag_of(const toml::node& n, const KeySpec& k) const {
    if (!n.is_boolean()) wrong_type(n, k);
    return n.as_boolean()->get();
  }
  std::vector<std::string> string_list_of(const toml::node& n, const KeySpec& k) const {
    const auto* a = n.as_array();
    if (!a) wrong_type(n, k);
    std::vector<std::string> out;
    for (const toml::node& e : *a) {
      if (!e.is_string()) wrong_type(n, k);
      const std::string v = e.as_string()->get();
      if (!allowed(k, v)) fail(n, k.path, "contains " + in_quotes(v) + ": each entry " + range_text(k));
      if (std::find(out.begin(), out.end(), v) != out.end()) fail(n, k.path, "lists " + in_quotes(v) + " twice");
      out.push_back(v);
    }
    return out;
  }

  const toml::table& root_;
  std::string origin_;
};

// ---------------------------------------------------------------- --set overrides

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

std::vector<std::string> split_dots(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t dot; (dot = path.find('.', start)) != std::string::npos; start = dot + 1)
    parts.push_back(path.substr(start, dot - start));
  parts.push_back(path.substr(start));
  return parts;
}

// The table of "name[i]" (cells[1], species[0]) for --set: the entry must exist in the
// scene file (--set changes values; it does not add cells or species).
toml::table* array_entry(toml::table& root, const std::string& part, const std::string& text,
                         const std::string& origin) {
  const auto open = part.find('[');
  const std::string name = part.substr(0, open);
  const std::string entries = "[[" + name + "]] entries";
  const bool well_formed = open != std::string::npos && part.back() == ']' && part.size() > open + 2 &&
                           part.find_first_not_of("0123456789", open + 1) == part.size() - 1;
  if (!well_formed)
    throw InputError(origin + ": --set " + text + ": " + entries + " are addressed by index, e.g. --set " + name +
                     "[0]." + text.substr(text.find('.') == std::string::npos ? 0 : text.find('.') + 1));
  // More digits than any index of a file could need is past the end too (no overflow).
  const std::string digits = part.substr(open + 1, part.size() - open - 2);
  const std::size_t index = digits.size() > 9 ? std::numeric_limits<std::size_t>::max() : std::stoul(digits);
  toml::array* array = root.get(name) ? root.get(name)->as_array() : nullptr;
  const std::size_t count = array ? array->size() : 0;
  if (index >= count)
    throw InputError(origin + ": --set " + text + ": the scene has " + std::to_string(count) + " " + entries +
                     (count ? " (index 0 … " + std::to_string(count - 1) + ")" : "") +
                     "; --set changes an entry the file has, it does not add one");
  toml::table* t = (*array)[index].as_table();
  if (!t) throw InputError(origin + ": --set " + text + ": " + name + "[" + std::to_string(index) + "] is not a table");
  return t;
}

// "--set a.b.c=value": the value is TOML ("v = <value>"), or else a bare string.
void apply_override(toml::table& root, const std::string& text, const std::string& origin) {
  const auto eq = text.find('=');
  const std::string key = eq == std::string::npos ? "" : trim(text.substr(0, eq));
  const std::string value = eq == std::string::npos ? "" : trim(text.substr(eq + 1));
  if (key.empty() || value.empty())
    throw InputError(origin + ": malformed --set '" + text + "': expected KEY=VALUE, e.g. --set fluid.viscosity_cP=1.2");
  if (!find_key(key) && !is_known_table(key))
    throw InputError(origin + ": --set " + text + ": unknown key '" + key + "'" + suggestion(key));

  const std::string source = "--set " + text;  // recorded as the node's source, for messages
  toml::table parsed;
  try {
    parsed = toml::parse(std::string_view("v = " + value), std::string_view(source));
  } catch (const toml::parse_error&) {
    std::ostringstream bare;  // not TOML: take the text literally, as a string
    bare << toml::value<std::string>(value);
    parsed = toml::parse(std::string_view("v = " + bare.str()), std::string_view(source));
  }
  if (parsed.size() != 1 || !parsed.contains("v"))
    throw InputError(origin + ": malformed --set '" + text + "': the value must be a single TOML value");

  // One of an exclusive pair replaces its partner from the file (a partner that
  // came from another --set stays, and the pair is then reported as a conflict).
  for (const auto& [x, y] : {std::pair{"time.tau", "time.step_s"}, std::pair{"run.steps", "run.duration_s"}}) {
    const std::string partner = key == x ? y : key == y ? x : "";
    if (partner.empty()) continue;
    const toml::node* p = root.at_path(partner).node();
    const bool from_set = p && p->source().path && p->source().path->rfind("--set ", 0) == 0;
    if (p && !from_set) root.at_path(partner.substr(0, partner.find('.'))).as_table()->erase(leaf(partner));
  }

  const std::vector<std::string> parts = split_dots(key);
  toml::table* t = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    if (parts[i].find('[') != std::string::npos || is_array_of_tables(parts[i])) {
      t = array_entry(*t, parts[i], text, origin);  // "cells[1]", "fluid.layers[0]": an entry the file has
      continue;
    }
    toml::node* n = t->get(parts[i]);
    if (!n) n = &t->insert(parts[i], toml::table{}).first->second;
    t = n->as_table();
    if (!t) throw InputError(origin + ": --set " + text + ": '" + parts[i] + "' is not a table in the scene");
  }
  t->insert_or_assign(parts.back(), std::move(*parsed.get("v")));  // move keeps the source
}

// ---------------------------------------------------------------- reading

SideSpec read_side(const Reader& r, const std::string& name) {
  const std::string p = "boundaries." + name + ".";
  SideSpec s;
  s.type = r.text(p + "type");
  s.velocity_um_s = r.vec2(p + "velocity_um_s");
  if (s.type != "moving_wall" && (s.velocity_um_s[0] != 0.0 || s.velocity_um_s[1] != 0.0))
    r.fail(*r.find(p + "velocity_um_s"), p + "velocity_um_s",
           "is not allowed here: only a side with type = \"moving_wall\" has a velocity (this side is \"" + s.type +
               "\")");
  return s;
}

// Exactly one of two keys: returns which one is given (0 or 1).
int exactly_one(const Reader& r, const std::string& table, const std::string& a, const std::string& b,
                const std::string& hint) {
  const toml::node* na = r.find(table + "." + a);
  const toml::node* nb = r.find(table + "." + b);
  if (na && nb) {  // blame the one given last (a --set override, or the later line)
    const auto rank = [](const toml::node* n) {
      const auto& src = n->source();
      const bool from_set = src.path && src.path->rfind("--set ", 0) == 0;
      return from_set ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t{src.begin.line};
    };
    const bool b_last = rank(nb) >= rank(na);
    const std::string first = table + "." + (b_last ? a : b), last = table + "." + (b_last ? b : a);
    r.fail(*(b_last ? nb : na), last,
           "conflicts with '" + first + "' = " + repr(*(b_last ? na : nb)) + " (" + r.where(b_last ? na : nb) +
               "): give exactly one of them (" + hint + ")");
  }
  if (!na && !nb)
    throw InputError(r.where_table(table) + ": missing key: give exactly one of '" + table + "." + a + "' or '" +
                     table + "." + b + "' (" + hint + ")");
  return na ? 0 : 1;
}

// The required keys of entry `i` of the array of tables `array` (e.g. "fluid.layers"): a missing one
// is named with its allowed range (the schema's entry "<array>.<key>").
void require_entry_keys(const Reader& r, const std::string& array, std::size_t i,
                        std::initializer_list<const char*> keys) {
  const std::string p = array + "[" + std::to_string(i) + "].";
  for (const char* key : keys)
    if (!r.has(p + key))
      throw InputError(r.where(r.find(array)->as_array()->get(i)) + ": missing key '" + p + key + "' (required; " +
                       range_text(*find_key(array + "." + key)) + ")");
}

// A band [from, to] in µm (y_um, x_um of a layer entry): from < to.
std::array<double, 2> read_band(const Reader& r, const std::string& path) {
  const std::array<double, 2> band = r.vec2(path);
  if (!(band[0] < band[1])) r.fail(*r.find(path), path, "is out of range: it must be [from, to] with from < to (µm)");
  return band;
}

// [no_o2] and [[no_o2.layers]] (scene.hpp NoO2Spec, CompartmentLayerSpec).
void read_no_o2(const Reader& r, Scene& s) {
  if (!r.has("no_o2")) {
    if (r.find("no_o2.layers")) throw InputError(r.where_table("no_o2") + ": [[no_o2.layers]] needs [no_o2]");
    return;
  }
  if (!s.transport) throw InputError(r.where_table("no_o2") + ": [no_o2] needs [transport] and its two [[species]]");
  NoO2Spec n;
  n.no_species = r.text("no_o2.no_species");
  n.o2_species = r.text("no_o2.o2_species");
  for (const auto& entry : {std::pair{"no_o2.no_species", n.no_species}, std::pair{"no_o2.o2_species", n.o2_species}}) {
    const std::string& name = entry.second;  // (not a structured binding: clang's lambdas cannot capture one)
    if (std::none_of(s.species.begin(), s.species.end(), [&](const SpeciesSpec& sp) { return sp.name == name; }))
      throw InputError(r.where_table("no_o2") + ": " + entry.first + " = \"" + name + "\" names no [[species]] entry");
  }
  if (n.no_species == n.o2_species)
    throw InputError(r.where_table("no_o2") + ": no_o2.no_species and no_o2.o2_species name the same species");
  n.wall_shear_stress_Pa = r.number("no_o2.wall_shear_stress_Pa");
  n.blood_no_scavenging_per_s = r.number("no_o2.blood_no_scavenging_per_s");
  n.core_po2_torr = r.number("no_o2.core_po2_torr");
  n.core_o2_exchange_per_s = r.number("no_o2.core_o2_exchange_per_s");
  n.no_consumption_per_s = r.number("no_o2.no_consumption_per_s");
  n.sm_o2_max_consumption_uM_s = r.number("no_o2.sm_o2_max_consumption_uM_s");
  n.tissue_o2_max_consumption_uM_s = r.number("no_o2.tissue_o2_max_consumption_uM_s");
  s.no_o2 = n;
  const toml::node* layers = r.find("no_o2.layers");
  const std::size_t count = layers ? layers->as_array()->size() : 0;
  if (count == 0) throw InputError(r.where_table("no_o2") + ": [no_o2] needs at least one [[no_o2.layers]] band");
  for (std::size_t i = 0; i < count; ++i) {
    const std::string p = "no_o2.layers[" + std::to_string(i) + "].";
    require_entry_keys(r, "no_o2.layers", i, {"compartment", "y_um"});
    CompartmentLayerSpec l;
    l.compartment = r.text(p + "compartment");
    l.y_um = read_band(r, p + "y_um");
    s.compartment_layers.push_back(l);
  }
}

Scene read_scene(const Reader& r, const std::string& origin) {
  Scene s;
  s.name = r.text("scene.name", std::filesystem::path(origin).stem().string());
  s.description = r.text("scene.description");

  for (const char* key : {"domain.size_um", "domain.spacing_um"})
    if (!r.has(key))
      throw InputError(r.where_table("domain") + ": missing key '" + key + "' (required; " +
                       range_text(*find_key(key)) + ")");
  s.domain.size_um = r.vec2("domain.size_um");
  s.domain.spacing_um = r.number("domain.spacing_um");
  s.domain.geometry = r.text("domain.geometry");
  s.domain.inner_radius_um = r.number("domain.inner_radius_um");

  // A still-medium transport scene builds no fluid and has no [time] (units.cpp says so
  // if one is given); every other scene gives exactly one fluid time key.
  const bool still_medium = r.has("transport") && r.text("transport.coupling") == "none";
  if (!still_medium) {
    if (exactly_one(r, "time", "step_s", "tau", "step_s in s, > 0; or tau, > 0.5") == 0)
      s.time.step_s = r.number("time.step_s");
    else
      s.time.tau = r.number("time.tau");
  } else {
    if (r.has("time.step_s")) s.time.step_s = r.number("time.step_s");
    if (r.has("time.tau")) s.time.tau = r.number("time.tau");
  }

  s.fluid.density_kg_m3 = r.number("fluid.density_kg_m3");
  s.fluid.viscosity_cP = r.number("fluid.viscosity_cP");
  s.fluid.collision = r.text("fluid.collision");
  s.fluid.trt_magic = r.number("fluid.trt_magic");
  read_layers(r, s);
  if (r.has("time_mapping")) {  // the optional keys first: a bad value is named before a missing key
    TimeMappingSpec m;
    if (r.has("time_mapping.radius_um")) m.radius_um = r.number("time_mapping.radius_um");
    if (r.has("time_mapping.shear_rate_per_s")) m.shear_rate_per_s = r.number("time_mapping.shear_rate_per_s");
    if (!r.has("time_mapping.reynolds"))
      throw InputError(r.where_table("time_mapping") + ": missing key 'time_mapping.reynolds' (required; " +
                       range_text(*find_key("time_mapping.reynolds")) + ")");
    m.reynolds = r.number("time_mapping.reynolds");
    s.time_mapping = m;
  }

  s.boundaries.left = read_side(r, "left");
  s.boundaries.right = read_side(r, "right");
  s.boundaries.bottom = read_side(r, "bottom");
  s.boundaries.top = read_side(r, "top");

  if (r.has("body_force")) {  // the table's presence engages the force
    BodyForceSpec f;
    f.density_N_m3 = r.vec2("body_force.density_N_m3");
    f.frequency_Hz = r.number("body_force.frequency_Hz");
    f.phase_rad = r.number("body_force.phase_rad");
    s.body_force = f;
  }

  s.initial.type = r.text("initial.type");
  s.initial.velocity_um_s = r.vec2("initial.velocity_um_s");
  s.initial.non_equilibrium = r.flag("initial.non_equilibrium");
  const auto& u0 = s.initial.velocity_um_s;
  if ((s.initial.type == "rest" || s.initial.type == "shear") && (u0[0] != 0.0 || u0[1] != 0.0))
    r.fail(*r.find("initial.velocity_um_s"), "initial.velocity_um_s",
           "is not allowed with initial.type = \"" + s.initial.type +
               "\" (only \"uniform\" and \"taylor_green\" take a velocity)");
  if ((s.initial.type == "taylor_green" || s.initial.type == "double_shear_layer") && u0[1] != 0.0)
    r.fail(*r.find("initial.velocity_um_s"), "initial.velocity_um_s",
           "is out of range: with initial.type = \"" + s.initial.type + "\" it must be [U, 0] (µm/s)");

  if (exactly_one(r, "run", "steps", "duration_s", "steps, an integer >= 1; or duration_s in s, > 0") == 0)
    s.run.steps = r.integer("run.steps");
  else
    s.run.duration_s = r.number("run.duration_s");
  if (r.has("run.steady_state")) {
    SteadyStateSpec ss;
    ss.tolerance = r.number("run.steady_state.tolerance");
    ss.check_interval_steps = r.integer("run.steady_state.check_interval_steps");
    s.run.steady_state = ss;
  }

  s.monitor.interval_steps = r.integer("monitor.interval_steps");
  s.monitor.max_mach = r.number("monitor.max_mach");
  s.monitor.max_area_change = r.number("monitor.max_area_change");
  s.monitor.max_edge_strain = r.number("monitor.max_edge_strain");
  if (r.has("monitor.concentration_range_uM")) {
    const auto range = r.vec2("monitor.concentration_range_uM");
    if (!(range[0] < range[1]))
      r.fail(*r.find("monitor.concentration_range_uM"), "monitor.concentration_range_uM",
             "is out of range: it must be [lo, hi] with lo < hi (µM)");
    s.monitor.concentration_range_uM = range;
  }

  s.output.fields_interval_steps = r.integer("output.fields_interval_steps");
  s.output.diagnostics_interval_steps =
      r.integer("output.diagnostics_interval_steps");
  s.output.fields = r.string_list("output.fields");
  s.output.extremes_interval_steps = r.integer("output.extremes_interval_steps");
  s.output.dense_diagnostics_steps = r.integer("output.dense_diagnostics_steps");
  s.output.checkpoint_interval_steps = r.integer("output.checkpoint_interval_steps");
  s.output.checkpoint_interval_s = r.number("output.checkpoint_interval_s");
  read_stop_when(r, s);

  s.limits.min_tau_margin = r.number("limits.min_tau_margin");
  s.limits.max_tau = r.number("limits.max_tau");
  if (!(s.limits.max_tau > 0.5 + s.limits.min_tau_margin)) {  // blame the one the scene gives
    const char* key = r.has("limits.max_tau") ? "limits.max_tau" : "limits.min_tau_margin";
    r.fail(*r.find(key), key,
           "leaves no τ allowed: limits.max_tau = " + format_number(s.limits.max_tau) +
               " must exceed 0.5 + limits.min_tau_margin = " + format_number(0.5 + s.limits.min_tau_margin));
  }
  s.limits.max_mach = r.number("limits.max_mach");
  s.limits.min_nodes_across_channel =
      static_cast<int>(r.integer("limits.min_nodes_across_channel"));
  s.limits.membrane_stability = r.text("limits.membrane_stability");
  s.limits.max_marker_spacing = r.number("limits.max_marker_spacing");
  s.limits.min_cell_gap = r.number("limits.min_cell_gap");

  if (r.has("membrane")) {
    MembraneSpec m;
    m.law = r.text("membrane.law");
    m.shear_modulus_dyn_cm = r.number("membrane.shear_modulus_dyn_cm");
    m.bending_modulus_dyn_cm = r.number("membrane.bending_modulus_dyn_cm");
    m.area_modulus_Pa = r.number("membrane.area_modulus_Pa");
    m.skalak_c = r.number("membrane.skalak_c");
    m.kernel = r.text("membrane.kernel");
    m.area_correction = r.text("membrane.area_correction");
    if (r.has("membrane.interior_viscosity_cP"))
      m.interior_viscosity_cP = r.number("membrane.interior_viscosity_cP");
    m.interior_method = r.text("membrane.interior_method");
    m.index_update_interval = r.integer("membrane.index_update_interval");
    for (const char* key : {"membrane.interior_method", "membrane.index_update_interval"})
      if (!m.interior_viscosity_cP && r.has(key))
        r.fail(*r.find(key), key, "needs membrane.interior_viscosity_cP (without it the interior has the fluid's viscosity)");
    if (m.law != "skalak" && r.has("membrane.skalak_c"))
      r.fail(*r.find("membrane.skalak_c"), "membrane.skalak_c",
             "is not allowed here: only membrane.law = \"skalak\" takes C (the law is \"" + m.law + "\")");
    s.membrane = m;
  }
  if (const toml::node* cells = r.find("cells")) {
    const std::size_t count = cells->as_array()->size();
    for (std::size_t i = 0; i < count; ++i) {
      const std::string p = "cells[" + std::to_string(i) + "].";
      CellSpec c;
      c.shape = r.text(p + "shape");
      const bool ellipse = c.shape == "ellipse";
      const std::string size_key = ellipse ? "semi_axes_um" : "radius_um";
      const std::string wrong_key = ellipse ? "radius_um" : "semi_axes_um";
      if (!r.has(p + size_key))
        throw InputError(r.where(cells->as_array()->get(i)) + ": missing key '" + p + size_key + "' (required for shape = \"" +
                         c.shape + "\"; " + range_text(*find_key("cells." + size_key)) + ")");
      if (r.has(p + wrong_key))
        r.fail(*r.find(p + wrong_key), p + wrong_key,
               "is not allowed with shape = \"" + c.shape + "\" (give " + size_key + ")");
      if (!r.has(p + "center_um"))
        throw InputError(r.where(cells->as_array()->get(i)) + ": missing key '" + p + "center_um' (required; µm)");
      c.radius_um = r.number(p + "radius_um", c.radius_um);
      c.semi_axes_um = r.vec2(p + "semi_axes_um", c.semi_axes_um);
      c.center_um = r.vec2(p + "center_um");
      c.angle_deg = r.number(p + "angle_deg");
      c.scale = r.number(p + "scale");
      c.markers = r.integer(p + "markers", c.markers);
      if (r.has(p + "shear_modulus_dyn_cm")) c.shear_modulus_dyn_cm = r.number(p + "shear_modulus_dyn_cm");
      c.prestretch = r.number(p + "prestretch");
      s.cells.push_back(c);
    }
  }
  read_cell_populations(r, s);
  if (r.has("aggregation")) {
    AggregationSpec a;
    const char* strengths[] = {"aggregation.de_star", "aggregation.surface_energy_J_m2", "aggregation.pair_density_Pa"};
    const int given = static_cast<int>(r.has(strengths[0])) + static_cast<int>(r.has(strengths[1])) +
                      static_cast<int>(r.has(strengths[2]));
    if (given != 1)
      throw InputError(r.where_table("aggregation") + ": give exactly one of aggregation.surface_energy_J_m2 (γ, "
                       "J/m², >= 0), aggregation.de_star (γ / 2.6e-8 J/m², the thesis's levels 1-5, >= 0) or "
                       "aggregation.pair_density_Pa (D_e, Pa, > 0); " +
                       std::to_string(given) + " given");
    if (r.has(strengths[0])) a.de_star = r.number(strengths[0]);
    if (r.has(strengths[1])) a.surface_energy_J_m2 = r.number(strengths[1]);
    if (r.has(strengths[2])) a.pair_density_Pa = r.number(strengths[2]);
    a.zero_force_distance_um = r.number("aggregation.zero_force_distance_um");
    a.decay_per_um = r.number("aggregation.decay_per_um");
    const double cutoff = r.number("aggregation.cutoff_um", a.zero_force_distance_um + 5.0 / a.decay_per_um);
    if (r.has("aggregation.cutoff_um")) a.cutoff_um = cutoff;
    if (cutoff <= a.zero_force_distance_um)
      throw InputError(r.where_table("aggregation") + ": aggregation.cutoff_um = " + format_number(cutoff) + " µm" +
                       (a.cutoff_um ? ""
                                    : " (r0 + 5/β, aggregation.decay_per_um = " + format_number(a.decay_per_um) +
                                          " /µm)") +
                       " must exceed aggregation.zero_force_distance_um = " +
                       format_number(a.zero_force_distance_um) + " µm (the potential is cut beyond r_c)");
    s.aggregation = a;
  }
  if (r.has("repulsion")) {
    RepulsionSpec rep;
    rep.pressure_Pa = r.number("repulsion.pressure_Pa");
    if (r.has("repulsion.range_um")) rep.range_um = r.number("repulsion.range_um");
    rep.walls = r.flag("repulsion.walls");
    s.repulsion = rep;
  } else if (!s.cell_populations.empty()) {
    throw InputError(r.where_table("cell_populations") +
                     ": [[cell_populations]] crowd cells together, and nothing would keep their membranes apart: "
                     "add a [repulsion] table (its defaults are fine: docs/scenes.md)");
  }
  read_transport(r, s);
  return s;
}

// [[fluid.layers]] (scene.hpp; docs/scenes.md): y_um and viscosity_cP required.
void read_layers(const Reader& r, Scene& s) {
  const toml::node* layers = r.find("fluid.layers");
  if (!layers) return;
  const std::size_t count = layers->as_array()->size();
  for (std::size_t i = 0; i < count; ++i) {
    const std::string p = "fluid.layers[" + std::to_string(i) + "].";
    require_entry_keys(r, "fluid.layers", i, {"y_um", "viscosity_cP"});
    ViscosityLayerSpec layer;
    layer.y_um = r.vec2(p + "y_um");
    if (r.has(p + "x_um")) layer.x_um = r.vec2(p + "x_um");
    layer.viscosity_cP = r.number(p + "viscosity_cP");
    s.fluid.layers.push_back(layer);
  }
}

// [[cell_populations]] (scene.hpp; docs/scenes.md): read, then placed among the cells read so
// far (cell_seeding.hpp) and appended to them; a target the draws cannot reach is refused.
void read_cell_populations(const Reader& r, Scene& s) {
  const toml::node* populations = r.find("cell_populations");
  if (!populations) return;
  const std::size_t count = populations->as_array()->size();
  for (std::size_t i = 0; i < count; ++i) {
    const std::string p = "cell_populations[" + std::to_string(i) + "].";
    const toml::node* entry = populations->as_array()->get(i);
    CellPopulationSpec pop;
    pop.shape = r.text(p + "shape");
    const bool ellipse = pop.shape == "ellipse";
    const std::string size_key = ellipse ? "semi_axes_um" : "radius_um";
    const std::string wrong_key = ellipse ? "radius_um" : "semi_axes_um";
    if (!r.has(p + size_key))
      throw InputError(r.where(entry) + ": missing key '" + p + size_key + "' (required for shape = \"" + pop.shape +
                       "\"; " + range_text(*find_key("cell_populations." + size_key)) + ")");
    if (r.has(p + wrong_key))
      r.fail(*r.find(p + wrong_key), p + wrong_key, "is not allowed with shape = \"" + pop.shape + "\" (give " + size_key + ")");
    pop.radius_um = r.number(p + "radius_um", pop.radius_um);
    pop.semi_axes_um = r.vec2(p + "semi_axes_um", pop.semi_axes_um);
    pop.markers = r.integer(p + "markers", pop.markers);
    if (r.has(p + "shear_modulus_dyn_cm")) pop.shear_modulus_dyn_cm = r.number(p + "shear_modulus_dyn_cm");
    if (exactly_one(r, "cell_populations[" + std::to_string(i) + "]", "area_fraction", "count",
                    "area_fraction in (0, 1); or count, an integer >= 1") == 0)
      pop.area_fraction = r.number(p + "area_fraction");
    else
      pop.count = r.integer(p + "count");
    if (r.has(p + "min_gap_um")) {
      pop.min_gap_um = r.number(p + "min_gap_um");
      const double set_up_gap = s.limits.min_cell_gap * s.domain.spacing_um;
      if (*pop.min_gap_um < set_up_gap)
        r.fail(*r.find(p + "min_gap_um"), p + "min_gap_um",
               "is below limits.min_cell_gap × domain.spacing_um = " + format_number(set_up_gap) +
                   " µm, the set-up's smallest distance between the markers of two cells");
    }
    pop.seed = r.integer(p + "seed");
    pop.attempts_per_cell = r.integer(p + "attempts_per_cell");

    const SeedingResult placed = seed_population(pop, seeding_domain(s), s.cells);
    if (!placed.reached()) {
      const std::string target_key = p + (pop.count ? "count" : "area_fraction");
      r.fail(*r.find(target_key), target_key,
             "cannot be reached: " + std::to_string(placed.cells.size()) + " of " + std::to_string(placed.target) +
                 " cells placed (area fraction " + format_number(placed.area_fraction) + ") before " + p +
                 "attempts_per_cell = " + std::to_string(pop.attempts_per_cell) +
                 " random draws of the next cell all came closer than " + format_number(placed.gap_um) +
                 " µm (min_gap_um) to a cell or a wall: lower the target or the gap, or enlarge the domain");
    }
    s.population_placements.push_back({s.cells.size(), placed.cells.size(), placed.area_fraction});
    s.cells.insert(s.cells.end(), placed.cells.begin(), placed.cells.end());
    s.cell_populations.push_back(pop);
  }
}

// [[stop_when]] (scene.hpp; docs/scenes.md): exactly one condition per entry.
void read_stop_when(const Reader& r, Scene& s) {
  const toml::node* rules = r.find("stop_when");
  if (!rules) return;
  const std::size_t count = rules->as_array()->size();
  for (std::size_t i = 0; i < count; ++i) {
    const std::string p = "stop_when[" + std::to_string(i) + "].";
    const toml::node* entry = rules->as_array()->get(i);
    if (!r.has(p + "series"))
      throw InputError(r.where(entry) + ": missing key '" + p + "series' (required: the name of a diagnostics series)");
    StopWhenSpec w;
    w.series = r.text(p + "series");
    const int conditions = static_cast<int>(r.has(p + "below")) + static_cast<int>(r.has(p + "above")) +
                           static_cast<int>(r.has(p + "change_below"));
    if (conditions != 1) {
      std::string given;  // name the keys given, so a message about one of them names it
      for (const char* c : {"below", "above", "change_below"})
        if (r.has(p + c)) given += std::string(given.empty() ? ": '" : ", '") + p + c + "'";
      throw InputError(r.where(entry) + ": [[stop_when]] entry " + std::to_string(i) +
                       " needs exactly one of below, above, change_below (has " + std::to_string(conditions) + given +
                       ")");
    }
    if (r.has(p + "below")) w.below = r.number(p + "below");
    if (r.has(p + "above")) w.above = r.number(p + "above");
    if (r.has(p + "change_below")) w.change_below = r.number(p + "change_below");
    w.window_steps = r.integer(p + "window_steps", 0);
    if (!w.change_below && r.has(p + "compare"))
      r.fail(*r.find(p + "compare"), p + "compare", "is only allowed with change_below");
    w.compare_window_means = r.text(p + "compare") == "window_means";
    if (w.change_below && w.window_steps < 1)
      throw InputError(r.where(entry) + ": missing key '" + p +
                       "window_steps' (required with change_below: the steps between the two values compared)");
    if (!w.change_below && r.has(p + "window_steps"))
      r.fail(*r.find(p + "window_steps"), p + "window_steps", "is only allowed with change_below");
    w.min_steps = r.integer(p + "min_steps");
    w.after_steps = r.integer(p + "after_steps");
    s.stop_when.push_back(w);
  }
}

// [transport], [[species]], [hemoglobin] (scene.hpp; docs/scenes.md).
void read_transport(const Reader& r, Scene& s) {
  if (r.has("transport")) {
    TransportSpec t;
    t.coupling = r.text("transport.coupling");
    if (r.has("transport.time_step_s")) t.time_step_s = r.number("transport.time_step_s");
    t.fluid_steps_per_step = r.integer("transport.fluid_steps_per_step", t.fluid_steps_per_step);
    t.stencil = r.text("transport.stencil");
    t.collision = r.text("transport.collision");
    t.trt_magic = r.number("transport.trt_magic");
    if (r.has("transport.velocity_um_s")) t.velocity_um_s = r.vec2("transport.velocity_um_s");
    t.cell_representation = r.text("transport.cell_representation");
    t.interface = r.text("transport.interface");
    t.layer_mean = r.text("transport.layer_mean");
    t.readout = r.text("transport.readout");
    s.transport = t;
  }
  if (const toml::node* species = r.find("species")) {
    if (!s.transport)
      throw InputError(r.where(species) + ": [[species]] needs a [transport] table (transport.coupling, time step)");
    const std::size_t count = species->as_array()->size();
    for (std::size_t i = 0; i < count; ++i) {
      const std::string p = "species[" + std::to_string(i) + "].";
      require_entry_keys(r, "species", i, {"name", "diffusivity_um2_s"});
      SpeciesSpec sp;
      sp.name = r.text(p + "name");
      for (const SpeciesSpec& other : s.species)
        if (other.name == sp.name) r.fail(*r.find(p + "name"), p + "name", "is used by two [[species]] entries");
      sp.diffusivity_um2_s = r.number(p + "diffusivity_um2_s");
      if (r.has(p + "cell_diffusivity_um2_s")) sp.cell_diffusivity_um2_s = r.number(p + "cell_diffusivity_um2_s");
      sp.initial_uM = r.number(p + "initial_uM");
      if (r.has(p + "cell_initial_uM")) sp.cell_initial_uM = r.number(p + "cell_initial_uM");
      sp.source_uM_per_s = r.number(p + "source_uM_per_s");
      sp.decay_per_s = r.number(p + "decay_per_s");
      const char* sides[] = {"left", "right", "bottom", "top"};
      for (int k = 0; k < 4; ++k) {
        sp.side[k] = r.text(p + sides[k], "");
        sp.side_value[k] = r.number(p + sides[k] + "_value", 0.0);
        const bool valued = sp.side[k] == "fixed_concentration" || sp.side[k] == "fixed_flux";
        if (!valued && r.has(p + sides[k] + "_value"))
          r.fail(*r.find(p + sides[k] + "_value"), p + sides[k] + "_value",
                 "is not allowed here: only a fixed_concentration or fixed_flux side takes a value");
        if (valued && !r.has(p + sides[k] + "_value"))
          r.fail(*r.find(p + sides[k]), p + sides[k],
                 "needs " + p + sides[k] + "_value (µM for fixed_concentration, µM·µm/s inward for fixed_flux)");
      }
      s.species.push_back(sp);
    }
  }
  if (s.transport && s.species.empty())
    throw InputError(r.where_table("transport") + ": [transport] needs at least one [[species]] entry");
  if (const toml::node* layers = r.find("transport.layers")) {  // [[transport.layers]] (scene.hpp)
    const std::size_t count = layers->as_array()->size();
    for (std::size_t i = 0; i < count; ++i) {
      const std::string p = "transport.layers[" + std::to_string(i) + "].";
      require_entry_keys(r, "transport.layers", i, {"species", "y_um"});
      TransportLayerSpec l;
      l.species = r.text(p + "species");
      if (std::none_of(s.species.begin(), s.species.end(), [&](const SpeciesSpec& sp) { return sp.name == l.species; }))
        r.fail(*r.find(p + "species"), p + "species", "names no [[species]] entry");
      l.y_um = read_band(r, p + "y_um");
      if (r.has(p + "x_um")) l.x_um = read_band(r, p + "x_um");
      if (r.has(p + "diffusivity_um2_s")) l.diffusivity_um2_s = r.number(p + "diffusivity_um2_s");
      if (r.has(p + "decay_per_s")) l.decay_per_s = r.number(p + "decay_per_s");
      if (r.has(p + "source_uM_per_s")) l.source_uM_per_s = r.number(p + "source_uM_per_s");
      s.transport_layers.push_back(l);
    }
  }
  read_no_o2(r, s);
  if (r.has("hemoglobin")) {
    if (!s.transport)
      throw InputError(r.where_table("hemoglobin") + ": [hemoglobin] needs [transport] and an O2 [[species]] entry");
    HemoglobinSpec hb;
    hb.species = r.text("hemoglobin.species");
    hb.k_off_per_s = r.number("hemoglobin.k_off_per_s");
    hb.heme_uM = r.number("hemoglobin.heme_uM");
    hb.solubility_uM_per_torr = r.number("hemoglobin.solubility_uM_per_torr");
    hb.p50_torr = r.number("hemoglobin.p50_torr");
    hb.hill_n = r.number("hemoglobin.hill_n");
    hb.rate_modifier = r.number("hemoglobin.rate_modifier");
    if (r.has("hemoglobin.initial_saturation"))
      hb.initial_saturation = r.number("hemoglobin.initial_saturation");
    hb.kinetics = r.text("hemoglobin.kinetics");
    hb.coupling = r.text("hemoglobin.coupling");
    hb.mean_pressure = r.text("hemoglobin.mean_pressure");
    hb.heme_weights = r.text("hemoglobin.heme_weights");
    const bool known = std::any_of(s.species.begin(), s.species.end(),
                                   [&](const SpeciesSpec& sp) { return sp.name == hb.species; });
    if (!known)
      throw InputError(r.where_table("hemoglobin") + ": hemoglobin.species = \"" + hb.species +
                       "\" names no [[species]] entry");
    if (s.cells.empty())
      throw InputError(r.where_table("hemoglobin") + ": [hemoglobin] acts inside cells: the scene has no [[cells]]");
    s.hemoglobin = hb;
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& origin, const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(std::string_view(text), std::string_view(origin));
  } catch (const toml::parse_error& e) {
    throw InputError(origin + ":" + std::to_string(e.source().begin.line) + ":" +
                     std::to_string(e.source().begin.column) + ": malformed TOML: " + std::string(e.description()));
  }
  for (const std::string& o : overrides) apply_override(root, o, origin);

  const Reader reader(root, origin);
  reader.reject_unknown(root, "");
  Scene scene = read_scene(reader, origin);

  std::ostringstream os;  // the scene exactly as it will run (after overrides)
  os << toml::toml_formatter(root) << '\n';
  scene.source_text = os.str();
  scene.source_path = origin;
  return scene;
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError("cannot read scene file '" + path + "': it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const std::string reason = std::filesystem::exists(path, ec) ? "permission denied" : "no such file";
    throw InputError("cannot read scene file '" + path + "': " + reason);
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError("cannot read scene file '" + path + "': read error");
  return parse_scene(text.str(), path, overrides);
}

}  // namespace erythro::scene
