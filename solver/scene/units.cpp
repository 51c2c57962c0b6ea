// Physical scene → lattice units (h = Δt = 1, ρ0 = 1), plus the checks that need
// several values at once. Formulas (docs/scenes.md "Unit conversion"):
//   n = L / h                               nodes per direction (must be a whole number)
//   ν = μ / ρ                               physical kinematic viscosity [m²/s]
//   ν_lat = c_s² (τ − ½) = (τ − ½) / 3      (docs/model.md eq 1.6)
//   Δt = (τ − ½) h² / (3ν)   ⇔   τ = ½ + 3 ν Δt / h²
//   u_lat = u Δt / h,   F_lat = F Δt² / (ρ h),   f_lat = f Δt
#include "scene/units.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "common/error.hpp"
#include "lattice/d2q9.hpp"
#include "scene/units_detail.hpp"

namespace erythro::scene {
namespace {

using namespace detail;  // num, vec, reject, wall_bounded, derive_membrane

const double cs = std::sqrt(d2q9::cs2);

// n = L/h per axis; rejects a size that is not a whole number of spacings.
Grid make_grid(const Scene& s) {
  const auto& L = s.domain.size_um;
  const double h = s.domain.spacing_um;
  if (!(h > 0.0) || !(L[0] > 0.0) || !(L[1] > 0.0))
    reject(s, "domain.size_um = " + vec(L) + " and domain.spacing_um = " + num(h) + " must all be > 0 (µm)");
  std::array<double, 2> n{};
  bool whole = true;
  for (int a = 0; a < 2; ++a) {
    const double ratio = L[a] / h;
    n[a] = std::max(1.0, std::round(ratio));
    whole = whole && std::abs(ratio - n[a]) <= 1e-6 * n[a];
  }
  // The size first: a grid too large to run needs no advice on its spacing.
  if (n[0] * n[1] > 2e9)
    reject(s, "domain.size_um = " + vec(L) + " µm at domain.spacing_um = " + num(h) + " µm has " +
                  num(n[0] * n[1]) + " nodes; at most 2e9 are supported");
  if (!whole) {
    // The spacing closest to h that divides both sizes (h' = Lx/Nx with Ly/h' whole).
    double best = 0.0;
    for (double nx = 1.0; nx <= 2.0 * n[0] + 1.0 && nx <= 1e6; nx += 1.0) {
      const double hc = L[0] / nx, ny = L[1] / hc;
      if (std::abs(ny - std::round(ny)) <= 1e-6 * ny && std::abs(hc - h) < std::abs(best - h)) best = hc;
    }
    char spacing[32];  // enough digits that the suggestion passes the 1e-6 test when copied
    std::snprintf(spacing, sizeof(spacing), "%.10g", best);
    reject(s, "domain.size_um = " + vec(L) + " µm is not a whole number of domain.spacing_um = " + num(h) +
                  " µm (size/spacing = " + vec({L[0] / h, L[1] / h}) + " nodes): " +
                  (best > 0.0 ? "nearest valid spacing is " + std::string(spacing) + " µm, or " : "") +
                  "set domain.size_um = " + vec({n[0] * h, n[1] * h}));
  }
  return Grid{static_cast<int>(n[0]), static_cast<int>(n[1])};
}

fluid::Side make_side(const Scene& s, const SideSpec& spec, const char* name, double velocity_scale) {
  fluid::Side side;
  if (!fluid::parse_side_type(spec.type, side.type))
    reject(s, std::string("boundaries.") + name + ".type = \"" + spec.type +
                  "\" is not one of \"periodic\", \"wall\", \"moving_wall\"");
  if (side.type == fluid::SideType::moving_wall) {
    side.ux = spec.velocity_um_s[0] * velocity_scale;
    side.uy = spec.velocity_um_s[1] * velocity_scale;
  }
  return side;
}

// One candidate for the largest speed in the run, in lattice units.
struct SpeedSource {
  double speed = 0.0;
  std::string key;       // the scene key that sets it
  std::string shown;     // its value, as written
  bool estimate = false; // force in a periodic direction: no steady state, bounded guess
};

// |u_w| of each moving wall, max |u| of the initial state, and for a body force the
// Poiseuille centre speed F H²/(8ν) across the channel (H in nodes), also bounded by
// F·steps (free acceleration from rest) and, for an oscillating force, F/(2π f).
std::vector<SpeedSource> speed_sources(const Scene& s, const LatticeSetup& L) {
  std::vector<SpeedSource> out;
  const std::pair<const char*, const fluid::Side*> sides[] = {
      {"left", &L.boundaries.left}, {"right", &L.boundaries.right},
      {"bottom", &L.boundaries.bottom}, {"top", &L.boundaries.top}};
  const std::pair<const char*, const SideSpec*> specs[] = {
      {"left", &s.boundaries.left}, {"right", &s.boundaries.right},
      {"bottom", &s.boundaries.bottom}, {"top", &s.boundaries.top}};
  for (int i = 0; i < 4; ++i) {
    if (sides[i].second->type != fluid::SideType::moving_wall) continue;
    out.push_back({std::hypot(sides[i].second->ux, sides[i].second->uy),
                   std::string("boundaries.") + sides[i].first + ".velocity_um_s",
                   vec(specs[i].second->velocity_um_s) + " µm/s", false});
  }
  if (s.initial.type == "uniform")
    out.push_back({std::hypot(L.initial_velocity[0], L.initial_velocity[1]), "initial.velocity_um_s",
                   vec(s.initial.velocity_um_s) + " µm/s", false});
  if (s.initial.type == "taylor_green") {  // u = −U cos sin, v = U (kx/ky) sin cos: max U·max(1, kx/ky)
    const double ratio = static_cast<double>(L.grid.ny) / L.grid.nx;  // kx/ky = ny/nx
    out.push_back({std::abs(L.initial_velocity[0]) * std::max(1.0, ratio), "initial.velocity_um_s",
                   vec(s.initial.velocity_um_s) + " µm/s", false});
  }
  if (s.initial.type == "double_shear_layer")  // |u| <= U, |v| <= 0.05 U
    out.push_back({std::abs(L.initial_velocity[0]) * std::hypot(1.0, 0.05), "initial.velocity_um_s",
                   vec(s.initial.velocity_um_s) + " µm/s", false});
  if (s.body_force) {
    std::array<double, 2> u{};
    bool estimate = false;
    for (int a = 0; a < 2; ++a) {
      const double F = std::abs(L.body_force[a]);
      const int across = 1 - a;  // flow along a is sheared across the other axis
      const double H = across == 0 ? L.grid.nx : L.grid.ny;
      u[a] = std::min(F * H * H / (8.0 * L.viscosity), F * static_cast<double>(L.total_steps));
      if (L.force_frequency > 0.0) u[a] = std::min(u[a], F / (2.0 * std::numbers::pi * L.force_frequency));
      estimate = estimate || (F > 0.0 && !wall_bounded(s, across));
    }
    out.push_back({std::hypot(u[0], u[1]), "body_force.density_N_m3", vec(s.body_force->density_N_m3) + " N/m³",
                   estimate});
  }
  return out;
}

SpeedSource fastest(const std::vector<SpeedSource>& sources) {
  SpeedSource best;
  for (const SpeedSource& src : sources)
    if (src.speed > best.speed) best = src;
  return best;
}


// The four sides in lattice units (moving-wall velocities × u_scale), checked for consistency.
fluid::BoundaryConfig make_boundaries(const Scene& s, double u_scale) {
  fluid::BoundaryConfig b;
  b.left = make_side(s, s.boundaries.left, "left", u_scale);
  b.right = make_side(s, s.boundaries.right, "right", u_scale);
  b.bottom = make_side(s, s.boundaries.bottom, "bottom", u_scale);
  b.top = make_side(s, s.boundaries.top, "top", u_scale);
  if (const std::string why = b.inconsistency(); !why.empty()) reject(s, "boundaries: " + why);
  return b;
}

// The run's length in steps of `dt`: run.steps, or ⌈duration / Δt⌉ (a ratio within
// 1e-9 of a whole number is that number). `dt_source` names the keys Δt follows from, for
// a duration too long: the step may be the one that is off (e.g. a huge viscosity at a given τ).
long run_steps(const Scene& s, double dt, const std::string& dt_source) {
  if (s.run.steps.has_value() == s.run.duration_s.has_value())
    reject(s, "give exactly one of run.steps or run.duration_s");
  long steps = 0;
  if (s.run.steps) {
    steps = *s.run.steps;
  } else {
    const double x = *s.run.duration_s / dt;
    if (!(x <= 1e12))
      reject(s, "run.duration_s = " + num(*s.run.duration_s) + " s is " + num(x) + " steps of Δt = " + num(dt) +
                    " s (from " + dt_source + "); at most 1e12 steps are supported: shorten the run or enlarge Δt");
    const double r = std::round(x);
    steps = std::max(1L, static_cast<long>(std::abs(x - r) <= 1e-9 * x ? r : std::ceil(x)));
  }
  if (steps < 1) reject(s, "run.steps = " + std::to_string(steps) + " must be >= 1");
  return steps;
}

// transport.coupling = "none": a still medium. No fluid is built: the run's clock is
// the transport step, cells are fixed shapes, and every flow key is refused rather
// than silently ignored.
LatticeSetup derive_still_medium(const Scene& s) {
  LatticeSetup L;
  L.grid = make_grid(s);
  L.has_fluid = false;
  if (!s.transport->time_step_s)
    reject(s, "transport.coupling = \"none\" needs transport.time_step_s (s): with no flow the transport's step is "
              "the run's clock (e.g. 1e-5 s at h = 0.2 µm, thesis ch. V)");
  if (s.time.tau || s.time.step_s)
    reject(s, "[time] sets the fluid's step, but transport.coupling = \"none\" builds no fluid: remove [time] "
              "(the clock is transport.time_step_s)");
  if (s.body_force) reject(s, "[body_force] needs a fluid, but transport.coupling = \"none\" builds none");
  if (s.run.steady_state)
    reject(s, "[run.steady_state] watches the fluid, but transport.coupling = \"none\" builds none: give run.steps or "
              "run.duration_s");
  if (s.initial.type != "rest")
    reject(s, "initial.type = \"" + s.initial.type + "\" needs a fluid, but transport.coupling = \"none\" builds none");
  if (s.membrane && s.membrane->interior_viscosity_cP)
    reject(s, "membrane.interior_viscosity_cP needs a fluid, but transport.coupling = \"none\" builds none");
  if (!s.fluid.layers.empty()) derive_layers(s, L);  // rejects: no fluid
  if (s.initial.non_equilibrium)
    reject(s, "initial.non_equilibrium = true needs a fluid, but transport.coupling = \"none\" builds none");
  const double h = s.domain.spacing_um * 1e-6;
  const double dt = *s.transport->time_step_s;
  L.scales = UnitScales{h, dt, s.fluid.density_kg_m3};
  for (const auto& [side, name] : {std::pair{&s.boundaries.left, "left"}, std::pair{&s.boundaries.right, "right"},
                                   std::pair{&s.boundaries.bottom, "bottom"}, std::pair{&s.boundaries.top, "top"}}) {
    if (side->type == "moving_wall")
      reject(s, std::string("boundaries.") + name + ".type = \"moving_wall\" needs a fluid, but transport.coupling = "
                "\"none\" builds none (use \"wall\")");
  }
  L.boundaries = make_boundaries(s, 0.0);
  L.total_steps = run_steps(s, dt, "transport.time_step_s");
  if (!s.cells.empty()) L.membrane = derive_membrane(s, L, /*mechanics=*/false);
  L.transport = derive_transport(s, L);
  return L;
}

}  // namespace

// domain.geometry (docs/model.md §7b): an axisymmetric domain is a transport-only set-up (the
// fluid and the cells are planar), radial between two walls.
void check_geometry(const Scene& s) {
  const DomainSpec& d = s.domain;
  if (d.geometry != "axisymmetric") {
    if (d.inner_radius_um != 0.0)
      reject(s, "domain.inner_radius_um = " + num(d.inner_radius_um) + " µm needs domain.geometry = \"axisymmetric\"");
    return;
  }
  const std::string what = "domain.geometry = \"axisymmetric\" ";
  if (!s.transport || s.transport->coupling != "none")
    reject(s, what + "is for the transport alone (the fluid and the cells are planar): it needs [transport] with "
                     "transport.coupling = \"none\"");
  // A cell is a body of revolution about the axis: its section must be centred on the axis and
  // symmetric about it (every shape is symmetric about its own two axes: a multiple of 90°).
  if (!s.cell_populations.empty())
    reject(s, what + "places cells on the axis only: [[cell_populations]] (random centres) cannot be used");
  for (std::size_t c = 0; c < s.cells.size(); ++c) {
    const CellSpec& cell = s.cells[c];
    const std::string key = "cells[" + std::to_string(c) + "].";
    if (d.inner_radius_um != 0.0)
      reject(s, what + "with domain.inner_radius_um = " + num(d.inner_radius_um) +
                    " µm has no axis for a cell to sit on: a cell needs domain.inner_radius_um = 0");
    if (cell.center_um[1] != 0.0)
      reject(s, "key '" + key + "center_um' = [" + num(cell.center_um[0]) + ", " + num(cell.center_um[1]) +
                    "]: with domain.geometry = \"axisymmetric\" a cell is a body of revolution about the axis, so its "
                    "centre's radius (second component) must be 0");
    const double quarter_turns = cell.angle_deg / 90.0;
    if (quarter_turns != std::round(quarter_turns))
      reject(s, "key '" + key + "angle_deg' = " + num(cell.angle_deg) +
                    ": with domain.geometry = \"axisymmetric\" the cell's section must be symmetric about the axis: a "
                    "multiple of 90 (90: a biconcave cell's axis of symmetry along the domain's axis)");
  }
  if (s.boundaries.bottom.type == "periodic" || s.boundaries.top.type == "periodic")
    reject(s, what + "is radial along y: boundaries.bottom (the axis or the inner radius) and boundaries.top (the "
                     "outer radius) must be walls, not periodic");
}

LatticeSetup derive_lattice(const Scene& s) {
  check_geometry(s);
  if (s.transport && s.transport->coupling == "none") return derive_still_medium(s);
  LatticeSetup L;
  L.grid = make_grid(s);

  // --- time step and relaxation time: Δt = (τ − ½) h² / (3ν)  ⇔  τ = ½ + 3νΔt/h²
  const double h = s.domain.spacing_um * 1e-6;                       // [m]
  // The fluid's density: fluid.density_kg_m3, or raised by [time_mapping] (eq 10.8).
  L.time_mapping = derive_time_mapping(s);
  const double rho = run_density_kg_m3(s, L.time_mapping);
  const std::string rho_source = L.time_mapping ? "the density of [time_mapping]" : "fluid.density_kg_m3";
  const double nu = s.fluid.viscosity_cP * 1e-3 / rho;  // [m²/s]
  if (!(nu > 0.0) || !std::isfinite(nu))
    reject(s, "fluid.viscosity_cP = " + num(s.fluid.viscosity_cP) + " and " + rho_source + " = " + num(rho) +
                  " must be > 0");
  if (s.time.tau.has_value() == s.time.step_s.has_value())
    reject(s, "give exactly one of time.step_s (s, > 0) or time.tau (> 0.5)");
  double tau = 0.0, dt = 0.0;
  if (s.time.tau) {
    tau = *s.time.tau;
    dt = (tau - 0.5) * h * h / (3.0 * nu);
  } else {
    dt = *s.time.step_s;
    tau = d2q9::tau_of_viscosity(nu * dt / (h * h));
  }
  const double tau_min = 0.5 + s.limits.min_tau_margin;
  if (!(tau >= tau_min && tau > 0.5)) {
    const std::string why = " (0.5 + limits.min_tau_margin; τ → ½ means vanishing lattice viscosity, unstable)";
    if (s.time.tau)
      reject(s, "key 'time.tau' = " + num(tau) + " is out of range: must be >= " + num(tau_min) + why);
    const double dt_min = (tau_min - 0.5) * h * h / (3.0 * nu);
    reject(s, "key 'time.step_s' = " + num(dt) + " s gives τ = " + num(tau) + ", below " + num(tau_min) + why +
                  ": time.step_s must be >= " + num(dt_min) + " s for this spacing and viscosity");
  }
  if (!(tau <= s.limits.max_tau)) {  // the same two messages at the other end
    const double tau_max = s.limits.max_tau;
    const std::string why = " (limits.max_tau; a large τ is a large Δt against the viscous time h²/ν, and the walls' "
                            "error grows as (τ − ½)²)";
    if (s.time.tau)
      reject(s, "key 'time.tau' = " + num(tau) + " is out of range: must be <= " + num(tau_max) + why);
    const double dt_max = (tau_max - 0.5) * h * h / (3.0 * nu);
    reject(s, "key 'time.step_s' = " + num(dt) + " s gives τ = " + num(tau) + ", above " + num(tau_max) + why +
                  ": time.step_s must be <= " + num(dt_max) + " s for this spacing and viscosity");
  }
  L.scales = UnitScales{h, dt, rho};
  L.viscosity = (tau - 0.5) * d2q9::cs2;

  // --- collision
  if (!fluid::parse_collision_model(s.fluid.collision, L.collision.model))
    reject(s, "fluid.collision = \"" + s.fluid.collision + "\" is not one of \"bgk\", \"trt\", \"regularized\"");
  if (!(s.fluid.trt_magic > 0.0)) reject(s, "fluid.trt_magic = " + num(s.fluid.trt_magic) + " must be > 0");
  L.collision.tau = tau;
  L.collision.trt_magic = s.fluid.trt_magic;
  check_trt_tau_minus(s, L, tau, s.time.tau ? "time.tau" : "τ from time.step_s");

  // --- boundaries: u_lat = u Δt / h
  const double u_scale = 1e-6 * dt / h;  // µm/s → lattice
  L.boundaries = make_boundaries(s, u_scale);

  const int min_nodes = s.limits.min_nodes_across_channel;
  for (int a = 0; a < 2; ++a) {
    const int n = a == 0 ? L.grid.nx : L.grid.ny;
    if (!wall_bounded(s, a) || n >= min_nodes) continue;
    reject(s, std::string("resolution too coarse: the channel between the ") +
                  (a == 0 ? "left and right" : "bottom and top") + " walls has " + std::to_string(n) +
                  " nodes across (domain.size_um[" + std::to_string(a) + "] / domain.spacing_um = " +
                  num(s.domain.size_um[a]) + " / " + num(s.domain.spacing_um) +
                  " µm), fewer than limits.min_nodes_across_channel = " + std::to_string(min_nodes) +
                  ": make domain.spacing_um <= " + num(s.domain.size_um[a] / min_nodes) + " µm");
  }

  // --- initial state
  if (s.initial.type != "rest" && s.initial.type != "uniform" && s.initial.type != "shear" &&
      s.initial.type != "taylor_green" && s.initial.type != "double_shear_layer")
    reject(s, "initial.type = \"" + s.initial.type +
                  "\" is not one of \"rest\", \"uniform\", \"shear\", \"taylor_green\", \"double_shear_layer\"");
  if (s.initial.type == "shear" && !wall_bounded(s, 1))
    reject(s, "initial.type = \"shear\" needs walls at bottom and top (the profile joins their velocities)");
  if ((s.initial.type == "taylor_green" || s.initial.type == "double_shear_layer") &&
      (wall_bounded(s, 0) || wall_bounded(s, 1)))
    reject(s, "initial.type = \"" + s.initial.type + "\" needs all four sides periodic");
  L.initial_velocity = {s.initial.velocity_um_s[0] * u_scale, s.initial.velocity_um_s[1] * u_scale};

  // --- body force: F_lat = F Δt² / (ρ h);  f_lat = f Δt (cycles per step)
  if (s.body_force) {
    const double f_scale = dt * dt / (rho * h);
    L.body_force = {s.body_force->density_N_m3[0] * f_scale, s.body_force->density_N_m3[1] * f_scale};
    L.force_frequency = s.body_force->frequency_Hz * dt;
    L.force_phase = s.body_force->phase_rad;
  }

  // --- run length in fluid steps
  // Where Δt comes from, for the messages about quantities it scales (steps, lattice speeds).
  const std::string dt_source = s.time.tau ? "time.tau, domain.spacing_um, fluid.viscosity_cP and " + rho_source +
                                                 ": Δt = (τ − ½) h²/(3ν)"
                                           : "time.step_s";
  L.total_steps = run_steps(s, dt, dt_source);

  // --- expected speed, Mach and Reynolds numbers
  const SpeedSource top = fastest(speed_sources(s, L));
  L.expected_max_speed = top.speed;
  L.speed_source = top.key;
  L.speed_is_estimate = top.estimate;
  L.mach = top.speed / cs;
  if (L.mach > s.limits.max_mach) {
    // Every speed source scales linearly with its own key, and (about) linearly with Δt.
    const double r = s.limits.max_mach / L.mach;
    const double tau_ok = 0.5 + (tau - 0.5) * r;  // τ giving Δt·r
    std::string smaller_dt;
    if (tau_ok >= tau_min)
      smaller_dt = ", or shrink the time step (" +
                   (s.time.tau ? "time.tau <= " + num(tau_ok) : "time.step_s <= " + num(dt * r) + " s") +
                   "; u_lattice = u Δt / h)";
    reject(s, "expected Mach number " + num(L.mach) + " exceeds limits.max_mach = " + num(s.limits.max_mach) +
                  ": the speed " + num(top.speed * L.scales.velocity_m_s() * 1e6) + " µm/s (" + num(top.speed) +
                  " lattice = u Δt/h, Δt = " + num(dt) + " s from " + dt_source + ") is set by " + top.key + " = " +
                  top.shown + (top.estimate ? " (estimate)" : "") +
                  "; lower it by a factor " + num(1.0 / r) + smaller_dt + ", or refine domain.spacing_um");
  }
  // Re = u L / ν, L = wall-to-wall distance (the narrower one if both axes have walls);
  // in a fully periodic box the shorter period.
  int length = std::min(L.grid.nx, L.grid.ny);
  if (wall_bounded(s, 0) != wall_bounded(s, 1)) length = wall_bounded(s, 0) ? L.grid.nx : L.grid.ny;
  L.reynolds = top.speed * length / L.viscosity;
  L.reynolds_length_m = length * h;
  if (!s.cells.empty()) L.membrane = derive_membrane(s, L);
  if (s.transport) L.transport = derive_transport(s, L);
  L.viscosity_layers = derive_layers(s, L);
  return L;
}

namespace {

// Pads to `width` display columns (UTF-8 aware: continuation bytes take no column).
std::string pad(const std::string& text, std::size_t width) {
  std::size_t cols = 0;
  for (unsigned char c : text) cols += (c & 0xC0) != 0x80;
  return text + std::string(cols < width ? width - cols : 1, ' ');
}

}  // namespace

namespace {
// The aggregation strength's rows of the report (docs/model.md eqs 4.7–4.8).
void append_aggregation_rows(const AggregationStrength& g, std::vector<std::array<std::string, 3>>& rows) {
  rows.push_back({"surface energy γ", "De* = " + num(g.de_star) + " (γ / 2.6e-8 J/m²)",
                  num(g.surface_energy_J_m2) + " J/m²"});
  rows.push_back({"peak adhesion stress γβ/2", "", num(g.peak_stress_Pa) + " Pa"});
  if (g.adhesion_to_viscous_stress)
    rows.push_back({"adhesion / viscous stress", num(*g.adhesion_to_viscous_stress),
                    "γβ/2 over μγ̇, γ̇ = " + num(*g.shear_rate_per_s) + " 1/s (walls)"});
}

// The transport's rows of the report, and the rows as an aligned table.
void append_transport_rows(const Scene& s, const LatticeSetup& L, std::vector<std::array<std::string, 3>>& rows);
std::string format_rows(const Scene& s, const LatticeSetup& L, const std::vector<std::array<std::string, 3>>& rows);
}  // namespace

std::optional<double> wall_shear_rate_per_s(const LatticeSetup& L) {
  using fluid::SideType;
  const fluid::BoundaryConfig& b = L.boundaries;
  const bool walls_in_y = b.bottom.type != SideType::periodic && b.top.type != SideType::periodic;
  const bool periodic_in_x = b.left.type == SideType::periodic && b.right.type == SideType::periodic;
  const bool no_force = L.body_force[0] == 0.0 && L.body_force[1] == 0.0;
  const double relative_speed = std::abs(b.top.ux - b.bottom.ux);  // lattice (a still wall has ux = 0)
  if (!walls_in_y || !periodic_in_x || !no_force || !(relative_speed > 0.0)) return std::nullopt;
  return relative_speed / L.grid.ny / L.scales.time_s;  // per step over n_y h, then per second
}

std::string format_lattice_report(const Scene& s, const LatticeSetup& L) {
  const UnitScales& u = L.scales;
  const double um = 1e6;
  const MembraneSpec spec = s.membrane.value_or(MembraneSpec{});
  std::vector<std::array<std::string, 3>> rows = {
      {"quantity", "lattice", "physical"},
      {"spacing h", "1", num(u.length_m * um) + " µm"},
      {"time step Δt", "1", num(u.time_s) + " s"},
      {"nodes", std::to_string(L.grid.nx) + " × " + std::to_string(L.grid.ny),
       vec(s.domain.size_um) + " µm"}};
  if (!L.has_fluid) {
    rows.push_back({"fluid", "none", "transport.coupling = \"none\": still medium"});
    rows.push_back({"steps", std::to_string(L.total_steps),
                    num(static_cast<double>(L.total_steps) * u.time_s) + " s simulated"});
    for (std::size_t i = 0; i < s.cells.size() && L.membrane; ++i)
      rows.push_back({"cell " + std::to_string(i) + " (" + s.cells[i].shape + ")",
                      std::to_string(L.membrane->cells[i].shape.size()) + " markers, fixed",
                      "R_eq = " + num(L.membrane->cells[i].equivalent_radius * u.length_m * um) + " µm"});
    append_transport_rows(s, L, rows);
    return format_rows(s, L, rows);
  }
  const std::vector<std::array<std::string, 3>> fluid_rows = {
      {"relaxation time τ (tau)", num(L.collision.tau), "limit >= " + num(0.5 + s.limits.min_tau_margin)},
      {"viscosity ν", num(L.viscosity),
       num(L.viscosity * u.kinematic_viscosity_m2_s()) + " m²/s (" + num(s.fluid.viscosity_cP) + " cP, " +
           num(u.density_kg_m3) + " kg/m³)"},
      {std::string("max speed") + (L.speed_is_estimate ? " (estimate)" : ""), num(L.expected_max_speed),
       num(L.expected_max_speed * u.velocity_m_s() * um) + " µm/s" +
           (L.speed_source.empty() ? "" : " (from " + L.speed_source + ")")},
      {"Mach", num(L.mach), "limit " + num(s.limits.max_mach)},
      {"Reynolds", num(L.reynolds), "L = " + num(L.reynolds_length_m * um) + " µm"},
      {"steps", std::to_string(L.total_steps),
       num(static_cast<double>(L.total_steps) * u.time_s) + " s simulated"},
  };
  rows.insert(rows.end(), fluid_rows.begin(), fluid_rows.end());
  if (const auto& m = L.time_mapping)  // eq 10.8
    rows.push_back({"time mapping", "Re = γ̇a²ρ/μ = " + num(m->reynolds) + " (physical " + num(m->physical_reynolds) + ")",
                    "ρ × " + num(m->density_factor()) + " (" + num(m->physical_density_kg_m3) + " → " +
                        num(m->run_density_kg_m3) + " kg/m³); γ̇ = " + num(m->shear_rate_per_s) + " 1/s, a = " +
                        num(m->radius_m * 1e6) + " µm; time and strain physical"});
  if (s.body_force)
    rows.push_back({"body force", vec(L.body_force), vec(s.body_force->density_N_m3) + " N/m³"});
  if (L.collision.model == fluid::CollisionModel::trt)
    rows.push_back({"collision", "trt, Λ = " + num(L.collision.trt_magic),
                    "τ− = " + num(fluid::trt_tau_minus(L.collision.tau, L.collision.trt_magic))});
  else
    rows.push_back({"collision", std::string(fluid::to_string(L.collision.model)), ""});
  // One row per pair of opposite sides; moving walls show their velocity.
  const auto pair_row = [&](const char* label, const fluid::Side& a, const fluid::Side& b, const char* na,
                            const char* nb) {
    std::string speeds;
    for (const auto& [side, name] : {std::pair{&a, na}, std::pair{&b, nb}}) {
      if (side->type != fluid::SideType::moving_wall) continue;
      const double scale = u.velocity_m_s() * um;
      speeds += std::string(speeds.empty() ? "" : "; ") + name + " moves at " +
                vec({side->ux * scale, side->uy * scale}) + " µm/s = " + vec({side->ux, side->uy}) + " lattice";
    }
    rows.push_back({label, std::string(fluid::to_string(a.type)) + " / " + std::string(fluid::to_string(b.type)),
                    speeds});
  };
  pair_row("left / right", L.boundaries.left, L.boundaries.right, "left", "right");
  pair_row("bottom / top", L.boundaries.bottom, L.boundaries.top, "bottom", "top");
  for (std::size_t i = 0; i < L.viscosity_layers.size(); ++i) {
    const fluid::ViscosityLayer& l = L.viscosity_layers[i];
    const double h_um = u.length_m * um;
    rows.push_back({"layer " + std::to_string(i), "τ = " + num(l.tau) + ", " + std::to_string(fluid::covered_nodes(L.grid, l)) + " nodes",
                    num(s.fluid.layers[i].viscosity_cP) + " cP, x " + vec({l.x_lo * h_um, l.x_hi * h_um}) + ", y " +
                        vec({l.y_lo * h_um, l.y_hi * h_um}) + " µm"});
  }

  if (const auto& M = L.membrane) {
    const membrane::StabilityEstimate& e = M->stability;
    rows.push_back({"membrane", std::string(membrane::to_string(M->model.tension.type)) + ", " +
                                    std::string(ib::to_string(M->kernel)),
                    M->indicator == interior::Method::indexless
                        ? std::string("interior viscosity = exterior")
                        : "interior " + num(spec.interior_viscosity_cP.value_or(0.0)) + " cP by " +
                              std::string(interior::to_string(M->indicator)) + " every " +
                              std::to_string(M->index_update_interval) + " step(s)" +
                              (spec.index_update_interval == 0 ? " (k U <= 0.1 h at the max speed)" : "")});
    if (M->indicator != interior::Method::indexless)
      rows.push_back({"interior τ", num(M->interior_tau), "limit >= " + num(0.5 + s.limits.min_tau_margin)});
    rows.push_back({"shear modulus E_s", num(M->model.tension.modulus),
                    num(spec.shear_modulus_dyn_cm) + " dyn/cm"});
    rows.push_back({"bending modulus E_B", num(M->model.bending),
                    num(spec.bending_modulus_dyn_cm) + " dyn·cm"});
    rows.push_back({"area modulus k_A", num(M->model.area_modulus),
                    num(spec.area_modulus_Pa) + " Pa"});
    if (const auto& a = M->aggregation)
      rows.push_back({"aggregation (Morse)", "D_e " + num(a->De) + ", r0 " + num(a->r0) + ", r_c " + num(a->cutoff),
                      "flat-contact gap " + num(M->aggregation_flat_gap * u.length_m * um) + " µm"});
    if (const auto& g = M->aggregation_strength) append_aggregation_rows(*g, rows);
    if (const auto& r = M->repulsion)
      rows.push_back({"repulsion", "P " + num(r->pressure) + ", d " + num(r->range) + (r->walls ? ", walls" : ""),
                      "d = " + num(r->range * u.length_m * um) + " µm"});
    rows.push_back({"stability Π_T", num(e.tension_number), "limit " + num(e.tension_limit)});
    rows.push_back({"stability Π_B", num(e.bending_number), "limit " + num(e.bending_limit)});
    rows.push_back({"stability Π_A", num(e.area_number), "limit " + num(e.area_limit)});
    rows.push_back({"max Δt factor", num(e.max_dt_factor), "accepted when >= 1"});
    for (std::size_t i = 0; i < M->cells.size(); ++i) {
      const CellSetup& c = M->cells[i];
      double cx = 0.0, cy = 0.0;
      geometry::centroid(c.shape, cx, cy);
      rows.push_back({"cell " + std::to_string(i) + " (" + s.cells[i].shape + ")",
                      std::to_string(c.shape.size()) + " markers, R_eq = " + num(c.equivalent_radius),
                      "centre " + vec({cx * u.length_m * um, cy * u.length_m * um}) + " µm, spacing " +
                          num(c.min_edge) + "–" + num(c.max_edge) + " h"});
    }
  }
  append_transport_rows(s, L, rows);
  return format_rows(s, L, rows);
}

namespace {

void append_transport_rows(const Scene& s, const LatticeSetup& L, std::vector<std::array<std::string, 3>>& rows) {
  const auto& T = L.transport;
  if (!T) return;
  rows.push_back({"transport", T->coupling + (T->stencil == transport::Stencil::d2q9 ? ", d2q9" : ", d2q5"),
                  "Δt_T = " + num(T->time_step_s) + " s" +
                      (T->fluid_steps_per_step > 0 ? " (" + std::to_string(T->fluid_steps_per_step) + " fluid steps)"
                                                   : "")});
  for (std::size_t i = 0; i < T->species.size(); ++i) {
    const SpeciesSetup& sp = T->species[i];
    rows.push_back({"species " + sp.name + " D", num(sp.diffusivity) + " (τ " + num(0.5 + 3.0 * sp.diffusivity) + ")",
                    num(s.species[i].diffusivity_um2_s) + " µm²/s, initial " + num(sp.initial) + " µM"});
    if (sp.cell_diffusivity != sp.diffusivity || sp.cell_initial != sp.initial)
      rows.push_back({"species " + sp.name + " in cells", num(sp.cell_diffusivity) + " (τ " +
                                                             num(0.5 + 3.0 * sp.cell_diffusivity) + ")",
                      num(s.species[i].cell_diffusivity_um2_s.value_or(s.species[i].diffusivity_um2_s)) +
                          " µm²/s, initial " + num(sp.cell_initial) + " µM"});
  }
  if (T->hemoglobin)
    rows.push_back({"hemoglobin", T->species[static_cast<std::size_t>(T->hemoglobin_species)].name,
                    "k_off " + num(T->hemoglobin->k_off) + " 1/s, M = " + num(T->hemoglobin->M) + ", heme " +
                        num(T->hemoglobin->C_heme) + " µM"});
  append_transport_option_rows(*T, rows);  // transport_options.cpp
}

std::string format_rows(const Scene& s, const LatticeSetup& L, const std::vector<std::array<std::string, 3>>& rows) {
  std::ostringstream os;
  os << "scene '" << s.name << "' (" << origin(s) << ")\n";
  for (const auto& r : rows) {
    std::string line = "  " + pad(r[0], 26) + pad(r[1], 26) + r[2];
    line.erase(line.find_last_not_of(' ') + 1);
    os << line << "\n";
  }
  if (L.speed_is_estimate)
    os << "  note: the body force acts along a periodic direction, which has no steady state;\n"
          "        the max speed is an estimate (Poiseuille F·H²/(8ν) with H = domain size, or F·steps)\n";
  if (L.membrane && !L.membrane->stability.warning.empty()) os << "  warning: " << L.membrane->stability.warning << "\n";
  return os.str();
}

}  // namespace

}  // namespace erythro::scene
