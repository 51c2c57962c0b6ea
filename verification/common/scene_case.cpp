#include "scene_case.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "common/case_support.hpp"
#include "common/error.hpp"
#include "io/field_pictures.hpp"
#include "io/scene_run.hpp"
#include "scene/scene_parser.hpp"

namespace erythro::vv {
namespace fs = std::filesystem;

namespace {
std::string exact(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  std::string s = b;
  // TOML needs a float to look like one: "3" is an integer, "3.0" a float.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string source_dir() {
  const char* dir = std::getenv("ERYTHRO_SOURCE_DIR");
  if (!dir || !*dir) throw InputError("ERYTHRO_SOURCE_DIR is not set (ctest sets it; run the case through ctest)");
  return dir;
}

// A folder name from a label: letters, digits, '.', '-', '_' kept, others '_'.
std::string folder_name(const std::string& label) {
  std::string s = label;
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_')) c = '_';
  return s;
}
}  // namespace

std::string set(const std::string& key, double value) { return key + "=" + exact(value); }
std::string set(const std::string& key, long value) { return key + "=" + std::to_string(value); }
std::string set(const std::string& key, const std::string& text) { return key + "=" + text; }
std::string set(const std::string& key, double x, double y) {
  return key + "=[" + exact(x) + ", " + exact(y) + "]";
}

scene::Scene case_scene(const std::string& relative_path, const std::vector<std::string>& overrides) {
  return scene::load_scene((fs::path(source_dir()) / relative_path).string(), overrides);
}

CaseRun run_case_scene(const scene::Scene& scene, const std::string& case_name, const std::string& label,
                       const CaseRunOptions& options) {
  Stopwatch clock;
  CaseRun run;
  run.scene = scene;
  run.setup = scene::derive_lattice(scene);
  const fs::path dir = fs::path(io::ResultRecord::results_dir()) / "runs" / case_name / folder_name(label);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const io::SceneRunResult result = io::run_scene(scene, run.setup, dir.string(), options.observers, options.configure);
  run.summary = result.summary;
  run.file = io::RunFile(result.h5_path);
  if (options.pictures) run.pictures = io::last_field_pictures(result.h5_path, label);
  if (!options.keep) fs::remove_all(dir);
  run.wall_time_s = clock.seconds();
  return run;
}

}  // namespace erythro::vv
