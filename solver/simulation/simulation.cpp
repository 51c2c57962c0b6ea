#include "simulation/simulation.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/error.hpp"
#include "fluid/initial_state.hpp"
#include "simulation/checkpoint_schedule.hpp"
#include "simulation/interrupt.hpp"
#include "simulation/observation.hpp"
#include "simulation/probes/cell_shape_probe.hpp"
#include "simulation/probes/channel_probe.hpp"
#include "simulation/probes/channel_profile_probe.hpp"
#include "simulation/probes/shear_probe.hpp"
#include "simulation/probes/contact_probe.hpp"
#include "simulation/probes/fluid_probe.hpp"
#include "simulation/probes/interior_probe.hpp"
#include "simulation/probes/marker_speed_probe.hpp"
#include "simulation/probes/pair_probe.hpp"
#include "simulation/probes/transport_probe.hpp"

namespace erythro::sim {

std::string to_string(RunStatus status) {
  switch (status) {
    case RunStatus::completed: return "completed";
    case RunStatus::steady_state: return "steady_state";
    case RunStatus::stopped: return "stopped";
    case RunStatus::diverged: return "diverged";
    case RunStatus::interrupted: return "interrupted";
  }
  return "?";
}

std::optional<RunStatus> run_status_from(const std::string& text) {
  for (const RunStatus s : {RunStatus::completed, RunStatus::steady_state, RunStatus::stopped, RunStatus::diverged,
                            RunStatus::interrupted})
    if (to_string(s) == text) return s;
  return std::nullopt;
}

Simulation::Simulation(scene::Scene scene, scene::LatticeSetup setup)
    : scene_(std::move(scene)), setup_(std::move(setup)) {
  // Only the modules the scene declares are built; a fluid-only scene has nothing else,
  // a still-medium transport scene has no fluid. Each registers its stages.
  if (setup_.has_fluid) {
    fluid_ = std::make_unique<fluid::FluidLattice>(setup_.grid, setup_.collision, setup_.boundaries);
    fluid::apply_viscosity_layers(*fluid_, setup_.viscosity_layers);  // before the start: its τ is per node
    apply_body_force(0);
    apply_initial_condition();
    if (setup_.membrane)  // cells start at their stress-free rest shape (or pre-stressed, cells.prestretch)
      cells_ = std::make_unique<CellPhysics>(*setup_.membrane, setup_.viscosity, *fluid_);
    register_fluid_stages();
    probes_.push_back(std::make_unique<FluidProbe>());
    if (ChannelProbe::applies(setup_)) probes_.push_back(std::make_unique<ChannelProbe>(cells_.get()));
    if (ShearProbe::applies(setup_)) probes_.push_back(std::make_unique<ShearProbe>());
    if (cells_)
      probes_.push_back(std::make_unique<CellShapeProbe>(*cells_, scene_.output.extremes_interval_steps));
    if (cells_)
      probes_.push_back(std::make_unique<MarkerSpeedProbe>(*cells_, scene_.output.extremes_interval_steps));
    if (cells_ && cells_->index_field()) probes_.push_back(std::make_unique<InteriorProbe>(*cells_));
    if (cells_ && cells_->aggregates() && cells_->cells().cell_count() == 2)  // a doublet
      probes_.push_back(std::make_unique<PairProbe>(*cells_));
    if (cells_ && cells_->contacts() && cells_->contacts()->law().repulsion)
      probes_.push_back(std::make_unique<ContactProbe>(*cells_, scene_.output.extremes_interval_steps));
  } else if (setup_.membrane) {
    for (const scene::CellSetup& c : setup_.membrane->cells) fixed_cells_.push_back(c.shape);
  }
  if (setup_.transport) {
    std::vector<geometry::Polygon> shapes = fixed_cells_;
    if (cells_)
      for (int c = 0; c < cells_->cells().cell_count(); ++c) shapes.push_back(cells_->cells().polygon(c));
    transport_ = std::make_unique<TransportPhysics>(*setup_.transport,
                                                    fluid::domain_of(setup_.grid, setup_.boundaries), shapes);
    register_transport_stages();
    probes_.push_back(std::make_unique<TransportProbe>(*transport_));
  }
  // Last, so that the other probes keep their checkpoint prefixes (probe_<i>); profiles only.
  if (ChannelProbe::applies(setup_)) probes_.push_back(std::make_unique<ChannelProfileProbe>(cells_.get()));
  for (const auto& p : probes_) p->register_stages(loop_);
}

void Simulation::register_fluid_stages() {
  if (setup_.body_force[0] != 0.0 || setup_.body_force[1] != 0.0)
    // The collision of step n (state n → n + 1) happens at t = n + 1, and the velocity
    // after it carries that collision's half force: it uses F(t = n + 1).
    loop_.add(Phase::prepare, "body_force", [this](long step) { apply_body_force(step + 1); });
  // One immersed-boundary cycle per fluid step around the fluid's own stage (cell_physics.hpp).
  if (cells_) cells_->register_stages(loop_, *fluid_);
  loop_.add(Phase::fluid, "fluid_step", [this](long) { fluid_->step(); });
}

void Simulation::register_transport_stages() {
  if (!fluid_) {  // still medium: one transport step per step
    loop_.add(Phase::transport, "transport", [this](long) { transport_->step({}, {}); });
    return;
  }
  // Sub-cycling: one transport step of Δt_T = k Δt_F after every k-th fluid step, with the
  // velocity of the last fluid step and the cells where they are now.
  const long k = std::max(1L, setup_.transport->fluid_steps_per_step);
  loop_.add(
      Phase::transport, "transport",
      [this](long) {
        if (cells_) {
          const membrane::ImmersedCells& cells = cells_->cells();
          moved_.resize(static_cast<std::size_t>(cells.cell_count()));
          for (int c = 0; c < cells.cell_count(); ++c) moved_[static_cast<std::size_t>(c)] = cells.polygon(c);
          transport_->place_cells(moved_);
        }
        const fluid::Moments m = fluid_->moments();
        transport_->step(m.ux, m.uy);
      },
      k, k - 1);
}

void Simulation::add_stage(Phase phase, std::string name, TimeLoop::Function function, long every, long first) {
  if (ran_) throw std::logic_error("Simulation::add_stage after run()");
  loop_.add(phase, std::move(name), std::move(function), every, first);
}

void Simulation::add_probe(std::unique_ptr<Probe> probe) {
  if (ran_) throw std::logic_error("Simulation::add_probe after run()");
  probe->register_stages(loop_);
  probes_.push_back(std::move(probe));
}

void Simulation::set_checkpoint_writer(CheckpointWriter writer) {
  if (ran_) throw std::logic_error("Simulation::set_checkpoint_writer after run()");
  checkpoint_writer_ = std::move(writer);
}

StateRecord Simulation::capture_state(long step, const Observation& observation) const {
  StateRecord r;
  r.put_scalar("step", static_cast<double>(step));
  if (fluid_) fluid_->save_state(r, "fluid.");
  if (cells_) cells_->save_state(r, "cells.");
  if (transport_) transport_->save_state(r, "transport.");
  observation.save_state(r, "observation.");
  return r;
}

void Simulation::restore(StateRecord state) {
  if (ran_) throw std::logic_error("Simulation::restore after run()");
  const long step = static_cast<long>(state.scalar("step"));
  if (step > setup_.total_steps)
    throw InputError("the checkpoint holds step " + std::to_string(step) + ", past the end of the run (" +
                     std::to_string(setup_.total_steps) + " steps): lengthen run.duration_s or run.steps");
  if (fluid_) fluid_->restore_state(state, "fluid.");
  if (cells_) cells_->restore_state(state, "cells.");
  if (transport_) transport_->restore_state(state, "transport.");
  start_step_ = step;
  restored_ = std::move(state);
}

void Simulation::apply_initial_condition() {
  // The analytic flows of [initial] (fluid/initial_state.hpp); with initial.non_equilibrium
  // the populations after a collision at t = 0 (non-equilibrium part, Guo half force F(0)).
  const Grid& g = setup_.grid;
  const std::string& type = scene_.initial.type;
  const bool neq = scene_.initial.non_equilibrium;
  fluid::FlowField field(g.size());
  if (type == "uniform") field = fluid::uniform_flow(g, setup_.initial_velocity, neq);
  if (type == "shear") field = fluid::shear_flow(g, setup_.boundaries, neq);
  if (type == "taylor_green") field = fluid::taylor_green_flow(g, setup_.initial_velocity[0], neq);
  if (type == "double_shear_layer") field = fluid::double_shear_layer_flow(g, setup_.initial_velocity[0], neq);
  if (!neq) {
    fluid_->initialize(field.rho, field.ux, field.uy);
    return;
  }
  if (!field.has_gradients()) field.resize(g.size(), true);  // rest: u = 0, ∇u = 0
  const auto [fx, fy] = fluid_->uniform_force();
  if (fx == 0.0 && fy == 0.0) return fluid::initialize_post_collision(*fluid_, field);
  const std::vector<double> force_x(g.size(), fx), force_y(g.size(), fy);
  fluid::initialize_post_collision(*fluid_, field, force_x, force_y);
}

void Simulation::apply_body_force(long step) {
  const auto [fx, fy] = setup_.body_force;
  const double modulation =
      setup_.force_frequency == 0.0
          ? 1.0
          : std::cos(2.0 * std::numbers::pi * setup_.force_frequency * static_cast<double>(step) + setup_.force_phase);
  fluid_->set_uniform_force(fx * modulation, fy * modulation);
}

RunSummary Simulation::run(RunObserver& observer) {
  if (ran_) throw std::logic_error("Simulation::run called twice");
  ran_ = true;
  using clock = std::chrono::steady_clock;
  RunSummary summary;
  summary.threads = omp_get_max_threads();
  observer.on_start(scene_, setup_);
  RunControl control;
  Observation observation(scene_, setup_, fluid_.get(), cells_.get(), transport_.get(), probes_, observer, control);
  observation.declare();
  if (restored_) {
    observation.restore_state(*restored_, "observation.");
    restored_.reset();
  }

  const long total = setup_.total_steps;
  const double nodes = static_cast<double>(setup_.grid.size());
  const auto start = clock::now();
  double mlups = 0.0;
  // After the probes' own observe stages, before the observation: a restart observes the
  // checkpoint's step exactly as the uninterrupted run did.
  CheckpointSchedule checkpoints(scene_.output.checkpoint_interval_steps, scene_.output.checkpoint_interval_s);
  if (checkpoint_writer_ && checkpoints.enabled())
    loop_.add(Phase::observe, "checkpoint", [&](long step) {
      if (!checkpoints.due(step + 1)) return;
      checkpoint_writer_(step + 1, capture_state(step + 1, observation));
      checkpoints.written();
    });
  loop_.add(Phase::observe, "progress", [&](long step) {
    const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
    mlups = elapsed > 0.0 ? nodes * static_cast<double>(step + 1 - start_step_) / elapsed * 1e-6 : 0.0;
    observer.on_progress(step + 1, total, mlups);
  });
  loop_.add(Phase::observe, "observation", [&](long step) { observation.observe(step + 1, step + 1 == total); });

  long step = start_step_;
  observation.observe(step, step == total);
  while (!control.stop && step < total) {
    if (const int signal = interrupt_signal(); signal != 0) {
      control.end(RunStatus::interrupted,
                  "interrupted by " + signal_name(signal) + " after step " + std::to_string(step));
      break;
    }
    try {
      loop_.run_step(step);
    } catch (const std::domain_error& e) {  // a marker velocity or position is not finite
      ++step;
      control.end(RunStatus::diverged, "diverged at step " + std::to_string(step) + ": membrane markers: " + e.what() +
                                           "; lower the moduli or the time step (see erythro check's stability numbers)");
      break;
    } catch (const interior::FillLeakError& e) {  // a membrane tangled: its interior is no longer closed
      control.end(RunStatus::diverged, "diverged at step " + std::to_string(step) + ": interior index field: " +
                                           e.what() + "; the membrane folded or crossed itself (lower the capillary "
                                                      "number or refine)");
      break;
    }
    ++step;
  }
  summary.status = control.status;
  summary.diagnosis = control.diagnosis;
  summary.steps = step;
  summary.wall_time_s = std::chrono::duration<double>(clock::now() - start).count();
  summary.mlups = mlups;
  summary.stages = loop_.timings();
  if (cells_) {
    summary.index_field_time_s = cells_->index_field_seconds();
    summary.index_field_exposed_time_s = cells_->index_field_exposed_seconds();
    summary.index_field_rebuilds_beside_forces = cells_->rebuilds_beside_forces();
    summary.index_field_rebuilds = summary.index_field_rebuilds_beside_forces + cells_->rebuilds_before_forces();
  }
  observer.on_finish(summary);
  return summary;
}

}  // namespace erythro::sim
