#include "simulation/transport_physics.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/grid_polygon.hpp"
#include "interior/index_field.hpp"
#include "transport/hb_kinetics.hpp"

namespace erythro::sim {

TransportPhysics::TransportPhysics(const scene::TransportSetup& setup, const geometry::Domain& domain,
                                   std::span<const geometry::Polygon> cells)
    : setup_(setup), domain_(domain) {
  lattices_.reserve(setup_.species.size());
  for (const scene::SpeciesSetup& sp : setup_.species) {
    lattices_.emplace_back(domain_.grid, setup_.stencil, sp.boundaries);
    lattices_.back().set_uniform_diffusivity(sp.diffusivity);
  }
  place_cells(cells);
  // Initial state: the medium's concentration outside, the cells' inside.
  const std::size_t N = domain_.grid.size();
  for (std::size_t i = 0; i < lattices_.size(); ++i) {
    std::vector<double> c(N, setup_.species[i].initial);
    for (const auto& nodes : interior_)
      for (std::size_t n : nodes) c[n] = setup_.species[i].cell_initial;
    lattices_[i].initialize(c);
  }
  if (setup_.hemoglobin) {
    // Each cell starts at the given saturation, or in equilibrium with its initial PO2.
    const transport::HbParameters& hb = *setup_.hemoglobin;
    const double P0 = setup_.species[setup_.hemoglobin_species].cell_initial / hb.alpha;
    saturation_.assign(interior_.size(), setup_.initial_saturation.value_or(transport::hill_saturation(P0, hb.P50, hb.n)));
  }
}

void TransportPhysics::place_cells(std::span<const geometry::Polygon> cells) {
  interior_.resize(cells.size());  // the lists keep their capacity from one call to the next
  for (std::size_t c = 0; c < cells.size(); ++c)
    // Interior = nodes whose centre lies inside the membrane polygon (even–odd rule).
    geometry::ray_cast_inside_nodes(cells[c], domain_, interior_[c]);
  apply_compartments();
}

void TransportPhysics::apply_compartments() {
  for (std::size_t i = 0; i < lattices_.size(); ++i) {
    const scene::SpeciesSetup& sp = setup_.species[i];
    if (sp.cell_diffusivity == sp.diffusivity) continue;  // one diffusivity: no field needed
    std::span<double> D = lattices_[i].diffusivity();
    std::fill(D.begin(), D.end(), sp.diffusivity);
    for (const auto& nodes : interior_)
      for (std::size_t n : nodes) D[n] = sp.cell_diffusivity;
  }
}

// Hb–O2 release (docs/transport.md §4.2, eqs H1–H3): per cell, the cell-implicit update
// of the cell-averaged saturation over Δt_T from the mean PO2 over its interior (stable
// for any Δt_T: the release's own feedback on P is implicit); the O2 released,
// C_heme (S_old − S_new), is the source of this step on every interior node.
void TransportPhysics::release_oxygen() {
  transport::TransportLattice& o2 = lattices_[static_cast<std::size_t>(setup_.hemoglobin_species)];
  std::span<double> q = o2.source();
  std::fill(q.begin(), q.end(), 0.0);
  const transport::HbParameters& hb = *setup_.hemoglobin;
  for (std::size_t c = 0; c < interior_.size(); ++c) {
    if (interior_[c].empty()) continue;
    const double P = transport::mean_partial_pressure(interior_[c], o2.concentration(), hb.alpha);
    const transport::HbStep r = transport::advance_saturation_cell_implicit(hb, saturation_[c], P, setup_.time_step_s);
    saturation_[c] = r.saturation;
    transport::distribute_release(interior_[c], r.released, q);
  }
}

void TransportPhysics::step(std::span<const double> fluid_ux, std::span<const double> fluid_uy) {
  if (setup_.hemoglobin) release_oxygen();
  const bool flow = !fluid_ux.empty();
  if (flow) {
    // u_T = u_F Δt_T/Δt_F (both in their own lattice units, same h).
    ux_.resize(fluid_ux.size());
    uy_.resize(fluid_uy.size());
    for (std::size_t n = 0; n < ux_.size(); ++n) {
      ux_[n] = fluid_ux[n] * setup_.velocity_scale;
      uy_[n] = fluid_uy[n] * setup_.velocity_scale;
    }
  }
  for (transport::TransportLattice& lat : lattices_) {
    if (flow) lat.set_velocity(ux_, uy_);
    lat.step();
  }
}

double TransportPhysics::max_relative_residual() const {
  double r = 0.0;
  for (const auto& lat : lattices_) r = std::max(r, std::abs(lat.mass_balance().relative_residual()));
  return r;
}

HealthReport TransportPhysics::check_health() const {
  for (std::size_t i = 0; i < lattices_.size(); ++i) {
    HealthReport h = lattices_[i].check_health();
    if (!h.healthy) {
      h.quantity = setup_.species[i].name + " " + h.quantity;
      return h;
    }
  }
  return {};
}

}  // namespace erythro::sim
