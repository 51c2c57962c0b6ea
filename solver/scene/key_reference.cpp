// The key reference of docs/scenes.md (key_reference.hpp), written from the scene schema.
#include "scene/key_reference.hpp"

#include <vector>

#include "scene/scene_schema.hpp"

namespace erythro::scene {
namespace {

using namespace detail;

const char* const kIntro =
    "Generated from the scene schema, `solver/scene/scene_keys.cpp`, by `erythro schema --write docs/scenes.md`:\n"
    "change the schema, not this section (the test `unit.scenes_doc_current` fails when they differ).\n"
    "\n"
    "Types: *number* is a TOML float or integer (`2` is read as `2.0`). *integer* must be a TOML\n"
    "integer: `steps = 10.5` and `steps = 10.0` are both errors. *[a, b]* is an array of exactly two\n"
    "numbers. Ranges: `(a, b]` excludes `a` and includes `b`. Every range is finite: ±1e30 is the\n"
    "outer limit of any number, 1e-30 of a positive one and 1e12 of a step count (\"Error\n"
    "messages\" below says why). A default in `code` is the value a missing key takes; a default in\n"
    "words says when the key is required or how its value follows from other keys. A condition\n"
    "after the range involves other keys: the parser (`solver/scene/scene_parser.cpp`) or the\n"
    "conversion to lattice units (`solver/scene/units.cpp`) checks it.\n";

// A table cell: '|' would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

std::string type_name(Kind kind) {
  switch (kind) {
    case Kind::string: return "string";
    case Kind::number: return "number";
    case Kind::integer: return "integer";
    case Kind::vec2: return "[a, b]";
    case Kind::string_list: return "array of strings";
    case Kind::boolean: return "true or false";
  }
  return "?";
}

// "[1, 1e+06]", "(0.5, 1e+30]": every bound is finite on both sides (scene_schema.hpp).
std::string bound_text(const Bound& b) {
  return (b.lo_open ? "(" : "[") + format_number(b.lo) + ", " + format_number(b.hi) + (b.hi_open ? ")" : "]");
}

// The allowed values of a key on their own, then the rule involving other keys.
std::string allowed_text(const KeySpec& k) {
  std::string s;
  if (!k.choices.empty()) {
    s = k.kind == Kind::string_list ? "each one of " : "";
    for (std::size_t i = 0; i < k.choices.size(); ++i) s += (i ? ", `\"" : "`\"") + k.choices[i] + "\"`";
  } else if (k.kind == Kind::string) {
    s = "any";
  } else if (k.kind == Kind::boolean) {
    s = "true, false";
  } else {
    s = (k.kind == Kind::vec2 ? "each " : "") + bound_text(k.bound);
  }
  if (k.rule.empty()) return s;
  return s == "any" ? k.rule : s + "; " + k.rule;
}

std::string row(const KeySpec& k, const std::string& table) {
  const std::string key = k.path.substr(table.size() + 1);
  const std::string fallback = k.when_absent.is_literal ? "`" + k.when_absent.text + "`" : k.when_absent.text;
  return "| `" + key + "` | " + type_name(k.kind) + " | " + (k.unit.empty() ? "–" : k.unit) + " | " + cell(fallback) +
         " | " + cell(allowed_text(k)) + " | " + cell(k.meaning) + " |\n";
}

std::string heading_name(const TableSpec& t) { return t.array ? "`[[" + t.path + "]]`" : "`[" + t.path + "]`"; }

struct Section {
  std::string names;  // "`[boundaries.left]`, `[boundaries.right]`"
  std::string body;   // meaning and table
};

}  // namespace

std::string key_reference_markdown() {
  // One section per table that has keys; tables with the same meaning and rows (the four
  // sides) share one section.
  std::vector<Section> sections;
  for (const TableSpec& t : known_tables()) {
    std::string rows;
    for (const KeySpec& k : known_keys())
      if (table_of(k.path) == t.path) rows += row(k, t.path);
    if (rows.empty()) continue;
    const std::string body = t.meaning + "\n\n| key | type | unit | default | allowed | meaning |\n" +
                             "| --- | --- | --- | --- | --- | --- |\n" + rows;
    if (!sections.empty() && sections.back().body == body) sections.back().names += ", " + heading_name(t);
    else sections.push_back({heading_name(t), body});
  }
  std::string out = kIntro;
  for (const Section& s : sections) out += "\n### " + s.names + "\n\n" + s.body;
  return out;
}

}  // namespace erythro::scene
