#include "rbc_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "capsule_run.hpp"  // make_shear_lattice: the undisturbed shear flow
#include "fluid/fluid_lattice.hpp"
#include "geometry/domain.hpp"
#include "geometry/shapes.hpp"
#include "interior/index_field.hpp"
#include "membrane/immersed_cells.hpp"
#include "membrane/stability.hpp"

namespace erythro::vv {

namespace {
constexpr double kPi = std::numbers::pi;
// Wraps an angle difference (degrees) into (−period/2, period/2].
double wrap(double d, double period) { return d - period * std::round(d / period); }

// Upper bound on any relaxation time of the run. BGK is linearly stable for every τ > ½,
// but the IB no-slip error (leakage, slip at the membrane) grows with τ, roughly as
// (τ − ½)² for the bounce-back-like halfway errors; τ = 5 (ratio 9 at τ_ex = 1) is kept
// as a hard stop against a mistyped ratio rather than a physical limit.
constexpr double kTauMax = 5.0;

// The health monitor's message (cf. sim::describe_divergence), in lattice units.
std::string describe(long step, const HealthReport& h, double tau_ex, double tau_in) {
  std::ostringstream out;
  out << "diverged at step " << step << ": " << h.quantity << " = " << h.value << " at node (" << h.node_x << ", "
      << h.node_y << ")";
  if (std::isnan(h.limit)) out << " is not finite";
  else if (h.quantity == "density") out << " is not positive";
  else out << " exceeds the limit " << h.limit << " (max_mach)";
  out << "; tau_ex = " << tau_ex << ", tau_in = " << tau_in;
  return out.str();
}
}  // namespace

std::string classify(const RbcResult& r) {
  if (r.diverged) return "undetermined";
  if (std::abs(r.body_rotation_deg) >= 90.0) return "tumbling";
  if (std::abs(r.marker_rotation_deg - r.body_rotation_deg) >= 90.0) return "tank-treading";
  return "undetermined";
}

RbcResult run_rbc(const RbcConfig& c) {
  using namespace membrane;
  using namespace geometry;
  const auto t_start = std::chrono::steady_clock::now();
  RbcResult r;
  // Dimensionless groups of the physical cell (docs/model.md §3, docs/parameters.md).
  r.capillary = c.mu_Pa_s * c.shear_rate * c.a_m / c.Es_N_m;  // Ca = μγ̇a/E_S
  r.bending_reduced = c.Eb_J / (c.a_m * c.a_m * c.Es_N_m);     // E_B* = E_B/(a²E_S)
  r.reynolds_physical = 1000.0 * c.shear_rate * c.a_m * c.a_m / c.mu_Pa_s;
  // Lattice: h = 1, ν = (τ − ½)/3, γ̇ from the chosen Re = γ̇a²/ν; the moduli keep Ca, E_B*, k_A a/E_S.
  const double a = c.a_m / c.h_m;
  const double nu = (c.tau - 0.5) / 3.0;
  r.a_lat = a;
  r.gamma_lat = c.reynolds * nu / (a * a);
  r.Es_lat = nu * r.gamma_lat * a / r.capillary;  // μ = ρ0ν = ν
  r.Eb_lat = r.bending_reduced * a * a * r.Es_lat;
  r.kA_lat = c.area_modulus * r.Es_lat / a;
  r.nx = static_cast<int>(std::lround(c.length * a));
  r.ny = static_cast<int>(std::lround(c.height * a));
  const int nx = r.nx, ny = r.ny;
  const double gamma = r.gamma_lat;
  fluid::FluidLattice lat = make_shear_lattice(nx, ny, gamma, c.tau);  // undisturbed shear u = γ̇(y − H/2)
  // Interior viscosity (docs/model.md §5): eq 27 with ν_ex from τ and ν_in = ratio·ν_ex, so
  // τ_in = ½ + ratio(τ_ex − ½). Indexless leaves the lattice untouched (no τ field).
  const bool varying = c.indicator != interior::Method::indexless;
  const double nu_in = varying ? c.viscosity_ratio * nu : nu;
  r.tau_ex = c.tau;
  r.tau_in = 0.5 + 3.0 * nu_in;
  if (!(c.tau > 0.5) || !(r.tau_in > 0.5) || r.tau_ex > kTauMax || r.tau_in > kTauMax)
    throw std::invalid_argument("rbc run: relaxation times tau_ex = " + std::to_string(r.tau_ex) + ", tau_in = " +
                                std::to_string(r.tau_in) + " outside (0.5, 5]");
  if (c.index_update_interval < 1) throw std::invalid_argument("rbc run: index_update_interval must be >= 1");
  std::optional<interior::IndexField> field;
  if (varying) {
    lat.enable_tau_field();
    field.emplace(fluid::domain_of(lat.grid(), lat.boundaries()), interior::IndexFieldOptions{c.indicator, 2.0});
  }

  // Biconcave cell, long axis along the flow (tilted 0.01 rad), centred slightly off the lattice symmetry.
  const double perimeter_over_a = 19.271 / 3.91;  // docs/parameters.md (2D biconcave section)
  const int n = static_cast<int>(std::lround(perimeter_over_a * a / c.marker_spacing));
  r.markers = n;
  const double xc0 = 0.5 * nx + 0.123, yc0 = 0.5 * ny;
  const Polygon shape = transformed(biconcave(n, a), 1.0, 0.01, xc0, yc0);
  const RestShape rest = RestShape::from_polygon(shape);  // stress-free; κ0 = biconcave curvature
  const MembraneModel model{{TensionLawType::neo_hookean, r.Es_lat}, r.Eb_lat, r.kA_lat};
  StabilityInput si;
  si.kernel = c.kernel;
  si.model = model;
  si.viscosity = std::min(nu, nu_in);  // the smallest viscosity at the membrane
  si.max_stretch = 1.2;
  const StabilityEstimate est = estimate_stability(si);
  r.stability_factor = est.max_dt_factor;
  if (!est.acceptable() && c.require_stability_estimate) throw std::runtime_error(est.problem);
  ImmersedCells cells(c.kernel, lat);
  cells.add_cell(shape, rest, model);
  const double A0 = rest.area;

  const long steps = std::lround(c.strain / gamma);
  const long sample_every = std::max(1L, std::lround(0.05 / gamma));
  std::vector<double> phase(static_cast<std::size_t>(n), 0.0), last(static_cast<std::size_t>(n), 0.0);
  double theta_unwrapped = 0, theta_raw_prev = 0, marker0_start = 0;
  std::size_t next_snap = 0;
  auto snapshot = [&](const Polygon& p, double strain) {
    double cx, cy;
    centroid(p, cx, cy);
    ShapeSnapshot s;
    s.strain = strain;
    const double um = c.h_m * 1e6;
    for (std::size_t m = 0; m <= p.size(); ++m) {  // closed: marker 0 repeated
      s.x_um.push_back((p.x[m % p.size()] - cx) * um);
      s.y_um.push_back((p.y[m % p.size()] - cy) * um);
    }
    r.snapshots.push_back(std::move(s));
  };
  // Index field → τ field from the current membrane (thesis §II.4: before each fluid step).
  auto update_viscosity = [&]() {
    const auto t0 = std::chrono::steady_clock::now();
    const Polygon p = cells.polygon(0);
    const interior::FillReport& fr = field->update(std::span<const Polygon>(&p, 1));
    // Eq 27: the whole τ field once, then only where I changed (bitwise the same;
    // IndexField::write_changed_relaxation_times), as sim::CellPhysics does.
    if (r.index_updates == 0)
      field->write_relaxation_times(lat.tau_field(), nu_in, nu);
    else
      field->write_changed_relaxation_times(lat.tau_field(), nu_in, nu);
    r.max_fill_mismatch = std::max(r.max_fill_mismatch, fr.max_area_mismatch / A0);
    r.fallback_cells = std::max(r.fallback_cells, fr.fallback_cells);
    ++r.index_updates;
    r.index_time_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  for (long s = 0; s <= steps; ++s) {
    if (s > 0) {
      try {
        if (varying && (s - 1) % c.index_update_interval == 0) update_viscosity();
        cells.advance(lat);
      } catch (const interior::FillLeakError& e) {
        r.diverged = true;
        r.diagnosis = "index field at step " + std::to_string(s) + ": " + e.what();
        break;
      } catch (const std::domain_error& e) {
        r.diverged = true;
        r.diagnosis = "step " + std::to_string(s) + ": " + e.what();
        break;
      }
      r.steps = s;
    }
    const Polygon p = cells.polygon(0);
    // Per step: area change and edge strain |ℓ_e/L_e − 1|.
    const double dA = signed_area(p) / A0 - 1.0;
    double emax = 0;
    for (std::size_t e = 0; e < p.size(); ++e) {
      const std::size_t f = (e + 1) % p.size();
      const double l = std::hypot(p.x[f] - p.x[e], p.y[f] - p.y[e]);
      emax = std::max(emax, std::abs(l / rest.length[e] - 1.0));
    }
    if (!std::isfinite(dA) || std::abs(dA) > 0.2) {
      r.diverged = true;
      r.diagnosis = "area change A/A0 - 1 = " + std::to_string(dA) + " at step " + std::to_string(s) +
                    " (limit 0.2): the membrane failed";
      break;
    }
    r.max_area_change = std::max(r.max_area_change, std::abs(dA));
    r.max_edge_strain = std::max(r.max_edge_strain, emax);
    if (s % sample_every != 0 && s != steps) continue;
    // Health monitor at every sample (finite ρ, u; ρ > 0; |u|/c_s ≤ max_mach).
    const HealthReport health = lat.check_health(c.max_mach);
    if (!health.healthy) {
      r.diverged = true;
      r.diagnosis = describe(s, health, r.tau_ex, r.tau_in);
      break;
    }
    const double strain = static_cast<double>(s) * gamma;
    double D, th;
    taylor_deformation(p, D, th);
    double cx, cy;
    centroid(p, cx, cy);
    if (s == 0) theta_unwrapped = th;
    else theta_unwrapped += wrap(th - theta_raw_prev, 180.0);  // the axis is defined mod 180°
    theta_raw_prev = th;
    for (std::size_t m = 0; m < p.size(); ++m) {
      const double ang = std::atan2(p.y[m] - cy, p.x[m] - cx) * 180.0 / kPi;
      if (s > 0) phase[m] += wrap(ang - last[m], 360.0);
      last[m] = ang;
    }
    if (s == 0) marker0_start = last[0];
    r.strain_h.push_back(strain);
    r.D_h.push_back(D);
    r.theta_h.push_back(theta_unwrapped);
    r.area_h.push_back(dA);
    r.estrain_h.push_back(emax);
    r.psi_h.push_back(marker0_start + phase[0] - theta_unwrapped);  // ψ: marker 0 from the long axis
    double mp = 0;
    for (double ph : phase) mp += ph / static_cast<double>(n);
    r.phase_h.push_back(mp);
    while (next_snap < c.snapshot_strains.size() && strain >= c.snapshot_strains[next_snap] - 0.5 * gamma) {
      snapshot(p, strain);
      ++next_snap;
    }
  }
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  if (r.diverged || r.strain_h.size() < 3) {
    if (r.diagnosis.empty()) r.diagnosis = "fewer than 3 samples";
    r.diverged = true;
    if (!r.strain_h.empty()) r.strain = r.strain_h.back();
    return r;
  }
  r.strain = r.strain_h.back();
  if (field) {  // Σ(1 − I)/A of the last update: 1 when the whole interior carries ν_in
    double filled = 0;
    for (double v : field->values()) filled += 1.0 - v;
    r.interior_fraction = filled / A0;
  }
  {  // rates over the second half of the run
    const std::size_t i0 = r.strain_h.size() / 2, i1 = r.strain_h.size() - 1;
    const double ds = r.strain_h[i1] - r.strain_h[i0];
    if (ds > 0) {
      r.marker_rate_deg = (r.phase_h[i1] - r.phase_h[i0]) / ds;
      r.body_rate_deg = (r.theta_h[i1] - r.theta_h[i0]) / ds;
    }
  }
  r.body_rotation_deg = r.theta_h.back() - r.theta_h.front();
  double mean = 0;
  for (double ph : phase) mean += ph / static_cast<double>(n);
  r.marker_rotation_deg = mean;
  r.marker0_rotation_deg = phase[0];
  r.theta_min = 1e9;
  r.theta_max = -1e9;
  double sD = 0, sT = 0;
  int k = 0;
  for (std::size_t i = 0; i < r.strain_h.size(); ++i) {
    if (r.strain_h[i] >= 2.0) {
      r.theta_min = std::min(r.theta_min, r.theta_h[i]);
      r.theta_max = std::max(r.theta_max, r.theta_h[i]);
    }
    if (r.strain_h[i] >= r.strain - 2.0) { sD += r.D_h[i]; sT += r.theta_h[i]; ++k; }
  }
  if (r.theta_min > r.theta_max) r.theta_min = r.theta_max = r.theta_h.back();  // run shorter than strain 2
  r.D_mean = sD / k;
  r.theta_mean = sT / k;
  const Polygon p = cells.polygon(0);
  double cx, cy;
  centroid(p, cx, cy);
  r.centre_drift = std::abs(cy - yc0) / a;
  return r;
}

}  // namespace erythro::vv
