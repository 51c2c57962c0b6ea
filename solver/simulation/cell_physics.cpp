#include "simulation/cell_physics.hpp"

#include <algorithm>
#include <chrono>
#include <exception>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace erythro::sim {

CellPhysics::CellPhysics(const scene::MembraneSetup& setup, double exterior_viscosity, fluid::FluidLattice& lattice)
    : cells_(setup.kernel, lattice),
      nu_interior_(setup.interior_viscosity),
      nu_exterior_(exterior_viscosity),
      index_interval_(std::max(1L, setup.index_update_interval)) {
  for (const scene::CellSetup& c : setup.cells)
    cells_.add_cell(c.shape, membrane::RestShape::from_polygon(c.rest.size() != 0 ? c.rest : c.shape), c.model);
  cells_.set_area_projection(setup.area_projection);
  if (setup.aggregation || setup.repulsion)
    contacts_.emplace(fluid::domain_of(lattice.grid(), lattice.boundaries()),
                      aggregation::ContactLaw{setup.aggregation, setup.repulsion});
  if (setup.indicator != interior::Method::indexless) {
    index_.emplace(fluid::domain_of(lattice.grid(), lattice.boundaries()), interior::IndexFieldOptions{setup.indicator});
    polygons_.resize(static_cast<std::size_t>(cells_.cell_count()));
    lattice.enable_tau_field();
    record_fill(index_->update(polygons_from_cells()));
    index_->write_relaxation_times(lattice.tau_field(), nu_interior_, nu_exterior_);  // every node once
    lattice.refresh_tau_rows();
  }
}

std::span<const geometry::Polygon> CellPhysics::polygons_from_cells() {
  for (int c = 0; c < cells_.cell_count(); ++c) {
    geometry::Polygon& p = polygons_[static_cast<std::size_t>(c)];
    p.x.assign(cells_.x(c).begin(), cells_.x(c).end());  // capacity kept: no allocation after the first step
    p.y.assign(cells_.y(c).begin(), cells_.y(c).end());
  }
  return polygons_;
}

void CellPhysics::record_fill(const interior::FillReport& report) {
  ++fill_history_.updates;
  fill_history_.max_area_mismatch = std::max(fill_history_.max_area_mismatch, report.max_area_mismatch);
  fill_history_.max_fallback_cells = std::max(fill_history_.max_fallback_cells, report.fallback_cells);
}

void CellPhysics::refresh_viscosity(fluid::FluidLattice& lattice) {
  record_fill(index_->update(polygons_from_cells()));
  // Eq 27: τ(x) = ½ + 3[ν_in + (ν_ex − ν_in) I(x)], rewritten only where I changed.
  index_->write_changed_relaxation_times(lattice.tau_field(), nu_interior_, nu_exterior_);
  lattice.refresh_tau_rows();  // the rows of one τ collide at the cost of a plain row
}

void CellPhysics::refresh_viscosity_timed(fluid::FluidLattice& lattice) {
  const auto start = std::chrono::steady_clock::now();
  refresh_viscosity(lattice);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  index_seconds_ += s;
  index_exposed_seconds_ += s;
}

void CellPhysics::add_contact_forces() {
  if (contacts_) contact_stats_ = contacts_->add_forces(cells_);
}

void CellPhysics::compute_marker_forces() {
  cells_.compute_forces();
  add_contact_forces();
}

bool CellPhysics::index_with_forces() const {
#if defined(_OPENMP)
  return index_.has_value() && omp_get_max_threads() >= 2;
#else
  return false;
#endif
}

void CellPhysics::refresh_viscosity_with_forces(fluid::FluidLattice& lattice) {
  // Beside the forces, the rebuild's threads do not help the forces and the forces' threads
  // do not help the rebuild; before them, each uses every thread but the rebuild's serial
  // parts (its fills) leave the others waiting. Which costs less depends on the host, the
  // cells and k, so by default both are measured (docs/performance-coupled-step.md).
  // A caller that has lowered the thread count to one since the stages were registered (the
  // bench's --alternate-threads) gets the one-thread arrangement, before the forces, unmeasured.
  constexpr int kBeside = 0, kBefore = 1;
#if defined(_OPENMP)
  const bool alone = omp_get_max_threads() < 2;
#else
  const bool alone = true;
#endif
  const bool beside = !alone && (arrangement_ == IndexArrangement::beside_forces ||
                                 (arrangement_ == IndexArrangement::measured && arrangement_times_.next() == kBeside));
  const auto start = std::chrono::steady_clock::now();
  if (beside) {
    refresh_viscosity_beside_forces(lattice);
    ++rebuilds_beside_;
  } else {
    refresh_viscosity_timed(lattice);
    compute_marker_forces();
    ++rebuilds_before_;
  }
  if (arrangement_ == IndexArrangement::measured && !alone)
    arrangement_times_.record(beside ? kBeside : kBefore,
                              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

void CellPhysics::refresh_viscosity_beside_forces(fluid::FluidLattice& lattice) {
  using clock = std::chrono::steady_clock;
  // The index field reads the marker positions and writes τ; the force stage reads the
  // positions and writes the marker forces: independent, so they run side by side, and
  // each gives the same bits as when run one after the other. An exception cannot leave
  // an OpenMP section: each section keeps its own, rethrown in serial order afterwards.
  std::exception_ptr index_error, forces_error;
  double index_s = 0.0, forces_s = 0.0;
  const auto start = clock::now();
#pragma omp parallel sections num_threads(2)
  {
#pragma omp section
    {
      try {
        refresh_viscosity(lattice);
      } catch (...) {
        index_error = std::current_exception();
      }
      index_s = std::chrono::duration<double>(clock::now() - start).count();
    }
#pragma omp section
    {
      const auto forces_start = clock::now();
      try {
        compute_marker_forces();
      } catch (...) {
        forces_error = std::current_exception();
      }
      forces_s = std::chrono::duration<double>(clock::now() - forces_start).count();
    }
  }
  const double region_s = std::chrono::duration<double>(clock::now() - start).count();
  index_seconds_ += index_s;
  index_exposed_seconds_ += std::max(0.0, region_s - forces_s);  // what the region added to the force stage
  if (index_error) std::rethrow_exception(index_error);
  if (forces_error) std::rethrow_exception(forces_error);
}

void CellPhysics::save_state(StateRecord& r, const std::string& prefix) const {
  cells_.save_state(r, prefix + "markers.");
  if (index_) index_->save_state(r, prefix + "index_field.");
  if (contacts_) {  // under "aggregation.", the name of the layer before it also repelled
    contacts_->save_state(r, prefix + "aggregation.");
    const aggregation::ContactStats& a = contact_stats_;
    r.put(prefix + "aggregation.stats", std::vector<double>{static_cast<double>(a.pairs), a.energy, a.max_force});
    if (contacts_->law().repulsion)
      r.put(prefix + "aggregation.closest", std::vector<double>{static_cast<double>(a.wall_markers),
                                                               a.min_pair_distance, a.min_wall_distance});
  }
  r.put(prefix + "fill_history", std::vector<double>{static_cast<double>(fill_history_.updates),
                                                     fill_history_.max_area_mismatch,
                                                     static_cast<double>(fill_history_.max_fallback_cells)});
}

void CellPhysics::restore_state(const StateRecord& r, const std::string& prefix) {
  cells_.restore_state(r, prefix + "markers.");
  if (index_) index_->restore_state(r, prefix + "index_field.");
  if (contacts_) {
    contacts_->restore_state(r, prefix + "aggregation.");
    const std::vector<double>& a = r.get(prefix + "aggregation.stats", 3);
    contact_stats_ = aggregation::ContactStats{};
    contact_stats_.pairs = static_cast<std::size_t>(a[0]);
    contact_stats_.energy = a[1];
    contact_stats_.max_force = a[2];
    if (contacts_->law().repulsion) {
      const std::vector<double>& c = r.get(prefix + "aggregation.closest", 3);
      contact_stats_.wall_markers = static_cast<std::size_t>(c[0]);
      contact_stats_.min_pair_distance = c[1];
      contact_stats_.min_wall_distance = c[2];
    }
  }
  const std::vector<double>& h = r.get(prefix + "fill_history", 3);
  fill_history_ = {static_cast<long>(h[0]), h[1], static_cast<int>(h[2])};
}

void CellPhysics::register_stages(TimeLoop& loop, fluid::FluidLattice& lattice) {
  if (index_with_forces()) {
    loop.add(Phase::forces, "forces_and_index_field", [this, &lattice](long step) {
      if (refresh_due(step))
        refresh_viscosity_with_forces(lattice);
      else
        compute_marker_forces();
    });
  } else {
    if (index_)
      loop.add(
          Phase::forces, "index_field",
          [this, &lattice](long) {
            refresh_viscosity_timed(lattice);
            ++rebuilds_before_;
          },
          index_interval_, index_interval_);
    loop.add(Phase::forces, "membrane_forces", [this](long) { cells_.compute_forces(); });
    if (contacts_) loop.add(Phase::forces, "contact_forces", [this](long) { add_contact_forces(); });
  }
  // The lattice's uniform (body) force is added to this field by the fluid step.
  loop.add(Phase::spread, "force_field_reset", [&lattice](long) { membrane::ImmersedCells::clear_force_field(lattice); });
  loop.add(Phase::spread, "spreading", [this, &lattice](long) { cells_.add_spread_forces(lattice); });
  // Right after the fluid step, before its forces change (ImmersedCells::support_velocity).
  loop.add(Phase::interpolate, "interpolation", [this, &lattice](long) { cells_.support_velocity(lattice); });
  loop.add(Phase::advect, "marker_advection", [this](long) { cells_.advect_markers(); });
}

}  // namespace erythro::sim
