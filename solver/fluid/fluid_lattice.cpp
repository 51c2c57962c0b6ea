#include "fluid/fluid_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fluid/stream_collide.hpp"
#include "lattice/d2q9.hpp"

namespace erythro::fluid {

FluidLattice::FluidLattice(Grid grid, CollisionConfig collision, BoundaryConfig boundaries)
    : grid_(grid), collision_(collision), boundaries_(boundaries) {
  if (grid_.nx < 1 || grid_.ny < 1) throw std::invalid_argument("FluidLattice: empty grid");
  if (!(collision_.tau > 0.5)) throw std::invalid_argument("FluidLattice: tau must exceed 1/2");
  if (auto why = boundaries_.inconsistency(); !why.empty()) throw std::invalid_argument("FluidLattice: " + why);
  f_.assign(d2q9::Q * grid_.size(), 0.0);
  f_next_.assign(d2q9::Q * grid_.size(), 0.0);
  initialize_uniform(1.0, 0.0, 0.0);
}

void FluidLattice::initialize(std::span<const double> rho, std::span<const double> ux,
                              std::span<const double> uy) {
  const std::size_t N = grid_.size();
  if (rho.size() != N || ux.size() != N || uy.size() != N) {
    throw std::invalid_argument("FluidLattice::initialize: field size does not match the grid");
  }
  for (std::size_t n = 0; n < N; ++n) {
    for (int i = 0; i < d2q9::Q; ++i) f_[i * N + n] = d2q9::equilibrium_deviation(i, rho[n], ux[n], uy[n]);
  }
}

void FluidLattice::initialize_uniform(double rho, double ux, double uy) {
  const std::size_t N = grid_.size();
  for (int i = 0; i < d2q9::Q; ++i) {
    const double feq = d2q9::equilibrium_deviation(i, rho, ux, uy);
    std::fill(f_.begin() + static_cast<std::ptrdiff_t>(i * N), f_.begin() + static_cast<std::ptrdiff_t>((i + 1) * N), feq);
  }
}

void FluidLattice::enable_force_field() {
  if (!force_x_.empty()) return;
  force_x_.assign(grid_.size(), 0.0);
  force_y_.assign(grid_.size(), 0.0);
}

void FluidLattice::enable_tau_field() {
  if (!tau_field_.empty()) return;
  tau_field_.assign(grid_.size(), collision_.tau);
}

void FluidLattice::step() {
  detail::KernelArgs args;
  args.grid = grid_;
  args.src = f_.data();
  args.dst = f_next_.data();
  args.collision = collision_;
  args.boundaries = boundaries_;
  args.tau_field = tau_field_.empty() ? nullptr : tau_field_.data();
  args.force_x = force_x_.empty() ? nullptr : force_x_.data();
  args.force_y = force_y_.empty() ? nullptr : force_y_.data();
  args.uniform_fx = uniform_force_[0];
  args.uniform_fy = uniform_force_[1];
  detail::stream_collide(args);
  applied_force_ = uniform_force_;
  f_.swap(f_next_);
  ++steps_done_;
}

void FluidLattice::compute_moments(std::span<double> rho, std::span<double> ux, std::span<double> uy) const {
  const std::size_t N = grid_.size();
  const double* f = f_.data();
  const bool field = has_force_field();
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
  for (int y = 0; y < grid_.ny; ++y) {
    for (int x = 0; x < grid_.nx; ++x) {
      const std::size_t n = grid_.index(x, y);
      double dr = 0.0, jx = 0.0, jy = 0.0;
      for (int i = 0; i < d2q9::Q; ++i) {
        const double fi = f[i * N + n];
        dr += fi;
        jx += d2q9::cx[i] * fi;
        jy += d2q9::cy[i] * fi;
      }
      double Fx = applied_force_[0], Fy = applied_force_[1];
      if (field) {
        Fx += force_x_[n];
        Fy += force_y_[n];
      }
      // Stored populations are post-collision: Σ c f* = ρu + F/2 (Guo forcing), so
      // the velocity of the last collision is ρu = Σ c f* − F/2.
      const double r = 1.0 + dr;
      rho[n] = r;
      ux[n] = (jx - 0.5 * Fx) / r;
      uy[n] = (jy - 0.5 * Fy) / r;
    }
  }
}

Moments FluidLattice::moments() const {
  Moments m;
  m.rho.resize(grid_.size());
  m.ux.resize(grid_.size());
  m.uy.resize(grid_.size());
  compute_moments(m.rho, m.ux, m.uy);
  return m;
}

double FluidLattice::total_mass() const {
  // Row sums, then a serial sum over rows: identical for any thread count.
  std::vector<double> row_sum(static_cast<std::size_t>(grid_.ny), 0.0);
  const std::size_t N = grid_.size();
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
  for (int y = 0; y < grid_.ny; ++y) {
    double s = 0.0;
    for (int i = 0; i < d2q9::Q; ++i) {
      const double* row = f_.data() + i * N + grid_.index(0, y);
      for (int x = 0; x < grid_.nx; ++x) s += row[x];
    }
    row_sum[static_cast<std::size_t>(y)] = s;
  }
  double deviation = 0.0;
  for (double s : row_sum) deviation += s;
  return static_cast<double>(N) + deviation;  // Σ f = N·Σw + Σ f̃
}

std::array<double, 2> FluidLattice::total_momentum() const {
  const Moments m = moments();
  double px = 0.0, py = 0.0;
  for (std::size_t n = 0; n < grid_.size(); ++n) {
    px += m.rho[n] * m.ux[n];
    py += m.rho[n] * m.uy[n];
  }
  return {px, py};
}

HealthReport check_health(const Grid& grid, const Moments& m, double max_mach) {
  const double max_speed = max_mach * std::sqrt(d2q9::cs2);
  HealthReport report;
  for (int y = 0; y < grid.ny && report.healthy; ++y) {
    for (int x = 0; x < grid.nx; ++x) {
      const std::size_t n = grid.index(x, y);
      auto fail = [&](const char* quantity, double value, double limit) {
        report.healthy = false;
        report.quantity = quantity;
        report.node_x = x;
        report.node_y = y;
        report.value = value;
        report.limit = limit;
      };
      const double nan = std::numeric_limits<double>::quiet_NaN();
      if (!std::isfinite(m.rho[n])) { fail("density", m.rho[n], nan); break; }
      if (!std::isfinite(m.ux[n])) { fail("velocity_x", m.ux[n], nan); break; }
      if (!std::isfinite(m.uy[n])) { fail("velocity_y", m.uy[n], nan); break; }
      if (!(m.rho[n] > 0.0)) { fail("density", m.rho[n], 0.0); break; }
      const double speed = std::hypot(m.ux[n], m.uy[n]);
      if (speed > max_speed) { fail("mach", speed / std::sqrt(d2q9::cs2), max_mach); break; }
      report.max_speed = std::max(report.max_speed, speed);
    }
  }
  return report;
}

}  // namespace erythro::fluid
