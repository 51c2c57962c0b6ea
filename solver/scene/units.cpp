// Physical scene → lattice units (h = Δt = 1, ρ0 = 1), plus the checks that need
// several values at once. Formulas (docs/scenes.md "Unit conversion"):
//   n = L / h                               nodes per direction (must be a whole number)
//   ν = μ / ρ                               physical kinematic viscosity [m²/s]
//   ν_lat = c_s² (τ − ½) = (τ − ½) / 3      (model.md §1)
//   Δt = (τ − ½) h² / (3ν)   ⇔   τ = ½ + 3 ν Δt / h²
//   u_lat = u Δt / h,   F_lat = F Δt² / (ρ h),   f_lat = f Δt
#include "scene/units.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

#include "common/error.hpp"
#include "lattice/d2q9.hpp"
#include "membrane/membrane_units.hpp"
#include "membrane/shapes.hpp"

namespace erythro::scene {
namespace {

const double cs = std::sqrt(d2q9::cs2);

std::string num(double v) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}
std::string vec(const std::array<double, 2>& v) {
  std::string out(1, '[');  // built by appending: GCC 12 -Wrestrict misfires on "lit" + string&&
  return out.append(num(v[0])).append(", ").append(num(v[1])).append("]");
}
std::string origin(const Scene& s) { return s.source_path.empty() ? "scene" : s.source_path; }

[[noreturn]] void reject(const Scene& s, const std::string& what) { throw InputError(origin(s) + ": " + what); }

bool is_wall(const SideSpec& side) { return side.type != "periodic"; }
// Axis 0 (x) is bounded by the left/right sides, axis 1 (y) by bottom/top.
bool wall_bounded(const Scene& s, int axis) {
  return axis == 0 ? is_wall(s.boundaries.left) : is_wall(s.boundaries.bottom);
}

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
  if (n[0] * n[1] > 2e9) reject(s, "domain has " + num(n[0] * n[1]) + " nodes; at most 2e9 are supported");
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

// Shortest distance between two markers along axis a, using the nearest periodic image.
double axis_gap(double d, int n, bool periodic) {
  if (periodic) d -= n * std::round(d / n);
  return d;
}

// Even-odd rule: is (px, py) inside polygon p?
bool inside(const membrane::Polygon& p, double px, double py) {
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p.y[i] > py) != (p.y[j] > py) &&
        px < (p.x[j] - p.x[i]) * (py - p.y[i]) / (p.y[j] - p.y[i]) + p.x[i])
      in = !in;
  }
  return in;
}

std::string cell_key(std::size_t i, const char* key) { return "cells[" + std::to_string(i) + "]." + key; }

// [membrane] and [[cells]] → lattice moduli, placed marker polygons and the stability
// estimate. Rules (docs/scenes.md): equivalent radius >= kMinCellRadius h, marker
// spacing in [kMinMarkerSpacing, kMaxMarkerSpacing] h, markers >= kMinCellGap h from
// another cell's markers and from a wall, stability numbers below their limits.
MembraneSetup derive_membrane(const Scene& s, const LatticeSetup& L) {
  const MembraneSpec spec = s.membrane.value_or(MembraneSpec{});
  MembraneSetup M;
  if (!ib::parse_kernel(spec.kernel, M.kernel))
    reject(s, "membrane.kernel = \"" + spec.kernel + "\" is not one of \"cosine4\", \"peskin4\", \"roma3\", \"linear2\"");
  membrane::TensionLawType law{};
  if (!membrane::parse_tension_law(spec.law, law))
    reject(s, "membrane.law = \"" + spec.law + "\" is not one of \"neo_hookean\", \"skalak\", \"hookean\"");
  // SI, then the layer's own conversion (membrane_units.hpp): E_s [N/m], E_B [J], k_A [Pa].
  const membrane::LatticeScales ms{L.scales.length_m, L.scales.time_s, L.scales.density_kg_m3};
  M.model.tension.type = law;
  M.model.tension.modulus = membrane::tension_to_lattice(spec.shear_modulus_dyn_cm * membrane::kDynPerCm, ms);
  M.model.tension.skalak_c = spec.skalak_c;
  M.model.bending = membrane::bending_to_lattice(spec.bending_modulus_dyn_cm * membrane::kDynCm, ms);
  M.model.area_modulus = membrane::pressure_to_lattice(spec.area_modulus_Pa, ms);

  const double h_um = s.domain.spacing_um;
  const int n[2] = {L.grid.nx, L.grid.ny};
  const bool periodic[2] = {!wall_bounded(s, 0), !wall_bounded(s, 1)};
  for (std::size_t i = 0; i < s.cells.size(); ++i) {
    const CellSpec& c = s.cells[i];
    if (c.markers != 0 && c.markers < 8)
      reject(s, "key '" + cell_key(i, "markers") + "' = " + std::to_string(c.markers) + " must be >= 8");
    std::string size_key = cell_key(i, "radius_um"), size_shown = num(c.radius_um) + " µm";
    const auto make = [&](int count) {
      if (c.shape == "circle") return membrane::circle(count, c.radius_um / h_um);
      if (c.shape == "ellipse") return membrane::ellipse(count, c.semi_axes_um[0] / h_um, c.semi_axes_um[1] / h_um);
      if (c.shape == "biconcave") return membrane::biconcave(count, c.radius_um / h_um);
      reject(s, "key '" + cell_key(i, "shape") + "' = \"" + c.shape + "\" is not one of \"circle\", \"ellipse\", \"biconcave\"");
    };
    if (c.shape == "ellipse") {
      size_key = cell_key(i, "semi_axes_um");
      size_shown = vec(c.semi_axes_um) + " µm";
    }
    // markers = 0 (key absent): perimeter / kAutoMarkerSpacing, at least 16.
    const int m = c.markers != 0 ? static_cast<int>(c.markers)
                                 : std::max(16, static_cast<int>(std::ceil(membrane::perimeter(make(512)) * c.scale /
                                                                            kAutoMarkerSpacing)));
    const membrane::Polygon base = make(m);
    CellSetup cell;
    cell.shape = membrane::transformed(base, c.scale, c.angle_deg * std::numbers::pi / 180.0, c.center_um[0] / h_um,
                                       c.center_um[1] / h_um);
    membrane::make_counter_clockwise(cell.shape);
    cell.equivalent_radius = std::sqrt(std::abs(membrane::signed_area(cell.shape)) / std::numbers::pi);
    cell.min_edge = std::numeric_limits<double>::infinity();
    for (std::size_t e = 0; e < cell.shape.size(); ++e) {
      const std::size_t f = (e + 1) % cell.shape.size();
      const double len = std::hypot(cell.shape.x[f] - cell.shape.x[e], cell.shape.y[f] - cell.shape.y[e]);
      cell.min_edge = std::min(cell.min_edge, len);
      cell.max_edge = std::max(cell.max_edge, len);
    }
    if (cell.equivalent_radius < kMinCellRadius)
      reject(s, "resolution too coarse: cell " + std::to_string(i) + " has " + size_key + " = " + size_shown +
                    " (× scale " + num(c.scale) + "), an equivalent radius √(A/π) of " + num(cell.equivalent_radius) +
                    " h, below " + num(kMinCellRadius) + " h: enlarge the cell or make domain.spacing_um <= " +
                    num(h_um * cell.equivalent_radius / kMinCellRadius) + " µm");
    if (cell.max_edge > kMaxMarkerSpacing)
      reject(s, "key '" + cell_key(i, "markers") + "' = " + std::to_string(m) + " is too few: markers are up to " +
                    num(cell.max_edge) + " h apart, more than " + num(kMaxMarkerSpacing) +
                    " h (fluid leaks between markers): use markers >= " +
                    std::to_string(static_cast<long>(std::ceil(m * cell.max_edge / kMaxMarkerSpacing))));
    if (cell.min_edge < kMinMarkerSpacing)
      reject(s, "key '" + cell_key(i, "markers") + "' = " + std::to_string(m) + " is too many: markers are as close as " +
                    num(cell.min_edge) + " h, less than " + num(kMinMarkerSpacing) +
                    " h (over-resolved membrane, stiff and noisy): use markers <= " +
                    std::to_string(static_cast<long>(std::floor(m * cell.min_edge / kMinMarkerSpacing))));
    const double centre[2] = {c.center_um[0] / h_um, c.center_um[1] / h_um};
    for (int a = 0; a < 2; ++a)
      if (!(centre[a] >= 0.0 && centre[a] < n[a]))
        reject(s, "key '" + cell_key(i, "center_um") + "' = " + vec(c.center_um) + " µm lies outside the domain " +
                      vec(s.domain.size_um) + " µm");
    for (int a = 0; a < 2; ++a) {
      if (periodic[a]) continue;
      const auto& coords = a == 0 ? cell.shape.x : cell.shape.y;
      const auto [lo, hi] = std::minmax_element(coords.begin(), coords.end());
      const double gap = std::min(*lo, n[a] - *hi);
      if (gap < kMinCellGap)
        reject(s, "key '" + cell_key(i, "center_um") + "' = " + vec(c.center_um) + " µm places cell " +
                      std::to_string(i) + " " + num(gap) + " h from the " +
                      (a == 0 ? "left/right" : "bottom/top") + " wall, closer than " + num(kMinCellGap) +
                      " h (overlaps the wall): move it inward or shrink it");
    }
    for (std::size_t j = 0; j < M.cells.size(); ++j) {
      const membrane::Polygon& o = M.cells[j].shape;
      double closest = std::numeric_limits<double>::infinity();
      for (std::size_t p = 0; p < cell.shape.size(); ++p)
        for (std::size_t q = 0; q < o.size(); ++q)
          closest = std::min(closest, std::hypot(axis_gap(cell.shape.x[p] - o.x[q], n[0], periodic[0]),
                                                 axis_gap(cell.shape.y[p] - o.y[q], n[1], periodic[1])));
      const bool nested = inside(o, cell.shape.x[0], cell.shape.y[0]) || inside(cell.shape, o.x[0], o.y[0]);
      if (nested || closest < kMinCellGap)
        reject(s, "key '" + cell_key(i, "center_um") + "' = " + vec(c.center_um) + " µm makes cell " +
                      std::to_string(i) + " overlap cell " + std::to_string(j) + " (" + cell_key(j, "center_um") +
                      " = " + vec(s.cells[j].center_um) + " µm): " +
                      (nested ? std::string("one lies inside the other")
                              : "their markers are " + num(closest) + " h apart, closer than " + num(kMinCellGap) + " h") +
                      "; move them apart");
    }
    M.cells.push_back(std::move(cell));
  }

  // Explicit-update stability (membrane/stability.hpp): Π = modulus Δt²/(ρ0 h^k) < limit.
  membrane::StabilityInput in;
  in.kernel = M.kernel;
  in.model = M.model;
  in.viscosity = L.viscosity;
  in.density = 1.0;
  in.max_stretch = 1.0;  // cells start at their rest shape
  M.stability = membrane::estimate_stability(in);
  if (!M.stability.acceptable()) {
    const auto& e = M.stability;
    struct Term {
      const char* key;
      std::string shown;
      const char* number;
      double value, limit;
    };
    const Term terms[] = {
        {"membrane.shear_modulus_dyn_cm", num(spec.shear_modulus_dyn_cm) + " dyn/cm", "Π_T = (dT/dλ) Δt²/(ρ0 h³)",
         e.tension_number, e.tension_limit},
        {"membrane.bending_modulus_dyn_cm", num(spec.bending_modulus_dyn_cm) + " dyn·cm", "Π_B = E_B Δt²/(ρ0 h⁵)",
         e.bending_number, e.bending_limit},
        {"membrane.area_modulus_Pa", num(spec.area_modulus_Pa) + " Pa", "Π_A = k_A Δt²/(ρ0 h²)", e.area_number,
         e.area_limit}};
    const Term* worst = &terms[0];
    for (const Term& t : terms)
      if (t.value / t.limit > worst->value / worst->limit) worst = &t;
    const double factor = std::sqrt(worst->limit / worst->value);
    reject(s, "key '" + std::string(worst->key) + "' = " + worst->shown +
                  " is outside the membrane's stability limit: " + worst->number + " = " + num(worst->value) +
                  " exceeds " + num(worst->limit) + " (explicit immersed-boundary update, " +
                  std::string(ib::to_string(M.kernel)) + " kernel, membrane::estimate_stability, " +
                  "docs/verification-ib-membrane.md); lower " + worst->key + " by a factor " +
                  num(1.0 / (factor * factor)) + ", or shrink the time step by a factor " + num(1.0 / factor) + " (" +
                  (s.time.tau ? "time.tau <= " + num(0.5 + (L.collision.tau - 0.5) * factor)
                              : "time.step_s <= " + num(L.scales.time_s * factor) + " s") +
                  ") or refine domain.spacing_um");
  }
  return M;
}

}  // namespace

LatticeSetup derive_lattice(const Scene& s) {
  LatticeSetup L;
  L.grid = make_grid(s);

  // --- time step and relaxation time: Δt = (τ − ½) h² / (3ν)  ⇔  τ = ½ + 3νΔt/h²
  const double h = s.domain.spacing_um * 1e-6;                       // [m]
  const double nu = s.fluid.viscosity_cP * 1e-3 / s.fluid.density_kg_m3;  // [m²/s]
  if (!(nu > 0.0) || !std::isfinite(nu))
    reject(s, "fluid.viscosity_cP = " + num(s.fluid.viscosity_cP) + " and fluid.density_kg_m3 = " +
                  num(s.fluid.density_kg_m3) + " must be > 0");
  if (s.time.tau.has_value() == s.time.step_s.has_value())
    reject(s, "give exactly one of time.step_s (s, > 0) or time.tau (> 0.5)");
  double tau = 0.0, dt = 0.0;
  if (s.time.tau) {
    tau = *s.time.tau;
    dt = (tau - 0.5) * h * h / (3.0 * nu);
  } else {
    dt = *s.time.step_s;
    tau = 0.5 + 3.0 * nu * dt / (h * h);
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
  L.scales = UnitScales{h, dt, s.fluid.density_kg_m3};
  L.viscosity = (tau - 0.5) * d2q9::cs2;

  // --- collision
  if (!fluid::parse_collision_model(s.fluid.collision, L.collision.model))
    reject(s, "fluid.collision = \"" + s.fluid.collision + "\" is not one of \"bgk\", \"trt\", \"regularized\"");
  if (!(s.fluid.trt_magic > 0.0)) reject(s, "fluid.trt_magic = " + num(s.fluid.trt_magic) + " must be > 0");
  L.collision.tau = tau;
  L.collision.trt_magic = s.fluid.trt_magic;

  // --- boundaries: u_lat = u Δt / h
  const double u_scale = 1e-6 * dt / h;  // µm/s → lattice
  L.boundaries.left = make_side(s, s.boundaries.left, "left", u_scale);
  L.boundaries.right = make_side(s, s.boundaries.right, "right", u_scale);
  L.boundaries.bottom = make_side(s, s.boundaries.bottom, "bottom", u_scale);
  L.boundaries.top = make_side(s, s.boundaries.top, "top", u_scale);
  if (const std::string why = L.boundaries.inconsistency(); !why.empty()) reject(s, "boundaries: " + why);

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
      s.initial.type != "taylor_green")
    reject(s, "initial.type = \"" + s.initial.type + "\" is not one of \"rest\", \"uniform\", \"shear\", \"taylor_green\"");
  if (s.initial.type == "shear" && !wall_bounded(s, 1))
    reject(s, "initial.type = \"shear\" needs walls at bottom and top (the profile joins their velocities)");
  if (s.initial.type == "taylor_green" && (wall_bounded(s, 0) || wall_bounded(s, 1)))
    reject(s, "initial.type = \"taylor_green\" needs all four sides periodic");
  L.initial_velocity = {s.initial.velocity_um_s[0] * u_scale, s.initial.velocity_um_s[1] * u_scale};

  // --- body force: F_lat = F Δt² / (ρ h);  f_lat = f Δt (cycles per step)
  if (s.body_force) {
    const double f_scale = dt * dt / (s.fluid.density_kg_m3 * h);
    L.body_force = {s.body_force->density_N_m3[0] * f_scale, s.body_force->density_N_m3[1] * f_scale};
    L.force_frequency = s.body_force->frequency_Hz * dt;
    L.force_phase = s.body_force->phase_rad;
  }

  // --- run length: steps, or ⌈duration / Δt⌉ (a ratio within 1e-9 of a whole number is that number)
  if (s.run.steps.has_value() == s.run.duration_s.has_value())
    reject(s, "give exactly one of run.steps or run.duration_s");
  if (s.run.steps) {
    L.total_steps = *s.run.steps;
  } else {
    const double x = *s.run.duration_s / dt;
    if (!(x <= 1e12))
      reject(s, "run.duration_s = " + num(*s.run.duration_s) + " s is " + num(x) + " steps of Δt = " + num(dt) +
                    " s; at most 1e12 steps are supported");
    const double r = std::round(x);
    L.total_steps = std::max(1L, static_cast<long>(std::abs(x - r) <= 1e-9 * x ? r : std::ceil(x)));
  }
  if (L.total_steps < 1) reject(s, "run.steps = " + std::to_string(L.total_steps) + " must be >= 1");

  // --- expected speed, Mach and Reynolds numbers
  const SpeedSource top = fastest(speed_sources(s, L));
  L.expected_max_speed = top.speed;
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
                  " lattice) is set by " + top.key + " = " + top.shown + (top.estimate ? " (estimate)" : "") +
                  "; lower it by a factor " + num(1.0 / r) + smaller_dt + ", or refine domain.spacing_um");
  }
  // Re = u L / ν, L = wall-to-wall distance (the narrower one if both axes have walls);
  // in a fully periodic box the shorter period.
  int length = std::min(L.grid.nx, L.grid.ny);
  if (wall_bounded(s, 0) != wall_bounded(s, 1)) length = wall_bounded(s, 0) ? L.grid.nx : L.grid.ny;
  L.reynolds = top.speed * length / L.viscosity;
  L.reynolds_length_m = length * h;
  if (!s.cells.empty()) L.membrane = derive_membrane(s, L);
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

std::string format_lattice_report(const Scene& s, const LatticeSetup& L) {
  const UnitScales& u = L.scales;
  const double um = 1e6;
  const SpeedSource top = fastest(speed_sources(s, L));
  std::vector<std::array<std::string, 3>> rows = {
      {"quantity", "lattice", "physical"},
      {"spacing h", "1", num(u.length_m * um) + " µm"},
      {"time step Δt", "1", num(u.time_s) + " s"},
      {"nodes", std::to_string(L.grid.nx) + " × " + std::to_string(L.grid.ny),
       vec(s.domain.size_um) + " µm"},
      {"relaxation time τ (tau)", num(L.collision.tau), "limit >= " + num(0.5 + s.limits.min_tau_margin)},
      {"viscosity ν", num(L.viscosity),
       num(L.viscosity * u.kinematic_viscosity_m2_s()) + " m²/s (" + num(s.fluid.viscosity_cP) + " cP, " +
           num(s.fluid.density_kg_m3) + " kg/m³)"},
      {std::string("max speed") + (top.estimate ? " (estimate)" : ""), num(L.expected_max_speed),
       num(L.expected_max_speed * u.velocity_m_s() * um) + " µm/s" +
           (top.key.empty() ? "" : " (from " + top.key + ")")},
      {"Mach", num(L.mach), "limit " + num(s.limits.max_mach)},
      {"Reynolds", num(L.reynolds), "L = " + num(L.reynolds_length_m * um) + " µm"},
      {"steps", std::to_string(L.total_steps),
       num(static_cast<double>(L.total_steps) * u.time_s) + " s simulated"},
  };
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

  if (const auto& M = L.membrane) {
    const membrane::StabilityEstimate& e = M->stability;
    rows.push_back({"membrane", std::string(membrane::to_string(M->model.tension.type)) + ", " +
                                    std::string(ib::to_string(M->kernel)),
                    "interior viscosity = exterior"});
    rows.push_back({"shear modulus E_s", num(M->model.tension.modulus),
                    num(s.membrane.value_or(MembraneSpec{}).shear_modulus_dyn_cm) + " dyn/cm"});
    rows.push_back({"bending modulus E_B", num(M->model.bending),
                    num(s.membrane.value_or(MembraneSpec{}).bending_modulus_dyn_cm) + " dyn·cm"});
    rows.push_back({"area modulus k_A", num(M->model.area_modulus),
                    num(s.membrane.value_or(MembraneSpec{}).area_modulus_Pa) + " Pa"});
    rows.push_back({"stability Π_T", num(e.tension_number), "limit " + num(e.tension_limit)});
    rows.push_back({"stability Π_B", num(e.bending_number), "limit " + num(e.bending_limit)});
    rows.push_back({"stability Π_A", num(e.area_number), "limit " + num(e.area_limit)});
    rows.push_back({"max Δt factor", num(e.max_dt_factor), "accepted when >= 1"});
    for (std::size_t i = 0; i < M->cells.size(); ++i) {
      const CellSetup& c = M->cells[i];
      double cx = 0.0, cy = 0.0;
      membrane::centroid(c.shape, cx, cy);
      rows.push_back({"cell " + std::to_string(i) + " (" + s.cells[i].shape + ")",
                      std::to_string(c.shape.size()) + " markers, R_eq = " + num(c.equivalent_radius),
                      "centre " + vec({cx * u.length_m * um, cy * u.length_m * um}) + " µm, spacing " +
                          num(c.min_edge) + "–" + num(c.max_edge) + " h"});
    }
  }

  std::ostringstream os;
  os << "scene '" << s.name << "' (" << origin(s) << ")\n";
  for (const auto& r : rows) {
    std::string line = "  " + pad(r[0], 26) + pad(r[1], 26) + r[2];
    line.erase(line.find_last_not_of(' ') + 1);
    os << line << "\n";
  }
  if (top.estimate)
    os << "  note: the body force acts along a periodic direction, which has no steady state;\n"
          "        the max speed is an estimate (Poiseuille F·H²/(8ν) with H = domain size, or F·steps)\n";
  if (L.membrane && !L.membrane->stability.warning.empty()) os << "  warning: " << L.membrane->stability.warning << "\n";
  return os.str();
}

}  // namespace erythro::scene
