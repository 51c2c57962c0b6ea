#pragma once
// The scene-file schema: every known key and table, with its type, unit and
// allowed range, and the text of the messages about them. Private to scene/.
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace erythro::scene::detail {

inline constexpr double inf = std::numeric_limits<double>::infinity();

enum class Kind { string, number, integer, vec2, string_list, boolean };

// Allowed interval of a number (or of each element of a vec2).
struct Bound {
  double lo = -inf;
  bool lo_open = false;  // true: lo itself is excluded
  double hi = inf;
  bool hi_open = false;

  bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
};

struct KeySpec {
  std::string path;  // full dotted key
  Kind kind;
  std::string unit;  // "" when dimensionless
  Bound bound;
  std::vector<std::string> choices;  // allowed strings (string, string_list); empty: any
};

// The schema entry of a dotted key ("cells[3].radius_um" matches "cells.radius_um"), or nullptr.
const KeySpec* find_key(std::string_view path);
bool is_known_table(std::string_view path);

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
