#pragma once
// One run of a scene as `erythro run` does it: the simulation with the run writer
// (OUT/run.h5 + run.xdmf) and any further observers; a run that throws is closed with
// status "aborted: <reason>" before the exception goes on. The command and the V&V
// cases both run scenes through this function.
#include <functional>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "simulation/run_observer.hpp"
#include "simulation/simulation.hpp"

namespace erythro::io {

struct SceneRunResult {
  sim::RunSummary summary;
  std::string h5_path, xdmf_path;
};

// `configure` (optional) is called with the simulation before it runs (extra stages or
// probes, an initial field). `out_dir` must exist and be writable.
SceneRunResult run_scene(scene::Scene scene, const scene::LatticeSetup& setup, const std::string& out_dir,
                         const std::vector<sim::RunObserver*>& observers = {},
                         const std::function<void(sim::Simulation&)>& configure = {});

}  // namespace erythro::io
