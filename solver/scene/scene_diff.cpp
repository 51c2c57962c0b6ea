#include "scene/scene_diff.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <toml++/toml.h>

#include "common/error.hpp"

namespace erythro::scene {
namespace {

// Every leaf of `node` as "path" → its TOML text; arrays of tables by entry ("cells[1].shape").
void flatten(const toml::node& node, const std::string& path, std::map<std::string, std::string>& out) {
  if (const toml::table* t = node.as_table()) {
    for (const auto& [key, value] : *t) flatten(value, path.empty() ? std::string(key.str()) : path + "." + std::string(key.str()), out);
    return;
  }
  if (const toml::array* a = node.as_array(); a && a->is_array_of_tables()) {
    for (std::size_t i = 0; i < a->size(); ++i) flatten(*a->get(i), path + "[" + std::to_string(i) + "]", out);
    return;
  }
  std::ostringstream text;
  text << toml::node_view<const toml::node>(node);
  out[path] = text.str();
}

std::map<std::string, std::string> leaves(const std::string& text, const std::string& what) {
  std::map<std::string, std::string> out;
  try {
    flatten(toml::parse(std::string_view(text), std::string_view(what)), "", out);
  } catch (const toml::parse_error& e) {
    throw InputError(what + ": malformed TOML: " + std::string(e.description()));
  }
  return out;
}

}  // namespace

std::vector<std::string> changed_keys(const std::string& before, const std::string& after) {
  const auto a = leaves(before, "the checkpoint's scene"), b = leaves(after, "the restart's scene");
  std::vector<std::string> changed;
  for (const auto& [key, value] : a)
    if (const auto it = b.find(key); it == b.end() || it->second != value) changed.push_back(key);
  for (const auto& [key, value] : b)
    if (!a.count(key)) changed.push_back(key);
  std::sort(changed.begin(), changed.end());
  return changed;
}

bool restart_may_change(const std::string& key) {
  static const char* const safe[] = {"run.duration_s",
                                     "run.steps",
                                     "output.fields_interval_steps",
                                     "output.diagnostics_interval_steps",
                                     "output.checkpoint_interval_steps",
                                     "output.checkpoint_interval_s"};
  return std::find(std::begin(safe), std::end(safe), key) != std::end(safe);
}

}  // namespace erythro::scene
