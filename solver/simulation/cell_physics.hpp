#pragma once
// The cell physics of a scene, one call per fluid step: the immersed-boundary cycle
// of membrane::ImmersedCells (thesis §II.3, eqs 23–25) with, when the scene asks for
// them, the interior viscosity of the index field (thesis §II.4, eqs 26–27) refreshed
// every k steps before the fluid step, and the Morse aggregation forces between cells
// (docs/model.md §4) added to the membrane forces. Only what the scene declares is built.
#include <memory>
#include <optional>
#include <vector>

#include "aggregation/morse_aggregation.hpp"
#include "fluid/fluid_lattice.hpp"
#include "interior/index_field.hpp"
#include "membrane/immersed_cells.hpp"
#include "scene/units.hpp"

namespace erythro::sim {

class CellPhysics {
 public:
  // Places the cells of `setup` (stress-free at their initial shape) on `lattice`.
  CellPhysics(const scene::MembraneSetup& setup, double exterior_viscosity, fluid::FluidLattice& lattice);

  // One step: [index field → τ every k steps], membrane forces [+ aggregation],
  // spreading (the lattice's uniform force adds to the field), fluid step, marker
  // advection. On two or more threads, when the force stage runs on one thread (fewer
  // than ImmersedCells::kParallelCells cells and MorseAggregation::kParallelMarkers
  // markers), the index field is rebuilt on a second thread beside the force stage
  // (independent: same results). docs/performance.md, "Index field".
  // Throws std::domain_error (non-finite marker) or interior::FillLeakError.
  void advance(fluid::FluidLattice& lattice, long step);

  const membrane::ImmersedCells& cells() const { return cells_; }
  // The index field, or nullptr when the interior has the fluid's viscosity.
  const interior::IndexField* index_field() const { return index_ ? &*index_ : nullptr; }
  // The aggregation, or nullptr; its statistics of the last step.
  const aggregation::MorseAggregation* aggregation() const { return aggregation_ ? &*aggregation_ : nullptr; }
  const aggregation::AggregationStats& aggregation_stats() const { return aggregation_stats_; }
  // Wall time spent so far rebuilding the index field and writing τ (s), and the part of
  // it the step waited for: all of it when run alone; when run beside the force stage,
  // the time by which that two-thread region outlasted the force stage.
  double index_field_seconds() const { return index_seconds_; }
  double index_field_exposed_seconds() const { return index_exposed_seconds_; }
  // Whether advance() rebuilds the index field beside the force stage (two or more
  // OpenMP threads and a force stage that runs on one).
  bool index_beside_forces() const;

 private:
  void refresh_viscosity(fluid::FluidLattice& lattice);
  void compute_marker_forces();  // membrane forces [+ aggregation]
  void refresh_viscosity_beside_forces(fluid::FluidLattice& lattice);
  std::span<const geometry::Polygon> polygons_from_cells();

  membrane::ImmersedCells cells_;
  std::optional<interior::IndexField> index_;
  std::optional<aggregation::MorseAggregation> aggregation_;
  aggregation::AggregationStats aggregation_stats_;
  std::vector<geometry::Polygon> polygons_;  // scratch for the index field
  double nu_interior_ = 0.0, nu_exterior_ = 0.0;
  long index_interval_ = 1;
  double index_seconds_ = 0.0, index_exposed_seconds_ = 0.0;
};

}  // namespace erythro::sim
