#include "fluid/initial_state.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "lattice/d2q9.hpp"

namespace erythro::fluid {

FlowField::FlowField(std::size_t n) { resize(n, false); }

void FlowField::resize(std::size_t n, bool with_gradients) {
  rho.assign(n, 1.0);
  ux.assign(n, 0.0);
  uy.assign(n, 0.0);
  const std::size_t m = with_gradients ? n : 0;
  dux_dx.assign(m, 0.0);
  dux_dy.assign(m, 0.0);
  duy_dx.assign(m, 0.0);
  duy_dy.assign(m, 0.0);
}

void FlowField::drop_gradients() {
  dux_dx.clear();
  dux_dy.clear();
  duy_dx.clear();
  duy_dy.clear();
}

void initialize_post_collision(FluidLattice& lattice, const FlowField& field, std::span<const double> fx,
                               std::span<const double> fy) {
  using namespace d2q9;
  const std::size_t N = lattice.grid().size();
  if (field.rho.size() != N || field.ux.size() != N || field.uy.size() != N)
    throw std::invalid_argument("initialize_post_collision: field size does not match the grid");
  const bool gradients = field.has_gradients();
  const bool force = !fx.empty();
  if ((gradients && field.dux_dx.size() != N) || (force && (fx.size() != N || fy.size() != N)))
    throw std::invalid_argument("initialize_post_collision: gradient or force size does not match the grid");
  const std::span<const double> tau_field = static_cast<const FluidLattice&>(lattice).tau_field();
  std::vector<double> f(Q * N);
  for (std::size_t n = 0; n < N; ++n) {
    const double rho = field.rho[n];
    const double tau = tau_field.empty() ? lattice.collision().tau : tau_field[n];
    for (int i = 0; i < Q; ++i) {
      double value = equilibrium_deviation(i, rho, field.ux[n], field.uy[n]);
      if (gradients) {
        // Q_i:∇u = Σ_ab (c_a c_b − c_s² δ_ab) ∂_a u_b
        const double q_grad = cx[i] * cx[i] * field.dux_dx[n] + cx[i] * cy[i] * (field.dux_dy[n] + field.duy_dx[n]) +
                              cy[i] * cy[i] * field.duy_dy[n] - cs2 * (field.dux_dx[n] + field.duy_dy[n]);
        value -= (tau - 1.0) * inv_cs2 * w[i] * rho * q_grad;
      }
      if (force) value += 0.5 * inv_cs2 * w[i] * (cx[i] * fx[n] + cy[i] * fy[n]);
      f[i * N + n] = value;
    }
  }
  lattice.set_populations(f);
}

FlowField uniform_flow(const Grid& g, std::array<double, 2> u0, bool gradients) {
  FlowField f;
  f.resize(g.size(), gradients);
  f.ux.assign(g.size(), u0[0]);
  f.uy.assign(g.size(), u0[1]);
  return f;
}

FlowField shear_flow(const Grid& g, const BoundaryConfig& walls, bool gradients) {
  FlowField f;
  f.resize(g.size(), gradients);
  const double ub = walls.bottom.ux, ut = walls.top.ux;
  for (int y = 0; y < g.ny; ++y) {
    const double s = (y + 0.5) / g.ny;
    for (int x = 0; x < g.nx; ++x) {
      const std::size_t n = g.index(x, y);
      f.ux[n] = ub + (ut - ub) * s;
      if (gradients) f.dux_dy[n] = (ut - ub) / g.ny;
    }
  }
  return f;
}

FlowField taylor_green_flow(const Grid& g, double U, bool gradients) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  FlowField f;
  f.resize(g.size(), gradients);
  const double kx = two_pi / g.nx, ky = two_pi / g.ny, r = kx / ky;
  for (int y = 0; y < g.ny; ++y) {
    for (int x = 0; x < g.nx; ++x) {
      const std::size_t n = g.index(x, y);
      const double px = x + 0.5, py = y + 0.5;
      const double cx = std::cos(kx * px), sx = std::sin(kx * px), cy = std::cos(ky * py), sy = std::sin(ky * py);
      f.ux[n] = -U * cx * sy;
      f.uy[n] = U * r * sx * cy;
      const double p = -0.25 * U * U * (std::cos(2 * kx * px) + r * r * std::cos(2 * ky * py));
      f.rho[n] = 1.0 + p * d2q9::inv_cs2;
      if (!gradients) continue;
      f.dux_dx[n] = U * kx * sx * sy;
      f.dux_dy[n] = -U * ky * cx * cy;
      f.duy_dx[n] = U * r * kx * cx * cy;
      f.duy_dy[n] = -U * kx * sx * sy;  // −U r k_y sin sin, r k_y = k_x
    }
  }
  return f;
}

FlowField double_shear_layer_flow(const Grid& g, double U, bool gradients) {
  FlowField f;
  f.resize(g.size(), gradients);
  const double Lx = g.nx, Ly = g.ny, delta = Ly / 30.0, eps = 0.05;
  const double k = 2.0 * std::numbers::pi / Lx;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = i + 0.5, y = j + 0.5;
      const std::size_t n = g.index(i, j);
      const bool lower = y <= 0.5 * Ly;
      const double t = lower ? std::tanh((y - 0.25 * Ly) / delta) : std::tanh((0.75 * Ly - y) / delta);
      f.ux[n] = U * t;
      f.uy[n] = eps * U * std::sin(2.0 * std::numbers::pi * (x / Lx + 0.25));
      if (!gradients) continue;
      f.dux_dy[n] = (lower ? U : -U) * (1.0 - t * t) / delta;
      f.duy_dx[n] = eps * U * k * std::cos(2.0 * std::numbers::pi * (x / Lx + 0.25));
    }
  }
  return f;
}

}  // namespace erythro::fluid
