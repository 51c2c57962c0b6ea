#include "app/commands.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <new>

#include "app/progress.hpp"
#include "app/resources.hpp"
#include "common/error.hpp"
#include "io/atomic_file.hpp"
#include "io/baseline_compare.hpp"
#include "io/scene_run.hpp"
#include "scene/resource_estimate.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"
#include "simulation/simulation.hpp"

namespace erythro::app {
namespace fs = std::filesystem;

namespace {

int report(int code, const std::string& message) {
  std::cerr << "erythro: error: " << message << "\n";
  return code;
}

// Runs `body`, mapping the project's error types to exit codes.
template <class Body>
int guarded(Body&& body) {
  try {
    return body();
  } catch (const InputError& e) {
    return report(exit_code::bad_input, e.what());
  } catch (const OutputError& e) {
    return report(exit_code::output_failure, e.what());
  } catch (const std::bad_alloc&) {  // e.g. a run started with --ignore-memory-check
    return report(exit_code::runtime_failure, "out of memory (`erythro check` shows the run's estimated memory)");
  } catch (const std::exception& e) {
    return report(exit_code::runtime_failure, std::string("internal error: ") + e.what());
  }
}

// Refuses to overwrite an earlier run unless forced; never deletes anything else.
void prepare_output_folder(const std::string& dir, bool force) {
  io::ensure_writable_directory(dir);
  for (const char* name : {"run.h5", "run.xdmf"}) {
    const fs::path p = fs::path(dir) / name;
    if (fs::exists(p) && !force) {
      throw OutputError("output '" + p.string() + "' already exists; use --force to overwrite it or --out to choose another folder");
    }
  }
}

}  // namespace

int run_command(const RunOptions& options) {
  return guarded([&] {
    scene::Scene scene = scene::load_scene(options.scene_path, options.overrides);
    const scene::LatticeSetup setup = scene::derive_lattice(scene);
    check_run_resources(scene::estimate_resources(scene, setup), options.scene_path, options.ignore_memory_check,
                        std::cerr);
    const std::string out_dir =
        options.out_dir.empty() ? (fs::path("out") / fs::path(options.scene_path).stem()).string() : options.out_dir;
    prepare_output_folder(out_dir, options.force);

    ProgressDisplay progress(options.quiet);
    const io::SceneRunResult run = io::run_scene(std::move(scene), setup, out_dir, {&progress});
    std::cout << "results: " << run.h5_path << "\n" << "fields:  " << run.xdmf_path << "\n";
    if (run.summary.status == sim::RunStatus::stopped) std::cout << "stopped: " << run.summary.diagnosis << "\n";
    if (run.summary.status == sim::RunStatus::diverged) {
      std::cerr << "erythro: " << run.summary.diagnosis << "\n"
                << "erythro: everything up to the last healthy output is in " << run.h5_path << "\n";
      return exit_code::diverged;
    }
    return exit_code::ok;
  });
}

int check_command(const std::string& scene_path, const std::vector<std::string>& overrides) {
  return guarded([&] {
    const scene::Scene scene = scene::load_scene(scene_path, overrides);
    const scene::LatticeSetup setup = scene::derive_lattice(scene);
    std::cout << scene::format_lattice_report(scene, setup)
              << scene::format_resource_report(scene::estimate_resources(scene, setup));
    return exit_code::ok;
  });
}

int compare_command(const std::string& current, const std::string& baseline, const std::string& tolerances) {
  return guarded([&] {
    const io::BaselineReport result = io::compare_to_baseline(current, baseline, tolerances);
    std::cout << "comparing " << current << " with baseline " << baseline << "\n" << result.to_text();
    return result.passed() ? exit_code::ok : exit_code::regression;
  });
}

}  // namespace erythro::app
