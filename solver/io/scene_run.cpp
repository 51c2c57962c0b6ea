#include "io/scene_run.hpp"

#include "io/checkpoint.hpp"
#include "io/run_writer.hpp"

namespace erythro::io {

SceneRunResult run_scene(scene::Scene scene, const scene::LatticeSetup& setup, const std::string& out_dir,
                         const std::vector<sim::RunObserver*>& observers,
                         const std::function<void(sim::Simulation&)>& configure) {
  sim::Simulation simulation(std::move(scene), setup);
  simulation.set_checkpoint_writer([&out_dir, &text = simulation.scene().source_text](long step, const StateRecord& s) {
    write_checkpoint(out_dir, text, step, s);  // when output.checkpoint_interval_* asks
  });
  if (configure) configure(simulation);
  RunWriter writer(out_dir);
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
