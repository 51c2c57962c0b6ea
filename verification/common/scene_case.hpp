#pragma once
// How every V&V case runs the solver: as a scene (a TOML file beside the case, read with
// --set-style overrides exactly as `erythro run FILE --set k=v` reads it), run by
// io::run_scene (the simulation and the run writer, as the command does) into
// <results>/runs/<case>/<label>/, and judged from the run.h5 it wrote (io::RunFile).
#include <functional>
#include <string>
#include <vector>

#include "io/result_record.hpp"
#include "io/run_file.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "simulation/run_observer.hpp"
#include "simulation/simulation.hpp"

namespace erythro::vv {

// "key=value" with the value written to round-trip (17 significant digits), for overrides.
std::string set(const std::string& key, double value);
std::string set(const std::string& key, long value);
std::string set(const std::string& key, const std::string& text);  // the TOML value as written, e.g. "\"trt\""
std::string set(const std::string& key, double x, double y);       // a 2-vector [x, y]

// The scene file at `relative_path` (from the source tree, $ERYTHRO_SOURCE_DIR) with the
// overrides applied, parsed and checked as by the command.
scene::Scene case_scene(const std::string& relative_path, const std::vector<std::string>& overrides = {});

struct CaseRun {
  scene::Scene scene;
  scene::LatticeSetup setup;
  sim::RunSummary summary;
  io::RunFile file;  // run.h5 as written
  double wall_time_s = 0.0;  // of this call; a run read back or continued: of the run's own (last) part
  std::vector<io::FieldPicture> pictures;  // with CaseRunOptions::pictures: the last field output
  // With CaseRunOptions::resume: what the folder gave (run_resume.hpp), the step continued
  // from (−1: run from the start or read back) and whether the run was read back.
  std::string resume_note;
  long resumed_from_step = -1;
  bool read_back = false;
  bool ok() const { return summary.status != sim::RunStatus::diverged; }
};

struct CaseRunOptions {
  // Called with the simulation before it runs: extra stages or probes, an initial field.
  std::function<void(sim::Simulation&)> configure;
  // Further observers (besides the run writer), e.g. one that keeps fields in memory.
  std::vector<sim::RunObserver*> observers;
  // Keep <results>/runs/<case>/<label>/ (run.h5, run.xdmf) after the run has been read
  // back, e.g. for the report's field pictures; otherwise it is removed.
  bool keep = false;
  // Read pictures of the last field output (speed, concentrations, membranes) for the
  // report: record.add_field(p) for each of CaseRun::pictures.
  bool pictures = false;
  // Continue after a kill (run_resume.hpp): read back the folder's finished run of this scene,
  // or continue from its checkpoint, when this build wrote them; the folder is then kept.
  // The scene should ask for checkpoints (output.checkpoint_interval_s). Only for runs
  // without `observers` (a run read back feeds none).
  bool resume = false;
};

// Derives the lattice set-up (InputError for an impossible scene), runs the scene and
// reads its run.h5 back.
CaseRun run_case_scene(const scene::Scene& scene, const std::string& case_name, const std::string& label,
                       const CaseRunOptions& options = {});

}  // namespace erythro::vv
