#pragma once
// The D2Q9 fluid: one structure-of-arrays population lattice updated in place by a
// fused stream–collide step (pull scheme, AA pattern: fluid/stream_collide.hpp).
// Everything is in lattice units (h = Δt = 1); the scene layer converts from physical
// units.
//
// Populations: populations()[q * N + n], n = y*nx + x (see lattice/grid.hpp); inside,
// the nine arrays are padded apart and alternate between the AA pattern's two layouts
// (fluid/stream_collide.hpp), which every read here resolves. They are kept as
// deviations from the rest state, f̃_i = f_i − w_i (ρ0 = 1). Sums of O(1) numbers
// that nearly cancel become sums of O(Ma) numbers, so round-off in mass, momentum
// and slow steady flows drops by about two orders (Skordos 1993, Phys Rev E
// 48:4823; Lehmann 2022). Optional
// per-node fields (force density, relaxation time) are allocated only when a
// caller enables them, so a plain channel flow carries neither.
#include <array>
#include <cstdint>
#include <new>
#include <span>
#include <vector>

#include "common/health.hpp"
#include "common/state_record.hpp"
#include "fluid/boundary.hpp"
#include "fluid/collision.hpp"
#include "fluid/force_rows.hpp"
#include "lattice/grid.hpp"

namespace erythro::fluid {

namespace detail {
// Cache-line (64 B) aligned storage for the population lattice: rows of grids with
// nx a multiple of 8 start on a cache line, so the kernel's vector loop reads and
// writes whole lines (docs/performance.md).
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t alignment{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), alignment)); }
  void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, alignment); }
  template <class U>
  bool operator==(const CacheLineAllocator<U>&) const noexcept { return true; }
};
}  // namespace detail

// Macroscopic fields with Guo's half-force correction: ρu = Σ f_i c_i + F/2.
struct Moments {
  std::vector<double> rho, ux, uy;
};

// Health scan of given moments (see FluidLattice::check_health).
HealthReport check_health(const Grid& grid, const Moments& m, double max_mach);

class FluidLattice {
 public:
  FluidLattice(Grid grid, CollisionConfig collision, BoundaryConfig boundaries);

  const Grid& grid() const { return grid_; }
  const CollisionConfig& collision() const { return collision_; }
  const BoundaryConfig& boundaries() const { return boundaries_; }

  // Sets every node to the equilibrium of the given fields (size N each).
  void initialize(std::span<const double> rho, std::span<const double> ux, std::span<const double> uy);
  void initialize_uniform(double rho, double ux, double uy);

  // Body force density applied at every node (added to the per-node field if enabled).
  void set_uniform_force(double fx, double fy) { uniform_force_ = {fx, fy}; }
  std::array<double, 2> uniform_force() const { return uniform_force_; }

  // Per-node force density (immersed boundary, manufactured solutions). Allocated,
  // zeroed, on the first call to enable_force_field().
  // The step skips the force term on rows known to hold no force: a zero force adds
  // exactly zero, so the values are the same (docs/performance-coupled-step.md, "Quiet rows").
  // force_x()/force_y() give write access anywhere, so after them every row counts as
  // forced until the next clear_force_field(); a writer that records the rows it writes
  // uses force_rows_writer() instead.
  void enable_force_field();
  bool has_force_field() const { return !force_x_.empty(); }
  std::span<double> force_x();
  std::span<double> force_y();
  // The field as stored: between clear_force_field() and the next step() or force_x(), a
  // row whose state is force_row::kCleared (force_row_state) still holds the force before
  // the clear, which counts as zero. The moments, collision_force and save_state read such
  // rows as zero; after step() no row is cleared.
  std::span<const double> force_x() const { return force_x_; }
  std::span<const double> force_y() const { return force_y_; }
  // A row's state (fluid/force_rows.hpp); kForced for every row while the rows are not known.
  std::uint8_t force_row_state(int y) const;
  // Clears the force field (enabling it if needed) without touching it: the rows that may
  // hold force are marked cleared, and each is zeroed when a writer first adds to it
  // (ForceRowsWriter) or else at the start of the next step() (docs/performance-coupled-step.md, "The
  // force field zeroed where it is written"). Every value read is that of a zeroed field.
  void clear_force_field();
  // Write access for a writer that, before its first addition to row y, zeroes the row if
  // rows[y] is force_row::kCleared and then sets rows[y] = force_row::kForced.
  struct ForceRowsWriter {
    std::span<double> fx, fy;
    std::span<std::uint8_t> rows;
  };
  ForceRowsWriter force_rows_writer();

  // Per-node relaxation time τ(x) (cell interiors). Initialised to collision().tau.
  // A row of one τ is collided with that τ's rates, computed once per row (the same
  // bits as per node). The mutable tau_field() forgets that summary until the writer
  // calls refresh_tau_rows(); until then every row is collided node by node.
  void enable_tau_field();
  bool has_tau_field() const { return !tau_field_.empty(); }
  std::span<double> tau_field();
  std::span<const double> tau_field() const { return tau_field_; }
  void refresh_tau_rows();

  // One fused stream–collide update of every node.
  void step();
  long steps_done() const { return steps_done_; }

  // The next step() also writes every node's velocity into ux and uy (grid-sized), as it
  // collides the node: the u that collision relaxed towards (docs/model.md eq 1.3b), the
  // u of compute_moments() after that step up to round-off, at the cost of the stores
  // alone (for a caller that needs it at most nodes, the dense immersed cells). For that
  // one step only.
  void write_velocity_with_next_step(std::span<double> ux, std::span<double> uy);
  // Whether the last step() wrote its velocity into this ux array (and the uy given with it),
  // and nothing has changed the populations since.
  bool last_step_wrote_velocity(const double* ux) const {
    return velocity_written_step_ == steps_done_ && velocity_written_ux_ == ux;
  }

  // Density and velocity of the last collision, from the stored post-collision
  // populations: ρu = Σ c_i f*_i − F/2 with the force that collision used.
  // (The per-node force field is read as it is now: compute moments before
  // overwriting it for the next step.) Before the first step, u is the
  // initial velocity minus F/(2ρ) if a force was already set.
  Moments moments() const;
  void compute_moments(std::span<double> rho, std::span<double> ux, std::span<double> uy) const;
  // The same for one node (x, y) (the same operations, so the same bits).
  void node_moments(int x, int y, double& rho, double& ux, double& uy) const;
  // The same for the nodes x0 ≤ x < x1 of row y, written at their node index n in rho, ux and
  // uy (each of grid().size(), like compute_moments'): the row's vector loop where the layout
  // allows, as compute_moments (which calls it for whole rows); the same bits.
  void span_moments(int y, int x0, int x1, std::span<double> rho, std::span<double> ux, std::span<double> uy) const;

  double total_mass() const;
  // Σ ρu of the last collision (see moments()).
  std::array<double, 2> total_momentum() const;

  // Finite density and velocity, ρ > 0, |u|/c_s ≤ max_mach; the first offending
  // node in row-major order is reported.
  HealthReport check_health(double max_mach) const { return fluid::check_health(grid_, moments(), max_mach); }

  // Raw post-collision populations as deviations f̃_i = f_i − w_i, [q * N + n]. The
  // lattice keeps its nine arrays padded apart (detail::padded_stride) and, after an odd
  // number of steps, in the AA pattern's streamed layout, so this is a copy gathered into
  // a second buffer (allocated on first use, kept until the next step or write; so not
  // to be called from two threads at once). Hot paths use compute_moments() or
  // node_moments(), which read the lattice in place.
  std::span<const double> populations() const;
  // Replaces every population ([q * N + n], size 9N), e.g. a non-equilibrium start.
  void set_populations(std::span<const double> populations);

  // Checkpoint (common/state_record.hpp): the stored populations as they lie (padding and
  // AA layout included, so the next step is the same bits), the layout parity, the force
  // and τ fields, the forces of the last step and the step count, under `prefix`.
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  using Storage = std::vector<double, detail::CacheLineAllocator<double>>;
  // Slot of f*_k(x, y) in f_ (the layout-dependent part of every read).
  std::size_t slot_of(int x, int y, int k) const;
  // f_ now holds the natural layout (after a write of every population).
  void mark_natural();
  // Row y of the post-collision populations: p[k][x] = f*_k(x, y) for first ≤ x < last
  // (the whole row in the natural layout; the interior columns of interior rows in the
  // streamed one). The other nodes are read through slot_of().
  struct RowView {
    const double* p[9];
    int first, last;
  };
  RowView row_view(int y) const;
  void gather_natural(Storage& out) const;
  // Uniform force of the last collision plus the force field at node n.
  std::array<double, 2> collision_force(std::size_t n) const;
  bool row_cleared(int y) const {
    return force_rows_known_ && force_rows_[static_cast<std::size_t>(y)] == force_row::kCleared;
  }
  // Zeroes the rows still cleared and marks them free of force (before the step, and
  // before write access to the whole field).
  void zero_cleared_rows();

  Grid grid_;
  CollisionConfig collision_;
  BoundaryConfig boundaries_;
  std::size_t stride_ = 0;  // distance between the population arrays in f_
  Storage f_;
  bool streamed_ = false;  // f_ in the AA streamed layout (after an odd number of steps)
  mutable Storage natural_copy_;  // what populations() returns
  mutable long natural_copy_step_ = -1;  // steps_done_ when gathered; −1: stale
  std::vector<double> force_x_, force_y_, tau_field_;
  // Per row its state (fluid/force_rows.hpp), when force_rows_known_; else every row may hold force.
  std::vector<std::uint8_t> force_rows_;
  bool force_rows_known_ = false;
  std::vector<double> zero_row_;  // nx zeros: the force of a cleared row, for the moments
  std::vector<double> row_tau_;  // the row's one τ, 0 where τ varies (when row_tau_known_)
  bool row_tau_known_ = false;
  std::array<double, 2> uniform_force_{0.0, 0.0};
  std::array<double, 2> applied_force_{0.0, 0.0};  // uniform force of the last step
  long steps_done_ = 0;
  std::array<double*, 2> velocity_request_{nullptr, nullptr};  // ux, uy for the next step
  const double* velocity_written_ux_ = nullptr;  // where the step velocity_written_step_ wrote it
  long velocity_written_step_ = -1;
};

}  // namespace erythro::fluid
