#include "io/scene_run.hpp"

#include "io/checkpoint.hpp"
#include "io/run_writer.hpp"

namespace erythro::io {

SceneRunResult run_scene(scene::Scene scene, const scene::LatticeSetup& setup, const std::string& out_dir,
                         const std::vector<sim::RunObserver*>& observers,
                         const std::function<void(sim::Simulation&)>& configure) {
  sim::Simulation simulation(std::move(scene), setup);
  if (configure) configure(simulation);
  RunWriter writer(out_dir);
  // When output.checkpoint_interval_* asks: run.h5 holds every sample before the
  // checkpoint's step before the checkpoint exists (a restart carries them over).
  simulation.set_checkpoint_writer([&](long step, const StateRecord& state) {
    writer.flush();
    write_checkpoint(out_dir, simulation.scene().source_text, step, state);
  });
  sim::ObserverList list;
  list.add(writer);
  for (sim::RunObserver* o : observers) list.add(*o);
  SceneRunResult result;
  try {
    result.summary = simulation.run(list);
  } catch (const std::exception& e) {
    writer.abort(e.what());
    throw;
  }
  result.h5_path = writer.h5_path();
  result.xdmf_path = writer.xdmf_path();
  return result;
}

}  // namespace erythro::io
