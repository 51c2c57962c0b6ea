// The scene-file schema (scene_schema.hpp): finding keys and tables, and the messages about
// them. The keys and tables themselves are listed in scene_keys.cpp.
#include "scene/scene_schema.hpp"

#include <algorithm>
#include <charconv>
#include <limits>

namespace erythro::scene::detail {
namespace {

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
  const Bound& b = k.bound;  // always finite on both sides (scene_schema.hpp)
  s = "must be in " + std::string(b.lo_open ? "(" : "[") + format_number(b.lo) + ", " + format_number(b.hi) +
      (b.hi_open ? ")" : "]");
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
  return std::any_of(t.begin(), t.end(), [&](const TableSpec& s) { return !s.array && s.path == path; });
}

bool is_array_of_tables(std::string_view path) {
  const auto& t = known_tables();
  return std::any_of(t.begin(), t.end(), [&](const TableSpec& s) { return s.array && s.path == path; });
}

std::string_view table_of(std::string_view key_path) {
  const auto dot = key_path.rfind('.');
  return dot == std::string_view::npos ? std::string_view{} : key_path.substr(0, dot);
}

std::string_view leaf(std::string_view path) {
  const auto dot = path.rfind('.');
  return dot == std::string_view::npos ? path : path.substr(dot + 1);
}

// " (did you mean 'x'?)" for the closest known key or table, or "" if none is close:
// a small edit distance on the full dotted key, else the same leaf in another table.
std::string suggestion(std::string_view bad) {
  std::vector<std::string> candidates;  // plain tables, then keys
  for (const TableSpec& t : known_tables())
    if (!t.array) candidates.push_back(t.path);
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
