#include "capsule_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fluid/fluid_lattice.hpp"
#include "geometry/shapes.hpp"
#include "membrane/immersed_cells.hpp"

namespace erythro::vv {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

fluid::FluidLattice make_shear_lattice(int nx, int ny, double gamma, double tau) {
  const double U = 0.5 * gamma * ny;
  fluid::BoundaryConfig bc;
  bc.bottom = {fluid::SideType::moving_wall, -U, 0.0};
  bc.top = {fluid::SideType::moving_wall, U, 0.0};
  fluid::FluidLattice lat(Grid{nx, ny}, fluid::CollisionConfig{fluid::CollisionModel::bgk, tau, 3.0 / 16.0}, bc);
  const std::size_t N = static_cast<std::size_t>(nx) * ny;
  std::vector<double> rho(N, 1.0), ux(N, 0.0), uy(N, 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) ux[static_cast<std::size_t>(j) * nx + i] = gamma * (j + 0.5 - 0.5 * ny);
  lat.initialize(rho, ux, uy);
  return lat;
}

CapsuleResult run_capsule(const CapsuleConfig& c) {
  using namespace membrane;
  using namespace geometry;
  const auto t_start = Clock::now();
  const int nx = static_cast<int>(std::lround(c.length * c.radius));
  const int ny = static_cast<int>(std::lround(c.height * c.radius));
  const double nu = (c.tau - 0.5) / 3.0;
  const double gamma = c.reynolds * nu / (c.radius * c.radius);  // Re = γ̇a²/ν
  fluid::FluidLattice lat = make_shear_lattice(nx, ny, gamma, c.tau);

  CapsuleResult r;
  r.shear_rate = gamma;
  r.modulus = nu * gamma * c.radius / c.capillary;  // G = μγ̇a/E_s, μ = ρ0ν = ν
  const int n = static_cast<int>(std::lround(c.markers_per_radius * c.radius));
  r.markers = n;
  ImmersedCells cells(c.kernel, lat);
  // Centre mid-channel, slightly off the lattice symmetry in x; marker 0 off the axes.
  const double xc0 = 0.5 * nx + 0.123, yc0 = 0.5 * ny;
  const Polygon shape = transformed(circle(n, c.radius), 1.0, 0.01, xc0, yc0);
  RestShape rest = RestShape::from_polygon(shape);  // stress-free: no prestress
  const MembraneModel model{{TensionLawType::neo_hookean, r.modulus}, 0.0, 0.0};
  cells.add_cell(shape, rest, model);
  const double A0 = signed_area(shape);
  // The IB cycle of ImmersedCells::advance, called piece by piece so each part can be
  // timed; zeroing the force field (grid work) and spreading (marker work) are timed
  // apart, as spread_forces() = zero + add_spread_forces().
  lat.enable_force_field();

  const double steps_per_strain = 1.0 / gamma;
  const long sample_every = std::max(1L, std::lround(0.1 * steps_per_strain));
  const long max_steps = std::lround(c.max_strain * steps_per_strain);
  // Unwrapped angle of every marker about the centroid (tank-treading), per sample.
  std::vector<double> phase(static_cast<std::size_t>(n), 0.0), last_angle(static_cast<std::size_t>(n), 0.0);
  std::vector<std::vector<double>> phase_history;
  for (long s = 1; s <= max_steps; ++s) {
    auto t0 = Clock::now();
    cells.compute_forces();
    r.t_forces += since(t0);
    t0 = Clock::now();
    std::fill(lat.force_x().begin(), lat.force_x().end(), 0.0);
    std::fill(lat.force_y().begin(), lat.force_y().end(), 0.0);
    r.t_zero += since(t0);
    t0 = Clock::now();
    cells.add_spread_forces(lat);
    r.t_spread += since(t0);
    t0 = Clock::now();
    lat.step();
    r.t_fluid += since(t0);
    t0 = Clock::now();
    cells.support_velocity(lat);
    r.t_moments += since(t0);
    t0 = Clock::now();
    try {
      cells.move_markers(cells.support_ux(), cells.support_uy());
    } catch (const std::domain_error&) {
      r.diverged = true;
      break;
    }
    cells.wrap_periodic();
    r.t_move += since(t0);
    r.steps = s;
    if (s % sample_every != 0) continue;
    const Polygon p = cells.polygon(0);
    double D, th;
    taylor_deformation(p, D, th);
    double cx, cy;
    centroid(p, cx, cy);
    for (std::size_t m = 0; m < p.size(); ++m) {
      const double ang = std::atan2(p.y[m] - cy, p.x[m] - cx);
      double d = phase_history.empty() ? 0.0 : ang - last_angle[m];
      d -= 2.0 * std::numbers::pi * std::round(d / (2.0 * std::numbers::pi));
      phase[m] += d;
      last_angle[m] = ang;
    }
    if (!std::isfinite(D) || std::abs(signed_area(p) / A0 - 1.0) > 0.2) { r.diverged = true; break; }
    const double strain = static_cast<double>(s) * gamma;
    r.strain_history.push_back(strain);
    r.D_history.push_back(D);
    r.theta_history.push_back(th);
    phase_history.push_back(phase);
    const std::size_t k = r.D_history.size();
    if (k > 10) {
      r.drift = std::abs(D - r.D_history[k - 11]);  // 10 samples = 1 strain unit
      if (strain >= c.min_strain && r.drift < c.steady_drift) break;
    }
  }
  r.wall_time_s = since(t_start);
  if (r.diverged || r.D_history.size() < 12) { r.diverged = true; return r; }
  const std::size_t k = r.D_history.size();
  r.strain = r.strain_history.back();
  // Steady values: means over the last strain unit (10 samples) smooth the marker jitter.
  r.D = 0;
  r.theta_deg = 0;
  for (std::size_t i = k - 10; i < k; ++i) { r.D += r.D_history[i] / 10.0; r.theta_deg += r.theta_history[i] / 10.0; }
  // Tank-treading period T: in steady tank-treading a marker at angle φ moves at
  // ω(φ) and the markers (equally spaced in the Lagrangian label) have density
  // ∝ 1/ω(φ), so the mean of ω over all markers is 2π / ∮dφ/ω = 2π/T exactly.
  // Mean over markers and over the last strain unit:
  double rate = 0;
  for (std::size_t m = 0; m < phase.size(); ++m) rate += phase_history[k - 1][m] - phase_history[k - 11][m];
  rate /= static_cast<double>(phase.size()) * (r.strain_history[k - 1] - r.strain_history[k - 11]);
  r.tt_period = 2.0 * std::numbers::pi / std::abs(rate);  // in units of 1/γ̇
  const Polygon p = cells.polygon(0);
  r.area_change = signed_area(p) / A0 - 1.0;
  double cx, cy;
  centroid(p, cx, cy);
  r.centre_drift = std::abs(cy - yc0) / c.radius;
  return r;
}

}  // namespace erythro::vv
