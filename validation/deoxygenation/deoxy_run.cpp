#include "deoxy_run.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <span>
#include <sstream>
#include <vector>

#include "common/case_support.hpp"
#include "common/error.hpp"
#include "deoxy_mask.hpp"
#include "geometry/grid_polygon.hpp"
#include "geometry/shapes.hpp"
#include "interior/index_field.hpp"
#include "transport/face_flux_correction.hpp"
#include "transport/transport_lattice.hpp"
#include "transport/transport_units.hpp"

namespace erythro::deoxy {

double diffusive_dt(double h_um, double dt_at_0p2_s) { return dt_at_0p2_s * (h_um / 0.2) * (h_um / 0.2); }

namespace {

struct Weighted {
  std::size_t node;
  double w;  // heme weight: φ (area fraction) or 1 (ray casting)
};

// Heme-weighted mean P = Σ w_n C_n / (α Σ w_n) (w = 1: transport::mean_partial_pressure).
double weighted_mean_P(const std::vector<Weighted>& cell, std::span<const double> C, double alpha, double w_sum) {
  double s = 0.0;
  for (const auto& c : cell) s += c.w * C[c.node];
  return s / (w_sum * alpha);
}

// Stops a diverging run with a diagnosis (step, time, node, quantity) instead of a curve of
// NaNs: the concentration must be finite and within [−C_ceiling/2, C_ceiling], S within [0, 1];
// face_gain (> 0 with the face-flux correction) is quoted in the diagnosis.
void check_bounded(const transport::TransportLattice& o2, const Grid& grid, long step, double t, double S,
                   double C_ceiling, double face_gain, const Setup& s) {
  auto fail = [&](const std::string& what) {
    std::ostringstream m;
    m << "deoxy::run diverged at step " << step << " (t = " << t << " s): " << what << "; h = " << s.h_um
      << " um, dt = " << s.dt_s * 1e6 << " us, D_in = " << s.D_in << ", D_out = " << s.D_out
      << " um^2/s, M = " << s.hb.M;
    if (face_gain > 0.0) m << ", face-flux correction lagged gain " << face_gain;
    throw std::runtime_error(m.str());
  };
  if (!(S >= 0.0 && S <= 1.0)) fail("cell saturation S = " + std::to_string(S) + " outside [0, 1]");
  const auto C = o2.concentration();
  for (int y = 0; y < grid.ny; ++y)
    for (int x = 0; x < grid.nx; ++x) {
      const double c = C[grid.index(x, y)];
      if (!(c >= -0.5 * C_ceiling && c <= C_ceiling))
        fail("concentration " + std::to_string(c) + " uM at node (" + std::to_string(x) + ", " + std::to_string(y) +
             ") outside [" + std::to_string(-0.5 * C_ceiling) + ", " + std::to_string(C_ceiling) + "]");
    }
}

}  // namespace

Result run(const Setup& s) {
  vv::Stopwatch clock;
  Result res;
  const int n = static_cast<int>(std::lround(2.0 * s.box_half_um / s.h_um));
  res.nodes = n;
  const Grid grid{n, n};
  const transport::TransportUnits units{s.h_um, s.dt_s};
  // Cell centred in the box; lattice units, node (i, j) at (i + ½, j + ½).
  const auto cell = geometry::transformed(geometry::biconcave(s.markers, s.a_um), 1.0 / s.h_um, 0.0,
                                          0.5 * n + s.offset_x_h, 0.5 * n + s.offset_y_h);
  res.polygon_area_um2 = std::abs(geometry::signed_area(cell)) * s.h_um * s.h_um;
  // The cell's nodes: area fractions φ (D, C0), heme weights of the release (heme) and of the
  // mean P (sample) (Setup::representation).
  std::vector<Weighted> mask, heme, sample;
  if (s.representation == Representation::ray_cast) {
    std::vector<std::size_t> nodes;
    geometry::ray_cast_inside_nodes(cell, geometry::Domain{grid, false, false}, nodes);
    for (std::size_t k : nodes) mask.push_back({k, 1.0});
    heme = mask;
  } else {
    const auto fractions = area_fractions(cell, n, n);
    for (const auto& f : fractions) mask.push_back({f.node, f.phi});
    heme = mask;
    if (s.representation != Representation::area_fraction) {
      std::vector<Weighted> moment;
      for (const auto& f : first_moment_weights(cell, n, n, fractions)) moment.push_back({f.node, f.phi});
      if (s.representation == Representation::area_fraction_moment) heme = moment;
      sample = moment;
    }
  }
  if (sample.empty()) sample = heme;
  if (heme.empty()) throw InputError("deoxy::run: no interior node (h too coarse)");
  double w_sum = 0.0;
  for (const auto& c : heme) w_sum += c.w;
  res.interior_nodes = static_cast<long>(heme.size());
  res.interior_area_um2 = w_sum * s.h_um * s.h_um;

  const transport::Side held{transport::SideKind::fixed_concentration, s.C_b_uM};
  transport::TransportLattice o2(grid, transport::Stencil::d2q5, {held, held, held, held});
  o2.set_collision(s.collision);
  o2.set_uniform_diffusivity(units.diffusivity(s.D_out));
  auto D = o2.diffusivity();
  std::vector<double> C0(grid.size(), s.C_b_uM);
  const double C0_in = s.C0_in_uM < 0.0 ? s.hb.alpha * s.P0_torr : s.C0_in_uM;
  for (const auto& c : mask) {
    // mixed node: series resistance 1/D = φ/D_in + (1 − φ)/D_out (eq T9, as reference_rbc.py);
    // cell in equilibrium at P0 over its area fraction, medium C_b over the rest
    D[c.node] = units.diffusivity(transport::series_diffusivity(c.w, s.D_in, s.D_out));
    C0[c.node] = c.w * C0_in + (1.0 - c.w) * s.C_b_uM;
  }
  if (s.link_diffusivity) {
    std::vector<double> R_phi(grid.size(), 1.0 / s.D_out);
    for (const auto& c : mask) R_phi[c.node] = c.w / s.D_in + (1.0 - c.w) / s.D_out;
    const auto R = link_resistivities(cell, n, n, s.D_in, s.D_out, R_phi);
    for (std::size_t k = 0; k < R.size(); ++k) D[k] = units.diffusivity(1.0 / R[k]);
  }
  if (s.interface != InterfaceRule::series && s.representation == Representation::ray_cast) {
    throw InputError("deoxy::run: the subpixel interface rules need area fractions");
  }
  // face subpixel tensor: the series lattice corrected towards the face targets (eq T11)
  std::unique_ptr<transport::FaceFluxCorrection> face_correction;
  if (s.interface == InterfaceRule::face_tensor) {
    face_correction = std::make_unique<transport::FaceFluxCorrection>(
        grid, D, transport::subpixel_face_targets(cell, n, n, units.diffusivity(s.D_in), units.diffusivity(s.D_out)));
    res.face_correction_gain = face_correction->lagged_gain(o2);
    face_correction->require_stable(o2);  // before running: a clear error, not a diverged curve
  }
  if (s.interface == InterfaceRule::node_tensor) {
    transport::set_node_subpixel_tensor(o2, transport::cut_cells(cell, n, n), units.diffusivity(s.D_in),
                                        units.diffusivity(s.D_out));
  }
  o2.initialize(C0);
  auto q = o2.source();
  double S = transport::hill_saturation(s.P0_torr, s.hb.P50, s.hb.n);
  const double S0 = S;
  const double M0 = o2.stored_amount();

  // at least t_end (a Δt that does not divide t_end overshoots by < Δt; never stops short of it)
  const long steps = static_cast<long>(std::ceil(s.t_end_s / s.dt_s - 1e-9));
  const long stride = std::max(1L, std::lround(2e-4 / s.dt_s));  // 0.2 ms samples after 2 ms
  res.S.t.push_back(0.0);
  res.S.y.push_back(S);
  double boundary_in = 0.0;
  double P_prev = 0.0, r_prev = 0.0;  // P^{k−1} and r^{k−1} (Torr) of the outflow predictor
  // Setup::source_corrected_P: the mean of Ĉ_n = C_n + c_n q_n / D_n (transport eq T7) is
  // P̄ + κ r, r = this step's release in Torr, κ = Σ c_n w_n w'_n / D_n / Σ w (lattice D; w, w':
  // sampling and release weights): the
  // offset responds to the step's own release, so it enters the implicit solve: P_end =
  // P^k − o^{k−1} + (1 + κ) r^k (C_heme scaled by 1 + κ in the solve only; the release itself
  // is C_heme ΔS).
  double kappa = 0.0;
  if (s.source_corrected_P) {
    std::vector<double> w_release(grid.size(), 0.0);
    for (const auto& c : heme) w_release[c.node] = c.w;
    for (const auto& c : sample) kappa += o2.source_offset_factor(c.node) * c.w * w_release[c.node];
    kappa /= w_sum;
  }
  // Divergence guard: C stays in [min(C_b, C0_in), max(C_b, C0_in)] (maximum principle: the
  // release only restores P towards what the heme held at P0); the bounds [−C_max, 2 C_max],
  // C_max = max(C_b, C0_in), catch a growing oscillation long before it is a NaN.
  const double C_ceiling = 2.0 * std::max(s.C_b_uM, C0_in);
  transport::HbParameters hb_end = s.hb;
  hb_end.C_heme *= 1.0 + kappa;
  for (long k = 1; k <= steps; ++k) {
    // eq H1/H2 with P the heme-weighted mean of the current C over the cell's nodes
    const double P = weighted_mean_P(sample, o2.concentration(), s.hb.alpha, w_sum);
    // Setup::coupling (deoxy_run.hpp): outflow of the last step o^{k−1} = P^{k−1} + r^{k−1} − P^k
    const double outflow = k == 1 ? 0.0 : P_prev + r_prev - P;
    double S_new = S;
    switch (s.coupling) {
      case Coupling::explicit_lagged: S_new = transport::advance_saturation(s.hb, S, P, s.dt_s).saturation; break;
      case Coupling::cell_implicit:
        S_new = transport::advance_saturation_cell_implicit(s.hb, S, P, s.dt_s).saturation;
        break;
      case Coupling::cell_implicit_outflow:
        S_new = transport::advance_saturation_cell_implicit(hb_end, S, std::max(0.0, P - outflow), s.dt_s).saturation;
        break;
    }
    const double released = s.hb.C_heme * (S - S_new);  // −C_heme ΔS, µM
    P_prev = P;
    r_prev = released / s.hb.alpha;
    S = S_new;
    if (face_correction) face_correction->evaluate(o2);  // from this step's Ĉ, before q is rewritten
    std::fill(q.begin(), q.end(), 0.0);
    for (const auto& c : heme) q[c.node] = c.w * released;  // µM per step = lattice source (w = 1:
                                                            // transport::distribute_release)
    if (face_correction) face_correction->add_to(q);
    o2.step();
    boundary_in += o2.mass_balance().boundary_in;
    res.max_step_residual = std::max(res.max_step_residual, std::abs(o2.mass_balance().relative_residual()));
    const double t = static_cast<double>(k) * s.dt_s;
    if (t <= 2e-3 + 1e-12 || k % stride == 0 || k == steps) {
      check_bounded(o2, grid, k, t, S, C_ceiling, res.face_correction_gain, s);
      res.S.t.push_back(t);
      res.S.y.push_back(S);
    }
  }
  res.steps = steps;
  const double area = s.h_um * s.h_um;  // lattice amount (µM per node) → µM·µm²
  res.released_uM_um2 = s.hb.C_heme * (S0 - S) * w_sum * area;
  res.medium_change_uM_um2 = (o2.stored_amount() - M0) * area;
  res.boundary_in_uM_um2 = boundary_in * area;
  res.balance_residual = (res.medium_change_uM_um2 - res.boundary_in_uM_um2 - res.released_uM_um2) / res.released_uM_um2;
  res.wall_s = clock.seconds();
  return res;
}

vv::Curve read_reference(const std::string& path, int column) {
  std::ifstream in(path);
  if (!in) throw InputError("deoxy: cannot read the reference curve " + path + " (reference_rbc.py --study)");
  vv::Curve c;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    if (static_cast<int>(v.size()) <= column) throw InputError("deoxy: short row in " + path);
    c.t.push_back(v[0]);
    c.y.push_back(v[static_cast<std::size_t>(column)]);
  }
  if (c.t.size() < 10) throw InputError("deoxy: too few rows in " + path);
  return c;
}

}  // namespace erythro::deoxy
