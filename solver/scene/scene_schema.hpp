#pragma once
// The scene-file schema: every known key and table, with its type, unit, allowed range,
// default and meaning, and the text of the messages about them. Private to scene/; the
// parser takes its checks and defaults from it, and the key reference of docs/scenes.md
// is generated from it (key_reference.hpp).
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace erythro::scene::detail {

// Every number in a scene has a finite range on both sides, at widest |x| <= 1e30 in its key's
// unit (and a positive quantity >= 1e-30, scene_keys.cpp): 30 orders of magnitude beyond any
// physical scene, yet far inside a double's range (1e±308), so the conversions to lattice
// units (products and quotients of a few keys) stay finite and non-zero, and the set-up
// checks after them compare real numbers and blame the key that is wrong, not a derived one.
inline constexpr double kMaxMagnitude = 1e30;
inline constexpr double kMinPositive = 1e-30;

enum class Kind { string, number, integer, vec2, string_list, boolean };

// Allowed interval of a number (or of each element of a vec2); NaN and ±inf never belong.
struct Bound {
  double lo = -kMaxMagnitude;
  bool lo_open = false;  // true: lo itself is excluded
  double hi = kMaxMagnitude;
  bool hi_open = false;

  bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
};

// What a key is when the scene leaves it out: either a TOML literal the parser reads in
// its place ("0.3", "\"bgk\"", "[0.0, 0.0]"), or a note in words for a key that is
// required or whose default follows from other keys ("required", "r0 + 5/β").
struct Default {
  std::string text;
  bool is_literal = false;
};
inline Default literal(std::string toml_value) { return {std::move(toml_value), true}; }
inline Default quoted(const std::string& word) { return {"\"" + word + "\"", true}; }  // a TOML string
inline Default note(std::string words) { return {std::move(words), false}; }

struct KeySpec {
  std::string path;  // full dotted key; [[array]] entries drop the index: "cells.radius_um"
  Kind kind = Kind::number;
  std::string unit;  // "" when dimensionless
  Bound bound;
  std::vector<std::string> choices;  // allowed strings (string, string_list); empty: any
  Default when_absent;
  // A condition beyond `bound` and `choices` that the parser or units.cpp checks together
  // with other keys ("only with law = \"skalak\""); documentation only, "" if none.
  std::string rule;
  std::string meaning;  // one line in plain words (Markdown code spans allowed)
};

struct TableSpec {
  std::string path;     // "boundaries.left", "cells"
  bool array = false;   // an array of tables: [[cells]], one entry per cell
  std::string meaning;  // one line: what the table is for, when it is required
};

// Every key and every table, in the order of docs/scenes.md (scene_keys.cpp).
const std::vector<KeySpec>& known_keys();
const std::vector<TableSpec>& known_tables();

// The schema entry of a dotted key ("cells[3].radius_um" matches "cells.radius_um"), or nullptr.
const KeySpec* find_key(std::string_view path);
// A plain table ([fluid], [boundaries.left]); not an array of tables.
bool is_known_table(std::string_view path);
// [[cells]], [[species]], [[stop_when]], [[fluid.layers]], [[transport.layers]].
bool is_array_of_tables(std::string_view path);
// The table holding a key: "boundaries.left.type" → "boundaries.left".
std::string_view table_of(std::string_view key_path);

// "must be > 0 (cP)", "must be in (0, 1]", "must be one of "bgk", "trt"".
std::string range_text(const KeySpec& k);
// "a number", "an array of 2 numbers", ...
std::string type_text(Kind kind);
// " (did you mean 'x'?)" for the closest known key or table, or "" if none is close.
std::string suggestion(std::string_view bad);

// Shortest round-trip decimal form of v.
std::string format_number(double v);
// The last component of a dotted path.
std::string_view leaf(std::string_view path);

}  // namespace erythro::scene::detail
