#pragma once
// The cell physics of a scene, one call per fluid step: the immersed-boundary cycle
// of membrane::ImmersedCells (thesis §II.3, eqs 23–25) with, when the scene asks for
// them, the interior viscosity of the index field (thesis §II.4, eqs 26–27) refreshed
// every k steps before the fluid step, and the Morse aggregation forces between cells
// (model.md §4) added to the membrane forces. Only what the scene declares is built.
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
  // advection.
  // Throws std::domain_error (non-finite marker) or interior::FillLeakError.
  void advance(fluid::FluidLattice& lattice, long step);

  const membrane::ImmersedCells& cells() const { return cells_; }
  // The index field, or nullptr when the interior has the fluid's viscosity.
  const interior::IndexField* index_field() const { return index_ ? &*index_ : nullptr; }
  // The aggregation, or nullptr; its statistics of the last step.
  const aggregation::MorseAggregation* aggregation() const { return aggregation_ ? &*aggregation_ : nullptr; }
  const aggregation::AggregationStats& aggregation_stats() const { return aggregation_stats_; }
  // Wall time spent so far rebuilding the index field and writing τ (s).
  double index_field_seconds() const { return index_seconds_; }

 private:
  void refresh_viscosity(fluid::FluidLattice& lattice);
  std::span<const membrane::Polygon> polygons_from_cells();

  membrane::ImmersedCells cells_;
  std::optional<interior::IndexField> index_;
  std::optional<aggregation::MorseAggregation> aggregation_;
  aggregation::AggregationStats aggregation_stats_;
  std::vector<membrane::Polygon> polygons_;  // scratch for the index field
  double nu_interior_ = 0.0, nu_exterior_ = 0.0;
  long index_interval_ = 1;
  double index_seconds_ = 0.0;
};

}  // namespace erythro::sim
