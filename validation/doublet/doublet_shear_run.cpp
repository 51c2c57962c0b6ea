#include "doublet_shear_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "aggregation/morse_aggregation.hpp"
#include "aggregation/morse_units.hpp"
#include "capsule_run.hpp"  // make_shear_lattice: the undisturbed shear flow
#include "geometry/pair_geometry.hpp"
#include "fluid/fluid_lattice.hpp"
#include "geometry/domain.hpp"
#include "geometry/shapes.hpp"
#include "membrane/immersed_cells.hpp"
#include "membrane/stability.hpp"

namespace erythro::vv {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kTauMax = 5.0;  // as validation/rbc: a guard against a mistyped ratio
double wrap(double d, double period) { return d - period * std::round(d / period); }
}  // namespace

DoubletShearResult run_doublet_shear(const DoubletShearConfig& c) {
  using namespace membrane;
  using namespace geometry;
  const auto t_start = std::chrono::steady_clock::now();
  DoubletShearResult r;
  if (c.cells != 1 && c.cells != 2) throw std::invalid_argument("doublet run: cells must be 1 or 2");
  // Dimensionless groups of the physical cells (docs/model.md §3, §6).
  r.capillary0 = c.mu_Pa_s * c.shear_rate * c.a_m / c.Es0_N_m;  // Ca = μγ̇a/E_S
  r.capillary1 = c.mu_Pa_s * c.shear_rate * c.a_m / c.Es1_N_m;
  r.bending_reduced = c.Eb_J / (c.a_m * c.a_m * c.Es0_N_m);
  r.reynolds_physical = 1000.0 * c.shear_rate * c.a_m * c.a_m / c.mu_Pa_s;
  // Lattice (h = Δt = ρ0 = 1): ν from τ, γ̇ from the chosen Re = γ̇a²/ν; the moduli keep Ca, E_B*, k_A a/E_S.
  const double a = c.a_m / c.h_m;
  const double nu = (c.tau - 0.5) / 3.0;
  r.a_lat = a;
  r.gamma_lat = c.reynolds * nu / (a * a);
  r.Es0_lat = nu * r.gamma_lat * a / r.capillary0;
  r.Es1_lat = nu * r.gamma_lat * a / r.capillary1;
  r.Eb_lat = r.bending_reduced * a * a * r.Es0_lat;
  r.kA_lat = c.area_modulus * r.Es0_lat / a;
  r.nx = r.ny = static_cast<int>(std::lround(c.box_m / c.h_m));
  const int nx = r.nx, ny = r.ny;
  const double gamma = r.gamma_lat;
  fluid::FluidLattice lat = make_shear_lattice(nx, ny, gamma, c.tau);
  // Interior viscosity (eq 27): τ_in = ½ + 3λν_ex.
  const bool varying = c.indicator != interior::Method::indexless;
  const double nu_in = varying ? c.viscosity_ratio * nu : nu;
  r.tau_in = 0.5 + 3.0 * nu_in;
  if (!(c.tau > 0.5) || c.tau > kTauMax || r.tau_in > kTauMax)
    throw std::invalid_argument("doublet run: relaxation times outside (0.5, 5]");
  if (c.index_update_interval < 1) throw std::invalid_argument("doublet run: index_update_interval must be >= 1");

  // Morse (docs/model.md §4) in lattice units; D_e from the surface energy γ = De*·E_S0
  // through the flat-contact integral (morse_units.hpp).
  aggregation::MorseParameters morse{1.0, c.r0_m / c.h_m, c.beta_per_m * c.h_m, 0.0};
  morse.cutoff = morse.r0 + c.cutoff_k / morse.beta;
  const aggregation::FlatContact flat = aggregation::flat_contact(morse);
  morse.De = aggregation::pair_density_for_de_star(c.de_star, r.Es0_lat, morse);
  r.De_lat = morse.De;
  r.r0_lat = morse.r0;
  r.beta_lat = morse.beta;
  r.cutoff_lat = morse.cutoff;
  r.flat_gap_lat = flat.gap;

  // Cells. Doublet: two Evans–Fung cells with their long axes normal to the line of
  // centres at θ0 (face to face), rims the flat-contact gap apart; single: one cell
  // with its long axis at θ0. Centre off the lattice symmetry by 0.123 h.
  const double xc = 0.5 * nx + 0.123, yc = 0.5 * ny;
  const double th0 = c.theta0_deg * kPi / 180.0;
  std::vector<Polygon> shapes;
  if (c.cells == 2) {
    const Polygon base = c.shape == CellShape::biconcave ? biconcave(c.markers, a)
                                                         : ellipse(c.markers, a, a / c.ellipse_axis_ratio);
    double half = 0;
    for (double y : base.y) half = std::max(half, std::abs(y));
    const double gap = c.initial_gap_m < 0 ? flat.gap : c.initial_gap_m / c.h_m;
    const double d = half + 0.5 * gap;
    const double ex = std::cos(th0), ey = std::sin(th0);
    shapes.push_back(transformed(base, 1.0, th0 - 0.5 * kPi, xc - d * ex, yc - d * ey));
    shapes.push_back(transformed(base, 1.0, th0 - 0.5 * kPi, xc + d * ex, yc + d * ey));
  } else {
    const Polygon base = c.shape == CellShape::biconcave ? biconcave(c.markers, a)
                                                         : ellipse(c.markers, a, a / c.ellipse_axis_ratio);
    shapes.push_back(transformed(base, 1.0, th0, xc, yc));
  }
  const MembraneModel m0{{TensionLawType::neo_hookean, r.Es0_lat}, r.Eb_lat, r.kA_lat};
  const MembraneModel m1{{TensionLawType::neo_hookean, r.Es1_lat}, r.Eb_lat, r.kA_lat};
  StabilityInput si;
  si.kernel = c.kernel;
  si.model = r.Es1_lat > r.Es0_lat ? m1 : m0;  // the stiffer membrane limits the step
  si.viscosity = std::min(nu, nu_in);
  si.max_stretch = 1.2;
  const StabilityEstimate est = estimate_stability(si);
  r.stability_factor = est.max_dt_factor;
  if (!est.acceptable()) throw std::runtime_error(est.problem);
  ImmersedCells cells(c.kernel, lat);
  std::vector<double> A0;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const RestShape rest = RestShape::from_polygon(shapes[k]);
    cells.add_cell(shapes[k], rest, k == 0 ? m0 : m1);
    A0.push_back(rest.area);
  }
  r.markers = c.markers;
  const geometry::Domain dom = fluid::domain_of(lat.grid(), lat.boundaries());
  std::optional<aggregation::MorseAggregation> agg;
  if (c.cells == 2) agg.emplace(dom, morse);
  const std::vector<std::size_t> offsets = aggregation::cell_offsets(cells);

  // Index field → τ field (thesis §II.4), every k steps before the fluid step.
  std::optional<interior::IndexField> field;
  std::vector<Polygon> polys(shapes.size());
  auto current_polygons = [&]() -> std::span<const Polygon> {
    for (int k = 0; k < cells.cell_count(); ++k) polys[k] = cells.polygon(k);
    return polys;
  };
  if (varying) {
    lat.enable_tau_field();
    field.emplace(dom, interior::IndexFieldOptions{c.indicator, 2.0});
    field->update(current_polygons());
    field->write_relaxation_times(lat.tau_field(), nu_in, nu);
  }

  const long steps = std::lround(c.strain / gamma);
  const long sample_every = std::max(1L, std::lround(c.sample_strain / gamma));
  double theta_unwrapped = 0, theta_prev = 0;
  double aspect_sum = 0;
  int aspect_n = 0;
  double next_snap = 0;
  r.min_contact_after1 = std::numeric_limits<double>::infinity();
  const double um = c.h_m * 1e6;
  for (long s = 0; s <= steps; ++s) {
    if (s > 0) {
      try {
        if (field && (s - 1) % c.index_update_interval == 0 && s > 1) {
          field->update(current_polygons());
          field->write_changed_relaxation_times(lat.tau_field(), nu_in, nu);
        }
        cells.compute_forces();
        if (agg) agg->add_forces(cells);
        cells.advance_after_forces(lat);
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
    if (s % sample_every != 0 && s != steps) continue;
    const HealthReport health = lat.check_health(c.max_mach);
    if (!health.healthy) {
      r.diverged = true;
      r.diagnosis = "step " + std::to_string(s) + ": fluid unhealthy (" + health.quantity + ")";
      break;
    }
    const double strain = static_cast<double>(s) * gamma;
    std::vector<Polygon> p;
    for (int k = 0; k < cells.cell_count(); ++k) p.push_back(cells.polygon(k));
    std::vector<double> cx(p.size()), cy(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) centroid(p[k], cx[k], cy[k]);
    double area_change = 0, edge = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      area_change = std::max(area_change, std::abs(signed_area(p[k]) / A0[k] - 1.0));
      const RestShape& rest = cells.rest(static_cast<int>(k));
      for (std::size_t e = 0; e < p[k].size(); ++e) {
        const std::size_t f = (e + 1) % p[k].size();
        const double eps = std::abs(std::hypot(p[k].x[f] - p[k].x[e], p[k].y[f] - p[k].y[e]) / rest.length[e] - 1.0);
        edge = std::max(edge, eps);
        r.max_edge_strain_cell[k] = std::max(r.max_edge_strain_cell[k], eps);
      }
    }
    if (!std::isfinite(area_change) || area_change > 0.2) {
      r.diverged = true;
      r.diagnosis = "area change " + std::to_string(area_change) + " at step " + std::to_string(s);
      break;
    }
    r.max_area_change = std::max(r.max_area_change, area_change);
    r.max_edge_strain = std::max(r.max_edge_strain, edge);
    double D0, th_axis, D1 = 0, dummy;
    taylor_deformation(p[0], D0, th_axis);
    double theta_raw = th_axis, period = 180.0;
    double separation = 0, gap = 0, c0 = 0, c1 = 0, sig = 0, bow = 0, aspect = 0;
    if (p.size() == 2) {
      // Cell 1 next to cell 0 (minimum image in x; walls in y).
      const double shift = nx * std::round((cx[1] - cx[0]) / nx);
      for (double& x : p[1].x) x -= shift;
      cx[1] -= shift;
      taylor_deformation(p[1], D1, dummy);
      const double dx = cx[1] - cx[0], dy = cy[1] - cy[0];
      theta_raw = std::atan2(dy, dx) * 180.0 / kPi;  // thesis §III.2: line of centres vs horizontal
      period = 360.0;
      separation = std::hypot(dx, dy);
      gap = min_marker_gap(p[0], p[1]);
      // Contact area from the aggregation forces of the last step (1.2 % of the largest).
      if (s > 0) {
        const auto mag = agg->force_magnitude();
        c0 = aggregation::relative_contact_area(mag, offsets, 0);
        c1 = aggregation::relative_contact_area(mag, offsets, 1);
        const double fmax = *std::max_element(mag.begin(), mag.end());
        std::vector<char> flag(p[0].size(), 0);
        for (std::size_t m = 0; m < p[0].size(); ++m) flag[m] = fmax > 0 && mag[offsets[0] + m] > 0.012 * fmax;
        const ContactShape cs = contact_shape(p[0], flag, cx[0], cy[0],
                                              dx / separation, dy / separation);
        sig = cs.sigmoid * um;
        bow = cs.bow * um;
      }
      aspect = equivalent_ellipse(p).axis_ratio;
      if (!r.dissociated && gap > morse.cutoff) {  // no marker pair within reach: no Morse force left
        r.dissociated = true;
        r.dissociation_strain = strain;
      }
      if (strain >= 1.0 && !r.dissociated) r.min_contact_after1 = std::min(r.min_contact_after1, std::min(c0, c1));
    } else {
      aspect = equivalent_ellipse(p).axis_ratio;
    }
    if (s == 0) theta_unwrapped = theta_raw;
    else theta_unwrapped += wrap(theta_raw - theta_prev, period);
    theta_prev = theta_raw;
    // First crossings of 0, −90°, −180°, interpolated linearly between samples.
    auto crossing = [&](double level, double& t) {
      if (t >= 0 || theta_unwrapped > level) return;
      if (r.strain_h.empty()) { t = strain; return; }
      const double ta = r.strain_h.back(), qa = r.theta_h.back();
      t = qa > theta_unwrapped ? ta + (strain - ta) * (qa - level) / (qa - theta_unwrapped) : strain;
    };
    crossing(0.0, r.t_theta0);
    crossing(-90.0, r.t_theta_m90);
    crossing(-180.0, r.t_theta_m180);
    if (r.t_theta0 >= 0 && r.t_theta_m90 < 0) {
      aspect_sum += aspect;
      ++aspect_n;
    }
    r.strain_h.push_back(strain);
    r.theta_h.push_back(theta_unwrapped);
    r.contact0_h.push_back(c0);
    r.contact1_h.push_back(c1);
    r.separation_h.push_back(separation * um);
    r.gap_h.push_back(gap * um);
    r.D0_h.push_back(D0);
    r.D1_h.push_back(D1);
    r.sigmoid_h.push_back(sig);
    r.bow_h.push_back(bow);
    r.aspect_h.push_back(aspect);
    r.area_h.push_back(area_change);
    if (strain >= next_snap - 0.5 * gamma) {  // outlines every 2 strain units, NaN between cells
      std::vector<double> xs, ys;
      for (std::size_t k = 0; k < p.size(); ++k) {
        if (k > 0) {
          xs.push_back(std::nan(""));
          ys.push_back(std::nan(""));
        }
        for (std::size_t m = 0; m <= p[k].size(); ++m) {
          xs.push_back(p[k].x[m % p[k].size()] * um);
          ys.push_back(p[k].y[m % p[k].size()] * um);
        }
      }
      r.snap_strain.push_back(strain);
      r.snap_x.push_back(std::move(xs));
      r.snap_y.push_back(std::move(ys));
      next_snap += 2.0;
    }
    if (theta_unwrapped < c.stop_theta_deg) break;
    if (r.dissociated && strain >= r.dissociation_strain + c.stop_after_dissociation) break;
  }
  if (aspect_n > 0) r.aspect_quadrant = aspect_sum / aspect_n;
  if (!r.strain_h.empty()) r.strain = r.strain_h.back();
  if (!std::isfinite(r.min_contact_after1)) r.min_contact_after1 = 0;
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return r;
}

}  // namespace erythro::vv
