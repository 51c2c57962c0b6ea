#include "simulation/observation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "membrane/cell_health.hpp"

namespace erythro::sim {
namespace {
bool due(long step, long interval) { return interval > 0 && step % interval == 0; }

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n) d = std::max(d, std::abs(a[n] - b[n]));
  return d;
}

// "diverged at step S: quantity = value at node (i, j) [x = … um, y = … um]"
void describe_where(std::ostream& out, long step, const HealthReport& r, const scene::LatticeSetup& setup) {
  const double h_um = setup.scales.length_m * 1e6;
  out << "diverged at step " << step << ": " << r.quantity << " = " << r.value << " at node (" << r.node_x << ", "
      << r.node_y << ") [x = " << (static_cast<double>(r.node_x) + 0.5) * h_um
      << " um, y = " << (static_cast<double>(r.node_y) + 0.5) * h_um << " um]";
}
}  // namespace

std::string describe_divergence(long step, const HealthReport& r, const scene::LatticeSetup& setup) {
  std::ostringstream out;
  describe_where(out, step, r, setup);
  if (std::isnan(r.limit)) {
    out << " is not finite";
  } else if (r.quantity == "density") {
    out << " is not positive";
  } else {
    out << " exceeds the limit " << r.limit << " (monitor.max_mach)";
  }
  out << "; tau = " << setup.collision.tau << ", expected Ma = " << setup.mach
      << ". Lower the velocity or force, raise tau, or refine the grid.";
  return out.str();
}

std::string describe_transport_divergence(long step, const HealthReport& r, const scene::LatticeSetup& setup) {
  std::ostringstream out;
  if (r.node_x >= 0) describe_where(out, step, r, setup);
  else out << "diverged at step " << step << ": " << r.quantity << " = " << r.value;  // a cell's saturation
  if (std::isnan(r.limit)) out << " is not finite";
  else out << " is outside its limit " << r.limit;
  if (!r.hint.empty()) out << ", " << r.hint;
  out << ". Lower transport.time_step_s or the diffusivity, or check the sides' values (docs/transport.md).";
  return out.str();
}

std::string describe_cell_divergence(long step, const HealthReport& r) {
  std::ostringstream out;
  out << "diverged at step " << step << ": " << r.quantity << " = " << r.value;
  if (r.node_y >= 0) out << " at marker " << r.node_y;
  if (std::isnan(r.limit)) {
    out << " is not finite; lower the moduli or the time step (see erythro check's stability numbers)";
  } else {
    const bool area = r.quantity.find("area") != std::string::npos;
    out << " exceeds the limit " << r.limit << (area ? " (monitor.max_area_change)" : " (monitor.max_edge_strain)")
        << "; the membrane " << (area ? "lost or gained area" : "tore")
        << ": lower the capillary number or the time step, refine, or raise membrane.area_modulus_Pa";
  }
  return out.str();
}

Observation::Observation(const scene::Scene& scene, const scene::LatticeSetup& setup, fluid::FluidLattice* fluid,
                         const CellPhysics* cells, const TransportPhysics* transport,
                         std::vector<std::unique_ptr<Probe>>& probes, RunObserver& observer, RunControl& control)
    : scene_(scene),
      setup_(setup),
      fluid_(fluid),
      cells_(cells),
      transport_(transport),
      probes_(probes),
      observer_(observer),
      control_(control) {}

void Observation::declare() {
  series_.push_back({"step", "", "steps done"});
  series_.push_back({"time_s", "s", "physical time, steps x time step"});
  for (const auto& p : probes_) {
    probe_offset_.push_back(series_.size());
    p->declare(series_);
  }
  row_.assign(series_.size(), 0.0);
  const std::string origin = scene_.source_path.empty() ? "scene" : scene_.source_path;
  for (std::size_t i = 0; i < scene_.stop_when.size(); ++i) stop_rules_.emplace_back(scene_.stop_when[i], i, series_, origin);
  observer_.on_series_declared(series_);
  const std::size_t rows = static_cast<std::size_t>(setup_.grid.ny);
  for (const auto& p : probes_) {
    profile_offset_.push_back(profiles_.size() * rows);
    p->declare_profiles(profiles_);
  }
  profile_row_.assign(profiles_.size() * rows, 0.0);
  if (!profiles_.empty()) observer_.on_profiles_declared(profiles_);
}

bool Observation::healthy(long step) {
  if (transport_) {
    const HealthReport h = transport_->check_health();
    if (!h.healthy) {
      control_.end(RunStatus::diverged, describe_transport_divergence(step, h, setup_));
      return false;
    }
  }
  if (cells_) {
    const HealthReport h =
        membrane::check_health(cells_->cells(), {scene_.monitor.max_area_change, scene_.monitor.max_edge_strain});
    if (!h.healthy) {
      control_.end(RunStatus::diverged, describe_cell_divergence(step, h));
      return false;
    }
  }
  return true;
}

void Observation::sample(long step, const fluid::Moments* moments) {
  row_[0] = static_cast<double>(step);
  row_[1] = static_cast<double>(step) * setup_.scales.time_s;
  const ProbeContext context{step, setup_, moments, cells_, transport_};
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    const std::size_t end = i + 1 < probes_.size() ? probe_offset_[i + 1] : row_.size();
    probes_[i]->sample(context, std::span<double>(row_).subspan(probe_offset_[i], end - probe_offset_[i]));
  }
  observer_.on_sample(step, row_);
  if (!profiles_.empty()) {
    for (std::size_t i = 0; i < probes_.size(); ++i) {
      const std::size_t end = i + 1 < probes_.size() ? profile_offset_[i + 1] : profile_row_.size();
      if (end == profile_offset_[i]) continue;
      const std::span<double> values(profile_row_.data() + profile_offset_[i], end - profile_offset_[i]);
      probes_[i]->sample_profiles(context, values);
    }
    observer_.on_profiles(step, profile_row_);
  }
  for (StopRule& rule : stop_rules_)
    if (!control_.stop && rule.check(step, row_)) control_.end(RunStatus::stopped, rule.diagnosis());
}

void Observation::output_fields(long step, const fluid::Moments* moments) {
  if (moments) observer_.on_fields(step, *moments);
  if (moments && cells_) observer_.on_cells(step, cells_->cells());
  if (!transport_) return;
  TransportFields f;
  for (std::size_t i = 0; i < transport_->species_count(); ++i) {
    f.names.push_back(transport_->name(i));
    f.concentration.push_back(transport_->readout(i));  // C, or Ĉ (transport.readout)
  }
  observer_.on_transport_fields(step, f);
}

void Observation::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "steady_previous_ux", previous_ux_);
  r.put(prefix + "steady_previous_uy", previous_uy_);
  for (std::size_t i = 0; i < stop_rules_.size(); ++i)
    stop_rules_[i].save_state(r, prefix + "stop_when_" + std::to_string(i) + ".");
  for (std::size_t i = 0; i < probes_.size(); ++i) probes_[i]->save_state(r, prefix + "probe_" + std::to_string(i) + ".");
}

void Observation::restore_state(const StateRecord& r, const std::string& prefix) {
  previous_ux_ = r.get(prefix + "steady_previous_ux");
  previous_uy_ = r.get(prefix + "steady_previous_uy");
  for (std::size_t i = 0; i < stop_rules_.size(); ++i)
    stop_rules_[i].restore_state(r, prefix + "stop_when_" + std::to_string(i) + ".");
  for (std::size_t i = 0; i < probes_.size(); ++i) probes_[i]->restore_state(r, prefix + "probe_" + std::to_string(i) + ".");
}

void Observation::observe(long step, bool final_state) {
  const auto& out = scene_.output;
  const auto& steady = scene_.run.steady_state;
  const bool fields = final_state || due(step, out.fields_interval_steps) || step == 0;
  const bool diagnostics =
      final_state || due(step, out.diagnostics_interval_steps) || step == 0 || step <= out.dense_diagnostics_steps;
  const bool monitor = due(step, scene_.monitor.interval_steps);
  const bool steady_check = steady && due(step, steady->check_interval_steps) && step > 0;
  if (!(fields || diagnostics || monitor || steady_check)) return;
  if (!healthy(step)) return;  // health first: nothing unhealthy is ever written

  if (!fluid_) {  // still medium: the transport is all there is
    if (diagnostics) sample(step, nullptr);
    if (fields || (control_.stop && control_.status == RunStatus::stopped)) output_fields(step, nullptr);
    return;
  }
  fluid::Moments m = fluid_->moments();
  const HealthReport health = fluid::check_health(setup_.grid, m, scene_.monitor.max_mach);
  if (!health.healthy) {
    control_.end(RunStatus::diverged, describe_divergence(step, health, setup_));
    return;
  }
  if (diagnostics) sample(step, &m);
  const bool stopped = control_.stop && control_.status == RunStatus::stopped;
  if (fields || stopped) output_fields(step, &m);
  if (stopped) return;
  if (steady_check) {
    if (!previous_ux_.empty()) {
      const double umax = health.max_speed;  // the health scan's max |u|, no second pass
      const double change = std::max(max_abs_difference(m.ux, previous_ux_), max_abs_difference(m.uy, previous_uy_));
      if (umax > 0.0 && change / umax < steady->tolerance) {
        control_.end(RunStatus::steady_state, "");
        if (!fields) output_fields(step, &m);
        if (!diagnostics) sample(step, &m);
        return;
      }
    }
    // Last use of m: keep its velocity for the next check without copying it.
    previous_ux_ = std::move(m.ux);
    previous_uy_ = std::move(m.uy);
  }
}

}  // namespace erythro::sim
