#include "simulation/cell_physics.hpp"

#include <algorithm>
#include <chrono>

namespace erythro::sim {

CellPhysics::CellPhysics(const scene::MembraneSetup& setup, double exterior_viscosity, fluid::FluidLattice& lattice)
    : cells_(setup.kernel, lattice),
      nu_interior_(setup.interior_viscosity),
      nu_exterior_(exterior_viscosity),
      index_interval_(std::max(1L, setup.index_update_interval)) {
  for (const scene::CellSetup& c : setup.cells)
    cells_.add_cell(c.shape, membrane::RestShape::from_polygon(c.shape), setup.model);
  if (setup.aggregation)
    aggregation_.emplace(ib::Domain::from(lattice.grid(), lattice.boundaries()), *setup.aggregation);
  if (setup.indicator != interior::Method::indexless) {
    index_.emplace(ib::Domain::from(lattice.grid(), lattice.boundaries()), interior::IndexFieldOptions{setup.indicator});
    polygons_.resize(static_cast<std::size_t>(cells_.cell_count()));
    lattice.enable_tau_field();
    index_->update(polygons_from_cells());
    index_->write_relaxation_times(lattice.tau_field(), nu_interior_, nu_exterior_);  // every node once
  }
}

std::span<const membrane::Polygon> CellPhysics::polygons_from_cells() {
  for (int c = 0; c < cells_.cell_count(); ++c) {
    membrane::Polygon& p = polygons_[static_cast<std::size_t>(c)];
    p.x.assign(cells_.x(c).begin(), cells_.x(c).end());  // capacity kept: no allocation after the first step
    p.y.assign(cells_.y(c).begin(), cells_.y(c).end());
  }
  return polygons_;
}

void CellPhysics::refresh_viscosity(fluid::FluidLattice& lattice) {
  const auto start = std::chrono::steady_clock::now();
  index_->update(polygons_from_cells());
  // Eq 27: τ(x) = ½ + 3[ν_in + (ν_ex − ν_in) I(x)], rewritten only where I changed.
  index_->write_changed_relaxation_times(lattice.tau_field(), nu_interior_, nu_exterior_);
  index_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void CellPhysics::advance(fluid::FluidLattice& lattice, long step) {
  if (index_ && step > 0 && step % index_interval_ == 0) refresh_viscosity(lattice);
  if (!aggregation_) {
    cells_.advance(lattice);
    return;
  }
  // ImmersedCells::advance with the aggregation forces added to the membrane forces.
  cells_.compute_forces();
  aggregation_stats_ = aggregation_->add_forces(cells_);
  cells_.spread_forces(lattice);
  lattice.step();
  cells_.support_velocity(lattice);
  cells_.move_markers(cells_.support_ux(), cells_.support_uy());
  cells_.wrap_periodic();
}

}  // namespace erythro::sim
