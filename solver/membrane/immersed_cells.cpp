#include "membrane/immersed_cells.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "common/chunk_stealing.hpp"
#include "common/portable_hypot.hpp"
#include "geometry/grid_polygon.hpp"
#include "geometry/polygon.hpp"
#include "lattice/d2q9.hpp"
#include "membrane/area_projection.hpp"

namespace erythro::membrane {

ImmersedCells::ImmersedCells(ib::KernelType kernel, const fluid::FluidLattice& lattice)
    : transfer_(kernel, fluid::domain_of(lattice.grid(), lattice.boundaries())) {}

int ImmersedCells::add_cell(const geometry::Polygon& shape, const RestShape& rest, const MembraneModel& model) {
  if (shape.size() != rest.size()) {
    throw std::invalid_argument("ImmersedCells::add_cell: the shape and the rest shape differ in marker count");
  }
  cells_.push_back({x_.size(), rest, model, geometry::signed_area(shape), 0.0});
  x_.insert(x_.end(), shape.x.begin(), shape.x.end());
  y_.insert(y_.end(), shape.y.begin(), shape.y.end());
  fx_.resize(x_.size(), 0.0);
  fy_.resize(x_.size(), 0.0);
  ux_.resize(x_.size(), 0.0);
  uy_.resize(x_.size(), 0.0);
  return cell_count() - 1;
}

geometry::Polygon ImmersedCells::polygon(int c) const {
  geometry::Polygon p;
  p.x.assign(x(c).begin(), x(c).end());
  p.y.assign(y(c).begin(), y(c).end());
  return p;
}

void ImmersedCells::compute_forces() {
  const int n = cell_count();
  // Cells own disjoint marker ranges (together every marker): parallel over cells is race-free
  // and deterministic. Each thread starts on its own share of neighbouring cells, the same
  // cells' markers in every step (faster than a dynamic schedule in the bench's box of like
  // cells: docs/performance-coupled-step.md, "The threads' shares of the cell work"), and takes the last
  // cells of a slower thread's share (common/chunk_stealing.hpp).
  parallel::for_each_chunk(n, threads_forces() ? omp_get_max_threads() : 1, [&](long q) {
    const int c = static_cast<int>(q);
    const std::span<double> fx = range(fx_, c), fy = range(fy_, c);
    std::fill(fx.begin(), fx.end(), 0.0);
    std::fill(fy.begin(), fy.end(), 0.0);
    add_membrane_forces_only(cells_[c].model, cells_[c].rest, x(c), y(c), fx, fy);
  });
}

void ImmersedCells::clear_force_field(fluid::FluidLattice& lattice) { lattice.clear_force_field(); }

void ImmersedCells::spread_forces(fluid::FluidLattice& lattice) {
  clear_force_field(lattice);
  add_spread_forces(lattice);
}

void ImmersedCells::add_spread_forces(fluid::FluidLattice& lattice) {
  const fluid::FluidLattice::ForceRowsWriter field = lattice.force_rows_writer();
  transfer_.spread(x_, y_, fx_, fy_, field.fx, field.fy, field.rows);
  if (dense_supports()) {  // the next step writes the velocity support_velocity() needs
    const std::size_t N = transfer_.domain().grid.size();
    grid_ux_.resize(N);
    grid_uy_.resize(N);
    lattice.write_velocity_with_next_step(grid_ux_, grid_uy_);
  }
}

bool ImmersedCells::dense_supports() const {
  const int W = ib::width(transfer_.kernel());
  return x_.size() * static_cast<std::size_t>(W * W) >= transfer_.domain().grid.size();
}

void ImmersedCells::move_markers(std::span<const double> ux, std::span<const double> uy) {
  transfer_.interpolate(x_, y_, ux, uy, ux_, uy_);
  ib::advance_markers(x_, y_, ux_, uy_);
}

void ImmersedCells::advance(fluid::FluidLattice& lattice) {
  compute_forces();
  advance_after_forces(lattice);
}

void ImmersedCells::advance_after_forces(fluid::FluidLattice& lattice) {
  spread_forces(lattice);
  lattice.step();
  support_velocity(lattice);  // force field still that of this step
  advect_markers();
}

void ImmersedCells::advect_markers() {
  move_markers(grid_ux_, grid_uy_);
  if (area_projection_) project_areas();
  wrap_periodic();
}

void ImmersedCells::project_areas() {  // eq 3.14; each cell its own markers: any thread count, the same bits
  const int n = cell_count();
  parallel::for_each_chunk(n, threads_forces() ? omp_get_max_threads() : 1, [&](long q) {
    const int c = static_cast<int>(q);
    cells_[c].restored_area += project_area(range(x_, c), range(y_, c), cells_[c].target_area);
  });
}

void ImmersedCells::support_velocity(fluid::FluidLattice& lattice) {
  const geometry::Domain& d = transfer_.domain();
  const std::size_t N = d.grid.size();
  grid_ux_.resize(N);
  grid_uy_.resize(N);
  const int W = ib::width(transfer_.kernel());
  if (dense_supports()) {  // dense markers: the whole grid is cheaper
    if (lattice.last_step_wrote_velocity(grid_ux_.data())) return;  // written by the step (add_spread_forces)
    rho_.resize(N);
    lattice.compute_moments(rho_, grid_ux_, grid_uy_);
    return;
  }
  // Only the nodes Transfer::interpolate reads (ib/transfer.cpp): the W×W support of each
  // marker, wrapped across periodic sides, clipped at walls. Each is marked once (neighbouring
  // markers' supports overlap many times), then the rows' runs of marked nodes are computed
  // (FluidLattice::span_moments: compute_moments' operations on those nodes, so the same bits;
  // its vector loop, where node by node took 5–7 % of a doublet run). A non-finite marker is left
  // to interpolate(), which reports it.
  const int nx = d.grid.nx, ny = d.grid.ny;
  support_marked_.resize(N, 0);
  row_first_.resize(static_cast<std::size_t>(ny), nx);
  row_last_.resize(static_cast<std::size_t>(ny), -1);
  const auto wrap = geometry::wrap_periodic;
  for (std::size_t m = 0; m < x_.size(); ++m) {
    if (!std::isfinite(x_[m]) || !std::isfinite(y_[m])) continue;
    const int i0 = ib::support_start(x_[m], W), j0 = ib::support_start(y_[m], W);
    for (int a = 0; a < W; ++a) {
      int j = j0 + a;
      if (d.periodic_y)
        j = wrap(j, ny);
      else if (j < 0 || j >= ny)
        continue;
      const auto row = static_cast<std::size_t>(j);
      if (row_last_[row] < 0) support_rows_.push_back(j);
      for (int b = 0; b < W; ++b) {
        int i = i0 + b;
        if (d.periodic_x)
          i = wrap(i, nx);
        else if (i < 0 || i >= nx)
          continue;
        support_marked_[d.grid.index(i, j)] = 1;
        row_first_[row] = std::min(row_first_[row], i);
        row_last_[row] = std::max(row_last_[row], i);
      }
    }
  }
  rho_.resize(N);
  for (const int j : support_rows_) {  // each row's nodes are its own: any order, the same values
    const auto row = static_cast<std::size_t>(j);
    unsigned char* marked = support_marked_.data() + d.grid.index(0, j);
    for (int x = row_first_[row]; x <= row_last_[row];) {
      if (marked[x] == 0) {
        ++x;
        continue;
      }
      const int run = x;
      while (x <= row_last_[row] && marked[x] != 0) marked[x++] = 0;  // left all 0 for the next call
      lattice.span_moments(j, run, x, rho_, grid_ux_, grid_uy_);
    }
    row_first_[row] = nx;
    row_last_[row] = -1;
  }
  support_rows_.clear();
}

void ImmersedCells::wrap_periodic() {
  const geometry::Domain& d = transfer_.domain();
  auto shift_of = [](double v, int n) { return v < 0.0 ? double(n) : (v >= n ? -double(n) : 0.0); };
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    const std::size_t o = cells_[c].offset, n = cells_[c].rest.size();
    const double sx = d.periodic_x ? shift_of(x_[o], d.grid.nx) : 0.0;
    const double sy = d.periodic_y ? shift_of(y_[o], d.grid.ny) : 0.0;
    if (sx == 0.0 && sy == 0.0) continue;
    for (std::size_t m = o; m < o + n; ++m) {
      x_[m] += sx;
      y_[m] += sy;
    }
  }
}

void ImmersedCells::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "x", x_);
  r.put(prefix + "y", y_);
  r.put(prefix + "fx", fx_);
  r.put(prefix + "fy", fy_);
  r.put(prefix + "ux", ux_);
  r.put(prefix + "uy", uy_);
  for (int c = 0; c < cell_count(); ++c) {
    const std::string rest = prefix + std::to_string(c) + ".rest_";
    r.put(rest + "length", cells_[c].rest.length);
    r.put(rest + "dual", cells_[c].rest.dual);
    r.put(rest + "turning", cells_[c].rest.turning);
    r.put_scalar(rest + "area", cells_[c].rest.area);
    if (area_projection_) r.put_scalar(prefix + std::to_string(c) + ".restored_area", cells_[c].restored_area);
  }
}

void ImmersedCells::restore_state(const StateRecord& r, const std::string& prefix) {
  r.copy_to(prefix + "x", x_);
  r.copy_to(prefix + "y", y_);
  r.copy_to(prefix + "fx", fx_);
  r.copy_to(prefix + "fy", fy_);
  r.copy_to(prefix + "ux", ux_);
  r.copy_to(prefix + "uy", uy_);
  for (int c = 0; c < cell_count(); ++c) {
    const std::string rest = prefix + std::to_string(c) + ".rest_";
    r.copy_to(rest + "length", cells_[c].rest.length);
    r.copy_to(rest + "dual", cells_[c].rest.dual);
    r.copy_to(rest + "turning", cells_[c].rest.turning);
    cells_[c].rest.area = r.scalar(rest + "area");
    if (area_projection_) cells_[c].restored_area = r.scalar(prefix + std::to_string(c) + ".restored_area");
  }
}

Energy ImmersedCells::energy(int c) const { return membrane_energy(cells_[c].model, cells_[c].rest, x(c), y(c)); }

double ImmersedCells::max_marker_speed() const {
  double s = 0.0;
  for (std::size_t m = 0; m < ux_.size(); ++m) s = std::max(s, numeric::hypot_portable(ux_[m], uy_[m]));
  return s;
}

}  // namespace erythro::membrane
