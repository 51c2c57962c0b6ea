#include "scene_case.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "common/case_support.hpp"
#include "common/error.hpp"
#include "common/run_resume.hpp"
#include "io/field_pictures.hpp"
#include "io/run_history.hpp"
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

namespace {
sim::RunSummary summary_of(const io::RunFile& file) {
  sim::RunSummary s;
  s.status = *sim::run_status_from(file.status());
  s.steps = file.steps();
  s.wall_time_s = file.wall_time_s();
  s.diagnosis = file.diagnosis();
  return s;
}
}  // namespace

CaseRun run_case_scene(const scene::Scene& scene, const std::string& case_name, const std::string& label,
                       const CaseRunOptions& options) {
  Stopwatch clock;
  CaseRun run;
  run.scene = scene;
  run.setup = scene::derive_lattice(scene);
  const fs::path dir = fs::path(io::ResultRecord::results_dir()) / "runs" / case_name / folder_name(label);
  if (options.resume && !options.observers.empty())
    throw std::logic_error("run_case_scene: a resumable run takes no observers (a run read back feeds none)");
  ResumePoint from;
  if (options.resume) from = find_resume_point(dir.string(), scene.source_text);
  run.resume_note = from.note;
  if (from.finished) {
    run.file = std::move(*from.finished);
    run.summary = summary_of(run.file);
    run.read_back = true;
  } else {
    std::string history;
    if (from.checkpoint) {
      history = io::set_aside_interrupted_run(io::interrupted_run_file(dir.string()), dir.string());
    } else {
      fs::remove_all(dir);
      fs::create_directories(dir);
    }
    // The case's own stages and probes first, then the checkpoint's state (which holds theirs).
    auto configure = [&](sim::Simulation& simulation) {
      if (options.configure) options.configure(simulation);
      if (from.checkpoint) simulation.restore(std::move(from.checkpoint->state));
    };
    const io::SceneRunResult result = io::run_scene(scene, run.setup, dir.string(), options.observers, configure);
    if (from.checkpoint) {
      io::carry_over_history(history, result.h5_path, result.xdmf_path, from.checkpoint->step);
      run.resumed_from_step = from.checkpoint->step;
    }
    run.summary = result.summary;
    run.file = io::RunFile(result.h5_path);
  }
  if (options.pictures) run.pictures = io::last_field_pictures(run.file.path(), label);
  if (!options.keep && !options.resume) fs::remove_all(dir);
  run.wall_time_s = run.read_back ? run.summary.wall_time_s : clock.seconds();
  return run;
}

}  // namespace erythro::vv
