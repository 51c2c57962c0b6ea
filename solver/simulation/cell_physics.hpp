#pragma once
// The cell physics of a scene: the immersed-boundary cycle of membrane::ImmersedCells
// (thesis §II.3, eqs 23–25; docs/model.md §2) with, when the scene asks for them, the
// interior viscosity of the index field (thesis §II.4, eqs 26–27; docs/model.md §5)
// refreshed every k steps before the fluid step, and the forces between cells (Morse
// aggregation, docs/model.md §4; short-range repulsion, §4b) added to the membrane forces. Only what the scene
// declares is built. The cycle is a set of stages of the time loop around the fluid
// step (register_stages).
#include <memory>
#include <optional>
#include <vector>

#include "aggregation/cell_contacts.hpp"
#include "fluid/fluid_lattice.hpp"
#include "interior/index_field.hpp"
#include "membrane/immersed_cells.hpp"
#include "scene/units.hpp"
#include "simulation/faster_of_two.hpp"
#include "simulation/time_loop.hpp"

namespace erythro::sim {

class CellPhysics {
 public:
  // Places the cells of `setup` (stress-free at their initial shape, or pre-stressed over
  // their CellSetup::rest, each with its own membrane model) on `lattice`; with an interior viscosity, builds the index field and
  // writes the whole τ field once.
  CellPhysics(const scene::MembraneSetup& setup, double exterior_viscosity, fluid::FluidLattice& lattice);

  // The stages of one step n, around the fluid's own stage (Phase::fluid):
  //   forces       index_field        I → τ when n > 0 and n is a multiple of k
  //                membrane_forces    F_m = −∂E/∂X_m (membrane_energy.hpp)
  //                contact_forces     + forces between cells: Morse ([aggregation]) and
  //                                   repulsion ([repulsion]), one neighbour search
  //   spread       force_field_reset  f = 0 on the grid (rows marked cleared, zeroed where written)
  //                spreading          f += Σ_m F_m δ_h(x − X_m)
  //   interpolate  interpolation      u of the fluid step at the markers' support nodes
  //   advect       marker_advection   X_m += U_m, periodic wrap
  // On two or more OpenMP threads the index field's rebuild and the force stage are one stage,
  // "forces_and_index_field" (they are independent: positions read, τ and marker forces
  // written). On a rebuild step it runs them in one of two arrangements (IndexArrangement):
  // the rebuild beside the forces, each on one thread of a two-thread region, or the rebuild
  // before the forces, each on all threads (IndexField::update across cells). Both give the
  // same bits; by default each is measured and the faster kept (FasterOfTwo,
  // docs/performance-coupled-step.md, "The index field beside or before the forces, by measurement"). On one
  // thread the stages "index_field", "membrane_forces" and "contact_forces" run one after the
  // other. Stages throw std::domain_error (non-finite marker)
  // or interior::FillLeakError (a membrane tangled).
  void register_stages(TimeLoop& loop, fluid::FluidLattice& lattice);

  const membrane::ImmersedCells& cells() const { return cells_; }
  // The index field, or nullptr when the interior has the fluid's viscosity.
  const interior::IndexField* index_field() const { return index_ ? &*index_ : nullptr; }
  // The forces between cells (Morse aggregation and/or repulsion), or nullptr; their
  // statistics of the last step.
  const aggregation::CellContacts* contacts() const { return contacts_ ? &*contacts_ : nullptr; }
  const aggregation::ContactStats& contact_stats() const { return contact_stats_; }
  // Whether Morse aggregation acts (a doublet's pair probe needs it).
  bool aggregates() const { return contacts_ && contacts_->law().morse.has_value(); }
  // Wall time spent so far rebuilding the index field and writing τ (s), and the part of
  // it the step waited for: all of it when run alone; when run beside the force stage,
  // the time by which that two-thread region outlasted the force stage.
  double index_field_seconds() const { return index_seconds_; }
  double index_field_exposed_seconds() const { return index_exposed_seconds_; }
  // Whether the index field's rebuild and the force stage form one stage with two
  // arrangements (an index field and two or more OpenMP threads).
  bool index_with_forces() const;
  // The arrangement of a rebuild in that stage: measured (the default: the faster of the two,
  // FasterOfTwo), or one of them always (tests and benchmarks that compare them).
  enum class IndexArrangement { measured, beside_forces, before_forces };
  void set_index_arrangement(IndexArrangement a) { arrangement_ = a; }
  // How many rebuilds so far ran beside the force stage, and before it (the one at
  // construction not counted; on one thread every rebuild runs before the forces).
  long rebuilds_beside_forces() const { return rebuilds_beside_; }
  long rebuilds_before_forces() const { return rebuilds_before_; }
  // What the index field's rebuilds so far reported (the first, at construction, included).
  struct FillHistory {
    long updates = 0;                 // rebuilds of I (and τ)
    double max_area_mismatch = 0.0;   // max over rebuilds and cells of |Σ(1 − I) − A| (lattice units²)
    int max_fallback_cells = 0;       // max over rebuilds of cells filled by ray casting (flood fill)
  };
  const FillHistory& fill_history() const { return fill_history_; }

  // Checkpoint (common/state_record.hpp), under `prefix`: the cells, the index field and
  // the fill history (the τ field it wrote is the fluid's), the contact forces'
  // magnitudes and statistics of the last step (its forces are recomputed every step).
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  bool refresh_due(long step) const { return index_ && step > 0 && step % index_interval_ == 0; }
  void refresh_viscosity(fluid::FluidLattice& lattice);
  void record_fill(const interior::FillReport& report);
  void refresh_viscosity_timed(fluid::FluidLattice& lattice);
  void compute_marker_forces();  // membrane forces [+ contact forces]
  void add_contact_forces();
  void refresh_viscosity_beside_forces(fluid::FluidLattice& lattice);
  void refresh_viscosity_with_forces(fluid::FluidLattice& lattice);  // in the arrangement due
  std::span<const geometry::Polygon> polygons_from_cells();

  membrane::ImmersedCells cells_;
  std::optional<interior::IndexField> index_;
  std::optional<aggregation::CellContacts> contacts_;
  aggregation::ContactStats contact_stats_;
  std::vector<geometry::Polygon> polygons_;  // scratch for the index field
  double nu_interior_ = 0.0, nu_exterior_ = 0.0;
  long index_interval_ = 1;
  double index_seconds_ = 0.0, index_exposed_seconds_ = 0.0;
  IndexArrangement arrangement_ = IndexArrangement::measured;
  FasterOfTwo arrangement_times_;  // 0: beside the forces, 1: before them
  long rebuilds_beside_ = 0, rebuilds_before_ = 0;
  FillHistory fill_history_;
};

}  // namespace erythro::sim
