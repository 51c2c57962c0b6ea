#include "app/restart.hpp"

#include <filesystem>

#include "common/error.hpp"
#include "io/run_history.hpp"
#include "scene/scene_diff.hpp"
#include "scene/scene_parser.hpp"

namespace erythro::app {
namespace fs = std::filesystem;
namespace {

void refuse_changes(const std::string& stored, const std::string& now, const std::string& checkpoint_path) {
  std::string refused;
  for (const std::string& key : scene::changed_keys(stored, now))
    if (!scene::restart_may_change(key)) refused += (refused.empty() ? "" : ", ") + key;
  if (!refused.empty())
    throw InputError("--restart: the scene differs from the one in " + checkpoint_path + " in " + refused +
                     "; a restart continues the same run, so only run.duration_s, run.steps and the output "
                     "intervals (output.*_interval_steps, output.checkpoint_interval_s) may change");
}

}  // namespace

Restart::Restart(const RunOptions& options) : checkpoint_(io::read_checkpoint(options.restart_dir)) {
  scene_ = options.scene_path.empty() ? scene::parse_scene(checkpoint_.scene_text, checkpoint_.path, options.overrides)
                                      : scene::load_scene(options.scene_path, options.overrides);
  refuse_changes(checkpoint_.scene_text, scene_.source_text, checkpoint_.path);
  restart_dir_ = options.restart_dir;
  out_dir_ = options.out_dir.empty() ? restart_dir_ : options.out_dir;
  history_ = io::interrupted_run_file(options.restart_dir);
}

bool Restart::set_aside_interrupted_run() {
  if (!fs::exists(out_dir_) || !fs::equivalent(restart_dir_, out_dir_)) return false;
  history_ = io::set_aside_interrupted_run(history_, restart_dir_);
  return true;
}

std::function<void(sim::Simulation&)> Restart::restore() {
  return [this](sim::Simulation& simulation) { simulation.restore(std::move(checkpoint_.state)); };
}

std::string Restart::carry_over_history(const std::string& h5_path, const std::string& xdmf_path) const {
  return io::carry_over_history(history_, h5_path, xdmf_path, checkpoint_.step);
}

}  // namespace erythro::app
