#pragma once
// Membranes immersed in the lattice fluid: the immersed-boundary cycle of the
// thesis (§II.3, eqs 23–25), one call per fluid step:
//
//   1. F_m = −∂E/∂X_m of every cell (membrane_energy.hpp)
//   2. f(x) = Σ_m F_m δ_h(x − X_m)  into the lattice force field (overwritten)
//   3. the fluid step (Guo forcing with f)
//   4. U_m = Σ_x u(x) δ_h(x − X_m), u of that step (ρu = Σcf* − f/2)
//   5. X_m ← X_m + U_m Δt (explicit Euler, Δt = 1)
//
// The markers of all cells live in one contiguous array (cell c owns the range
// offset(c) … offset(c) + size(c)), so one spreading pass serves every cell.
#include <span>
#include <vector>

#include "common/state_record.hpp"
#include "fluid/fluid_lattice.hpp"
#include "geometry/polygon.hpp"
#include "ib/transfer.hpp"
#include "membrane/membrane_energy.hpp"
#include "membrane/rest_shape.hpp"

namespace erythro::membrane {

class ImmersedCells {
 public:
  ImmersedCells(ib::KernelType kernel, const fluid::FluidLattice& lattice);

  // Adds a cell with markers at `shape` (lattice units) and the given rest shape
  // and moduli; returns its index. Invalidates spans previously returned.
  int add_cell(const geometry::Polygon& shape, const RestShape& rest, const MembraneModel& model);

  int cell_count() const { return static_cast<int>(cells_.size()); }
  std::size_t marker_count() const { return x_.size(); }
  std::size_t offset(int c) const { return cells_[c].offset; }
  std::size_t size(int c) const { return cells_[c].rest.size(); }
  const RestShape& rest(int c) const { return cells_[c].rest; }
  const MembraneModel& model(int c) const { return cells_[c].model; }

  // Marker positions, forces and velocities of cell c (or of all markers).
  std::span<const double> x(int c) const { return range(x_, c); }
  std::span<const double> y(int c) const { return range(y_, c); }
  std::span<const double> fx(int c) const { return range(fx_, c); }
  std::span<const double> fy(int c) const { return range(fy_, c); }
  std::span<const double> ux(int c) const { return range(ux_, c); }
  std::span<const double> uy(int c) const { return range(uy_, c); }
  std::span<double> marker_x() { return x_; }
  std::span<double> marker_y() { return y_; }
  std::span<double> marker_fx() { return fx_; }
  std::span<double> marker_fy() { return fy_; }
  geometry::Polygon polygon(int c) const;

  // Step 1: overwrites the marker forces with the internal membrane forces
  // (other forces, e.g. aggregation, may be added to marker_fx/fy afterwards).
  // Parallel over cells from kParallelCells cells on (threads_forces()), else one thread.
  void compute_forces();
  static constexpr int kParallelCells = 4;
  bool threads_forces() const { return cell_count() >= kParallelCells; }
  // Step 2: zeroes the lattice force field, then spreads the marker forces into it
  // (= clear_force_field + add_spread_forces).
  void spread_forces(fluid::FluidLattice& lattice);
  // Enables the lattice's force field and sets it to zero (grid work, O(nodes)).
  static void clear_force_field(fluid::FluidLattice& lattice);
  // Step 2 without the zeroing: ADDS the spread marker forces to the lattice force
  // field (which must be enabled). spread_forces() = zero the field + this. When the
  // supports cover the grid anyway (dense_supports()), it also asks the lattice to write
  // the velocity of its next step (FluidLattice::write_velocity_with_next_step), which
  // support_velocity() then takes as it is.
  void add_spread_forces(fluid::FluidLattice& lattice);
  // Steps 4–5 from the velocity of the last fluid step.
  void move_markers(std::span<const double> ux, std::span<const double> uy);
  // Velocity of the last fluid step into support_ux/uy() at the markers' kernel-support
  // nodes only (as FluidLattice::compute_moments, bit for bit; other entries are stale),
  // or on the whole grid when the supports would cover it anyway (there the velocity the
  // step wrote, its collisions' own u: docs/model.md eq 1.3b, the moments' up to
  // round-off; compute_moments if the step wrote none). Step 4 reads only
  // those nodes; advance() = forces, spread, step, this, move_markers(support_ux/uy).
  // Call right after lattice.step(), before its forces change (as compute_moments).
  void support_velocity(fluid::FluidLattice& lattice);
  // Whether the markers' W×W supports hold at least as many nodes as the grid: then the
  // velocity is computed everywhere rather than support by support.
  bool dense_supports() const;
  std::span<const double> support_ux() const { return grid_ux_; }
  std::span<const double> support_uy() const { return grid_uy_; }
  // Step 5 from the support velocity of the last fluid step: move_markers(support_ux/uy),
  // the area projection if it is on, then wrap_periodic.
  void advect_markers();
  // Steps 1–5 for one fluid step: compute_forces(), then advance_after_forces().
  void advance(fluid::FluidLattice& lattice);
  // Steps 2–5 with the marker forces as they are (compute_forces() plus whatever a caller
  // added, e.g. aggregation): spread_forces, the fluid step, support_velocity,
  // move_markers(support_ux/uy), wrap_periodic.
  void advance_after_forces(fluid::FluidLattice& lattice);
  // Shifts every cell whose marker 0 left [0, n) on a periodic axis back by ±n
  // (a rigid shift of the whole cell: its shape and forces are unchanged), so
  // unwrapped coordinates stay small over long runs. Called by advance().
  void wrap_periodic();

  // Area projection (docs/model.md eq 3.14): after every marker move each cell's polygon gets
  // its enclosed area at creation back (the immersed boundary's leakage no longer accumulates).
  // Off by default (membrane.area_correction).
  void set_area_projection(bool on) { area_projection_ = on; }
  bool area_projection() const { return area_projection_; }
  // The area the projection has given cell c back so far, summed over steps, over its target
  // (> 0: the membrane leaked fluid out); 0 without the projection.
  double restored_area_fraction(int c) const { return cells_[c].restored_area / cells_[c].target_area; }

  Energy energy(int c) const;
  double max_marker_speed() const;

  // Checkpoint (common/state_record.hpp), under `prefix`: per marker its position, force
  // and velocity; per cell its rest shape. Restoring needs the same cells and marker counts
  // (the cells of the same scene).
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);
  const ib::Transfer& transfer() const { return transfer_; }

 private:
  struct Cell {
    std::size_t offset;
    RestShape rest;
    MembraneModel model;
    double target_area = 0.0;    // signed area of the shape at creation (the projection's target)
    double restored_area = 0.0;  // Σ over steps of the area the projection added
  };
  void project_areas();
  std::span<const double> range(const std::vector<double>& v, int c) const {
    return {v.data() + cells_[c].offset, cells_[c].rest.size()};
  }
  std::span<double> range(std::vector<double>& v, int c) {
    return {v.data() + cells_[c].offset, cells_[c].rest.size()};
  }

  ib::Transfer transfer_;
  std::vector<Cell> cells_;
  std::vector<double> x_, y_, fx_, fy_, ux_, uy_;
  std::vector<double> rho_, grid_ux_, grid_uy_;  // scratch moments
  // support_velocity(), sparse supports: per node whether a support holds it, per row the
  // first and last such column and the rows that hold any (all 0, nx, −1 and empty between calls).
  std::vector<unsigned char> support_marked_;
  std::vector<int> row_first_, row_last_, support_rows_;
  bool area_projection_ = false;
};

}  // namespace erythro::membrane
