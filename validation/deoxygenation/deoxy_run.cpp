#include "deoxy_run.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "common/case_support.hpp"
#include "common/error.hpp"
#include "interior/index_field.hpp"
#include "membrane/shapes.hpp"
#include "transport/transport_lattice.hpp"
#include "transport/transport_units.hpp"

namespace erythro::deoxy {

double diffusive_dt(double h_um) { return 1e-5 * (h_um / 0.2) * (h_um / 0.2); }

Result run(const Setup& s) {
  vv::Stopwatch clock;
  Result res;
  const int n = static_cast<int>(std::lround(2.0 * s.box_half_um / s.h_um));
  res.nodes = n;
  const Grid grid{n, n};
  const transport::TransportUnits units{s.h_um, s.dt_s};
  // Cell centred in the box; lattice units, node (i, j) at (i + ½, j + ½).
  const auto cell = membrane::transformed(membrane::biconcave(s.markers, s.a_um), 1.0 / s.h_um, 0.0, 0.5 * n, 0.5 * n);
  std::vector<std::size_t> nodes;
  interior::ray_cast_inside_nodes(cell, ib::Domain{grid, false, false}, nodes);
  if (nodes.empty()) throw InputError("deoxy::run: no interior node (h too coarse)");
  res.interior_nodes = static_cast<long>(nodes.size());
  res.interior_area_um2 = static_cast<double>(nodes.size()) * s.h_um * s.h_um;

  const transport::Side held{transport::SideKind::fixed_concentration, s.C_b_uM};
  transport::TransportLattice o2(grid, transport::Stencil::d2q5, {held, held, held, held});
  o2.set_uniform_diffusivity(units.diffusivity(s.D_out));
  auto D = o2.diffusivity();
  std::vector<double> C0(grid.size(), s.C_b_uM);
  for (std::size_t k : nodes) {
    D[k] = units.diffusivity(s.D_in);
    C0[k] = s.hb.alpha * s.P0_torr;  // cell in equilibrium at P0
  }
  o2.initialize(C0);
  auto q = o2.source();
  double S = transport::hill_saturation(s.P0_torr, s.hb.P50, s.hb.n);
  const double S0 = S;
  const double M0 = o2.stored_amount();
  const double cell_nodes = static_cast<double>(nodes.size());

  const long steps = std::lround(s.t_end_s / s.dt_s);
  const long stride = std::max(1L, std::lround(2e-4 / s.dt_s));  // 0.2 ms samples after 2 ms
  res.S.t.push_back(0.0);
  res.S.y.push_back(S);
  double boundary_in = 0.0;
  for (long k = 1; k <= steps; ++k) {
    // eq H1/H2 with P the mean over the interior nodes of the current C (explicit coupling)
    const double P = transport::mean_partial_pressure(nodes, o2.concentration(), s.hb.alpha);
    // Setup::implicit_coupling: the layer's cell-implicit update (eq H3), else the lagged P.
    const double S_new = s.implicit_coupling ? transport::advance_saturation_cell_implicit(s.hb, S, P, s.dt_s).saturation
                                             : transport::advance_saturation(s.hb, S, P, s.dt_s).saturation;
    const double released = s.hb.C_heme * (S - S_new);  // −C_heme ΔS, µM
    S = S_new;
    std::fill(q.begin(), q.end(), 0.0);
    transport::distribute_release(nodes, released, q);  // µM per step = lattice source
    o2.step();
    boundary_in += o2.mass_balance().boundary_in;
    res.max_step_residual = std::max(res.max_step_residual, std::abs(o2.mass_balance().relative_residual()));
    const double t = static_cast<double>(k) * s.dt_s;
    if (t <= 2e-3 + 1e-12 || k % stride == 0 || k == steps) {
      res.S.t.push_back(t);
      res.S.y.push_back(S);
    }
  }
  res.steps = steps;
  const double area = s.h_um * s.h_um;  // lattice amount (µM per node) → µM·µm²
  res.released_uM_um2 = s.hb.C_heme * (S0 - S) * cell_nodes * area;
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
