#include "simulation/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "lattice/d2q9.hpp"

namespace erythro::sim {

std::string to_string(RunStatus status) {
  switch (status) {
    case RunStatus::completed: return "completed";
    case RunStatus::steady_state: return "steady_state";
    case RunStatus::diverged: return "diverged";
  }
  return "?";
}

Simulation::Simulation(scene::Scene scene, scene::LatticeSetup setup)
    : scene_(std::move(scene)), setup_(std::move(setup)) {
  // Only the modules the scene declares are built; a fluid-only scene has nothing else.
  fluid_ = std::make_unique<fluid::FluidLattice>(setup_.grid, setup_.collision, setup_.boundaries);
  apply_initial_condition();
  apply_body_force(0);
}

void Simulation::apply_initial_condition() {
  const Grid& g = setup_.grid;
  const std::size_t N = g.size();
  std::vector<double> rho(N, 1.0), ux(N, 0.0), uy(N, 0.0);
  const std::string& type = scene_.initial.type;
  const auto [u0x, u0y] = setup_.initial_velocity;
  constexpr double two_pi = 2.0 * std::numbers::pi;
  for (int y = 0; y < g.ny; ++y) {
    for (int x = 0; x < g.nx; ++x) {
      const std::size_t n = g.index(x, y);
      // Node centres sit at (i + ½)h: walls (halfway bounce-back) are at 0 and L.
      const double px = x + 0.5, py = y + 0.5;
      if (type == "uniform") {
        ux[n] = u0x;
        uy[n] = u0y;
      } else if (type == "shear") {
        const auto& b = setup_.boundaries.bottom;
        const auto& t = setup_.boundaries.top;
        const double s = py / g.ny;
        ux[n] = b.ux + (t.ux - b.ux) * s;
      } else if (type == "taylor_green") {
        // u = −U cos(kx x) sin(ky y), v = U (kx/ky) sin(kx x) cos(ky y),
        // p = p0 − ρU²/4 [cos(2kx x) + (kx/ky)² cos(2ky y)], ρ = 1 + p'/c_s².
        const double kx = two_pi / g.nx, ky = two_pi / g.ny, U = u0x;
        ux[n] = -U * std::cos(kx * px) * std::sin(ky * py);
        uy[n] = U * (kx / ky) * std::sin(kx * px) * std::cos(ky * py);
        const double p = -0.25 * U * U * (std::cos(2 * kx * px) + (kx / ky) * (kx / ky) * std::cos(2 * ky * py));
        rho[n] = 1.0 + p * d2q9::inv_cs2;
      }
    }
  }
  fluid_->initialize(rho, ux, uy);
}

void Simulation::apply_body_force(long step) {
  const auto [fx, fy] = setup_.body_force;
  const double modulation =
      setup_.force_frequency == 0.0
          ? 1.0
          : std::cos(2.0 * std::numbers::pi * setup_.force_frequency * static_cast<double>(step) + setup_.force_phase);
  fluid_->set_uniform_force(fx * modulation, fy * modulation);
}

DiagnosticsSample diagnose(long step, const fluid::Moments& m) {
  DiagnosticsSample d;
  d.step = step;
  double max_u2 = 0.0;
  for (std::size_t n = 0; n < m.rho.size(); ++n) {
    const double u2 = m.ux[n] * m.ux[n] + m.uy[n] * m.uy[n];
    d.total_mass += m.rho[n];
    d.kinetic_energy += 0.5 * m.rho[n] * u2;
    max_u2 = std::max(max_u2, u2);
  }
  d.max_speed = std::sqrt(max_u2);
  d.max_mach = d.max_speed / std::sqrt(d2q9::cs2);
  return d;
}

std::string describe_divergence(long step, const HealthReport& r, const scene::LatticeSetup& setup) {
  std::ostringstream out;
  const double h_um = setup.scales.length_m * 1e6;
  out << "diverged at step " << step << ": " << r.quantity << " = " << r.value << " at node (" << r.node_x << ", "
      << r.node_y << ") [x = " << (static_cast<double>(r.node_x) + 0.5) * h_um << " um, y = " << (static_cast<double>(r.node_y) + 0.5) * h_um << " um]";
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

namespace {
bool due(long step, long interval) { return interval > 0 && step % interval == 0; }

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n) d = std::max(d, std::abs(a[n] - b[n]));
  return d;
}
}  // namespace

RunSummary Simulation::run(RunObserver& observer) {
  using clock = std::chrono::steady_clock;
  RunSummary summary;
  summary.threads = omp_get_max_threads();
  observer.on_start(scene_, setup_);

  const long total = setup_.total_steps;
  const auto& out = scene_.output;
  const long monitor_every = scene_.monitor.interval_steps;
  const auto& steady = scene_.run.steady_state;
  std::vector<double> previous_ux, previous_uy;
  const double nodes = static_cast<double>(setup_.grid.size());
  const auto start = clock::now();
  double mlups = 0.0;

  // Observes the state after `step` steps; returns false when the monitor stops the run.
  auto observe = [&](long step, bool final_state) -> bool {
    const bool fields = final_state || due(step, out.fields_interval_steps) || step == 0;
    const bool diagnostics = final_state || due(step, out.diagnostics_interval_steps) || step == 0;
    const bool monitor = due(step, monitor_every);
    const bool steady_check = steady && due(step, steady->check_interval_steps) && step > 0;
    if (!(fields || diagnostics || monitor || steady_check)) return true;

    const fluid::Moments m = fluid_->moments();
    // Health first: nothing unhealthy is ever written.
    const HealthReport health = fluid::check_health(setup_.grid, m, scene_.monitor.max_mach);
    if (!health.healthy) {
      summary.status = RunStatus::diverged;
      summary.diagnosis = describe_divergence(step, health, setup_);
      return false;
    }
    if (diagnostics) observer.on_diagnostics(diagnose(step, m));
    if (fields) observer.on_fields(step, m);
    if (steady_check) {
      if (!previous_ux.empty()) {
        double umax = 0.0;
        for (std::size_t n = 0; n < m.ux.size(); ++n) umax = std::max(umax, std::hypot(m.ux[n], m.uy[n]));
        const double change = std::max(max_abs_difference(m.ux, previous_ux), max_abs_difference(m.uy, previous_uy));
        if (umax > 0.0 && change / umax < steady->tolerance) {
          summary.status = RunStatus::steady_state;
          if (!fields) observer.on_fields(step, m);
          if (!diagnostics) observer.on_diagnostics(diagnose(step, m));
          return false;
        }
      }
      previous_ux = m.ux;
      previous_uy = m.uy;
    }
    return true;
  };

  long step = 0;
  bool keep_going = observe(0, total == 0);
  while (keep_going && step < total) {
    apply_body_force(step);
    fluid_->step();
    ++step;
    const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
    mlups = elapsed > 0.0 ? nodes * static_cast<double>(step) / elapsed * 1e-6 : 0.0;
    observer.on_progress(step, total, mlups);
    keep_going = observe(step, step == total);
  }
  summary.steps = step;
  summary.wall_time_s = std::chrono::duration<double>(clock::now() - start).count();
  summary.mlups = mlups;
  observer.on_finish(summary);
  return summary;
}

}  // namespace erythro::sim
