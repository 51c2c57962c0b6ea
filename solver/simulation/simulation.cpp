#include "simulation/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

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
  // Only the modules the scene declares are built; a fluid-only scene has nothing else,
  // a still-medium transport scene has no fluid.
  if (setup_.has_fluid) {
    fluid_ = std::make_unique<fluid::FluidLattice>(setup_.grid, setup_.collision, setup_.boundaries);
    apply_initial_condition();
    apply_body_force(0);
    if (setup_.membrane)  // cells start at their stress-free rest shape
      cells_ = std::make_unique<CellPhysics>(*setup_.membrane, setup_.viscosity, *fluid_);
  } else if (setup_.membrane) {
    for (const scene::CellSetup& c : setup_.membrane->cells) fixed_cells_.push_back(c.shape);
  }
  if (setup_.transport) {
    std::vector<geometry::Polygon> shapes = fixed_cells_;
    if (cells_)
      for (int c = 0; c < cells_->cells().cell_count(); ++c) shapes.push_back(cells_->cells().polygon(c));
    transport_ = std::make_unique<TransportPhysics>(*setup_.transport,
                                                    fluid::domain_of(setup_.grid, setup_.boundaries), shapes);
  }
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

double taylor_deformation(const geometry::Polygon& p) {
  double cx = 0.0, cy = 0.0;
  geometry::centroid(p, cx, cy);
  // Second area moments about the centroid (Green's theorem over the polygon edges):
  //   ∫x² = (1/12) Σ c (x_i² + x_i x_j + x_j²), ∫y² likewise,
  //   ∫xy = (1/24) Σ c (x_i y_j + 2 x_i y_i + 2 x_j y_j + x_j y_i),  c = x_i y_j − x_j y_i.
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double xi = p.x[i] - cx, yi = p.y[i] - cy, xj = p.x[j] - cx, yj = p.y[j] - cy;
    const double c = xi * yj - xj * yi;
    sxx += c * (xi * xi + xi * xj + xj * xj);
    syy += c * (yi * yi + yi * yj + yj * yj);
    sxy += c * (xi * yj + 2.0 * xi * yi + 2.0 * xj * yj + xj * yi);
  }
  sxx /= 12.0;
  syy /= 12.0;
  sxy /= 24.0;
  // Eigenvalues of [[sxx, sxy], [sxy, syy]]; for an ellipse ∫x'² = π a³ b / 4, so a/b = √(λ1/λ2).
  const double mean = 0.5 * (sxx + syy), half = std::hypot(0.5 * (sxx - syy), sxy);
  const double l1 = mean + half, l2 = mean - half;
  if (!(l2 > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  const double ratio = std::sqrt(l1 / l2);  // L / B
  return (ratio - 1.0) / (ratio + 1.0);
}

namespace {
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
  describe_where(out, step, r, setup);
  out << (std::isnan(r.limit) ? " is not finite" : " is outside its limit " + std::to_string(r.limit))
      << ". Lower transport.time_step_s or the diffusivity (docs/transport.md).";
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

  // Transport diagnostics and fields (scenes with [transport]).
  auto transport_sample = [&](long step) {
    if (!transport_) return;
    TransportDiagnostics d;
    d.step = step;
    for (std::size_t i = 0; i < transport_->species_count(); ++i) {
      const auto& lat = transport_->lattice(i);
      d.mean_concentration.push_back(lat.total_amount() / nodes);
      d.residual.push_back(step == 0 ? 0.0 : lat.mass_balance().relative_residual());
    }
    d.saturation.assign(transport_->saturation().begin(), transport_->saturation().end());
    observer.on_transport_diagnostics(d);
  };
  auto transport_fields = [&](long step) {
    if (!transport_) return;
    TransportFields f;
    for (std::size_t i = 0; i < transport_->species_count(); ++i) {
      f.names.push_back(transport_->name(i));
      f.concentration.push_back(transport_->lattice(i).concentration());
    }
    observer.on_transport_fields(step, f);
  };

  // Fluid diagnostics plus, with cells, each cell's area change and Taylor deformation.
  auto sample = [&](long step, const fluid::Moments& m) {
    observer.on_diagnostics(diagnose(step, m));
    transport_sample(step);
    if (!cells_) return;
    CellDiagnostics d;
    d.step = step;
    const membrane::ImmersedCells& cells = cells_->cells();
    for (int c = 0; c < cells.cell_count(); ++c) {
      const geometry::Polygon p = cells.polygon(c);
      d.area_change.push_back(geometry::signed_area(p) / cells.rest(c).area - 1.0);
      d.taylor_deformation.push_back(taylor_deformation(p));
    }
    observer.on_cell_diagnostics(d);
  };

  // Observes the state after `step` steps; returns false when the monitor stops the run.
  auto observe = [&](long step, bool final_state) -> bool {
    const bool fields = final_state || due(step, out.fields_interval_steps) || step == 0;
    const bool diagnostics = final_state || due(step, out.diagnostics_interval_steps) || step == 0;
    const bool monitor = due(step, monitor_every);
    const bool steady_check = steady && due(step, steady->check_interval_steps) && step > 0;
    if (!(fields || diagnostics || monitor || steady_check)) return true;

    if (transport_) {  // health first: nothing unhealthy is ever written
      const HealthReport th = transport_->check_health();
      if (!th.healthy) {
        summary.status = RunStatus::diverged;
        summary.diagnosis = describe_transport_divergence(step, th, setup_);
        return false;
      }
    }
    if (!fluid_) {  // still medium: the transport is all there is
      if (diagnostics) {
        DiagnosticsSample d;
        d.step = step;
        observer.on_diagnostics(d);
        transport_sample(step);
      }
      if (fields) transport_fields(step);
      return true;
    }

    fluid::Moments m = fluid_->moments();
    // Health first: nothing unhealthy is ever written.
    const HealthReport health = fluid::check_health(setup_.grid, m, scene_.monitor.max_mach);
    if (!health.healthy) {
      summary.status = RunStatus::diverged;
      summary.diagnosis = describe_divergence(step, health, setup_);
      return false;
    }
    if (diagnostics) sample(step, m);
    if (fields) observer.on_fields(step, m);
    if (fields && cells_) observer.on_cells(step, cells_->cells());
    if (fields) transport_fields(step);
    if (steady_check) {
      if (!previous_ux.empty()) {
        const double umax = health.max_speed;  // the health scan's max |u|, no second pass
        const double change = std::max(max_abs_difference(m.ux, previous_ux), max_abs_difference(m.uy, previous_uy));
        if (umax > 0.0 && change / umax < steady->tolerance) {
          summary.status = RunStatus::steady_state;
          if (!fields) observer.on_fields(step, m);
          if (!fields && cells_) observer.on_cells(step, cells_->cells());
          if (!fields) transport_fields(step);
          if (!diagnostics) sample(step, m);
          return false;
        }
      }
      // Last use of m: keep its velocity for the next check without copying it.
      previous_ux = std::move(m.ux);
      previous_uy = std::move(m.uy);
    }
    return true;
  };

  long step = 0;
  bool keep_going = observe(0, total == 0);
  const long transport_every = setup_.transport ? std::max(1L, setup_.transport->fluid_steps_per_step) : 0;
  std::vector<geometry::Polygon> moved;
  while (keep_going && step < total) {
    if (!fluid_) {  // still medium: one transport step per step
      transport_->step({}, {});
      ++step;
      const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
      mlups = elapsed > 0.0 ? nodes * static_cast<double>(step) / elapsed * 1e-6 : 0.0;
      observer.on_progress(step, total, mlups);
      keep_going = observe(step, step == total);
      continue;
    }
    apply_body_force(step);
    if (cells_) {
      // One immersed-boundary cycle per fluid step (immersed_cells.hpp): membrane forces,
      // spreading (the body force adds to the field), fluid step, marker advection.
      try {
        cells_->advance(*fluid_, step);
      } catch (const std::domain_error& e) {  // a marker velocity or position is not finite
        ++step;
        summary.status = RunStatus::diverged;
        summary.diagnosis = "diverged at step " + std::to_string(step) + ": membrane markers: " + e.what() +
                            "; lower the moduli or the time step (see erythro check's stability numbers)";
        break;
      } catch (const interior::FillLeakError& e) {  // a membrane tangled: its interior is no longer closed
        summary.status = RunStatus::diverged;
        summary.diagnosis = "diverged at step " + std::to_string(step) + ": interior index field: " + e.what() +
                            "; the membrane folded or crossed itself (lower the capillary number or refine)";
        break;
      }
    } else {
      fluid_->step();
    }
    if (transport_ && (step + 1) % transport_every == 0) {
      // Sub-cycling: one transport step of Δt_T = k Δt_F every k fluid steps, with the
      // velocity of the last fluid step and the cells where they are now.
      if (cells_) {
        moved.resize(static_cast<std::size_t>(cells_->cells().cell_count()));
        for (int c = 0; c < cells_->cells().cell_count(); ++c) moved[static_cast<std::size_t>(c)] = cells_->cells().polygon(c);
        transport_->place_cells(moved);
      }
      const fluid::Moments m = fluid_->moments();
      transport_->step(m.ux, m.uy);
    }
    ++step;
    const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
    mlups = elapsed > 0.0 ? nodes * static_cast<double>(step) / elapsed * 1e-6 : 0.0;
    observer.on_progress(step, total, mlups);
    keep_going = observe(step, step == total);
  }
  summary.steps = step;
  summary.wall_time_s = std::chrono::duration<double>(clock::now() - start).count();
  summary.mlups = mlups;
  if (cells_) {
    summary.index_field_time_s = cells_->index_field_seconds();
    summary.index_field_exposed_time_s = cells_->index_field_exposed_seconds();
  }
  observer.on_finish(summary);
  return summary;
}

}  // namespace erythro::sim
