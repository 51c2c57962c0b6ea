#pragma once
// One transported species (NO or O2): advection–diffusion–reaction lattice Boltzmann,
// lattice units h = Δt = 1 (docs/transport.md). Solves
//   ∂C/∂t + ∇·(C u) = ∇·(D ∇C) + q − k C                                   (T1)
// with BGK, per-node τ = ½ + D/c_s² (c_s² = 1/3), an equilibrium linear in u (T2),
// g_i^eq = w_i C (1 + c_i·u/c_s²), and a second-order source (T3–T4):
//   g_i(x + c_i, t + 1) = g_i − ω (g_i − g_i^eq) + (1 − ω/2) w_i q_tot (1 + c_i·u/c_s²),
//   C = Σ g_i + q_tot/2,    q_tot = q − k C   ⇒   C = (Σ g_i + q/2) / (1 + k/2).
// Per-node τ with this equilibrium gives ∇·(D∇C), not ∇²(DC) (measured:
// verification.transport_manufactured). Optional TRT collision (T3', set_collision), a per-node
// diffusivity tensor (T8, diffusivity_tensor; D2Q5 TRT only) and the
// steady source offset of the concentration (T7, source_corrected_concentration).
// The first-order sink k is thus implicit (trapezoidal in time, unconditionally
// stable); q is whatever the caller set before step() (reactions computed from the
// previous step's concentrations: explicit).
//
// Storage: structure of arrays g[i*N + n], n = y*nx + x, post-collision values; one
// fused pull stream–collide step, OpenMP over rows (as fluid/stream_collide.cpp).
// Node (x, y) sits at ((x+½)h, (y+½)h): every non-periodic side lies halfway between
// the last node and the (virtual) next one.
//
// Axisymmetric geometry (set_axisymmetric; docs/model.md §7b, eqs 7.6–7.10): x is the axial
// coordinate z, y the radial one, and the lattice carries φ = r C, which obeys the planar
// equation with the velocity u + (D/r) e_r and the source r q (eq 7.7): the r-weighted amount is
// conserved exactly and the steady D2Q5 TRT (Λ = ¼) state is the conservative cylindrical
// finite-volume scheme (eq 7.9).
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "common/health.hpp"
#include "common/state_record.hpp"
#include "lattice/grid.hpp"

namespace erythro::transport {
namespace detail {
struct KernelArgs;
}

enum class Stencil { d2q5, d2q9 };

// Collision operator (docs/transport.md §1, eq T3 / T3'):
//  bgk: one rate ω = 1/τ, τ = ½ + D/c_s² (T3; the default, the former behaviour);
//  trt: two relaxation times (Ginzburg 2005): for each link pair (i, ī) the antisymmetric
//       part g⁻_i = (g_i − g_ī)/2 relaxes with τ⁻ = ½ + D/c_s² (sets D), the symmetric part
//       g⁺_i = (g_i + g_ī)/2 with τ⁺ = ½ + Λ/(τ⁻ − ½) (T3'), Λ = `magic`, the SAME at every
//       node whatever D_n. BGK is TRT with a per-node Λ_n = (τ_n − ½)²; a uniform Λ makes the
//       steady and the slowly varying solutions depend on D only, not on the τ's
//       (parametrisation invariance), also across a jump of D. Λ = 1/4 (default), 1/6
//       (cancels the fourth-order diffusion error), 1/12 (third-order advection error).
enum class Collision { bgk, trt };
struct CollisionModel {
  Collision kind = Collision::bgk;
  double magic = 0.25;  // Λ of trt (> 0); ignored by bgk
};

// Steady source offset (docs/transport.md §1, eq T7). With a source, the symmetric TRT
// populations carry a part ∝ q_tot, and the steady C = Σ g + q_tot/2 is not the finite-volume
// solution. Derived on a 1D D2Q5 row (face flux J = D (C_n − C_m) + c (q_n − q_m)) and
// verified in 2D to round-off (unit test SteadyOffsetCorrectedConcentrationIsFiniteVolume):
// for TRT with Λ = 1/4 on D2Q5,
//   Ĉ_n = C_n + c q_tot,n / D_n,   c = ¼ − 2Λ/3 = 1/12,
// solves EXACTLY the 5-point finite-volume equations Σ_m D_nm (Ĉ_m − Ĉ_n) + q_tot,n = 0 with
// harmonic face diffusivities D_nm = 2/(1/D_n + 1/D_m), across jumps of D and q alike. For
// other Λ (and BGK, Λ_n = (τ_n − ½)²) non-local terms remain: c is then the 1D value only.
double source_offset_coefficient(double magic);

// Boundary condition of one side (docs/transport.md §3):
//  periodic            : populations leaving one side enter the opposite one.
//  fixed_concentration : C = value on the side (anti-bounce-back, halfway, 2nd order)
//                        g_ī(x, t+1) = −g*_i(x, t) + 2 w_i value.
//  fixed_flux          : net amount `value` per unit side length per step enters
//                        through the side (inward flux, advective + diffusive)
//                        g_ī(x, t+1) = g*_i(x, t) + value w_i / Σ_crossing w.
//  zero_flux           : bounce-back, g_ī(x, t+1) = g*_i(x, t) (fixed_flux with 0).
// The velocity at a non-periodic side must be tangential (u·n = 0).
enum class SideKind { periodic, fixed_concentration, fixed_flux, zero_flux };
struct Side {
  SideKind kind = SideKind::periodic;
  double value = 0.0;  // concentration, or inward flux per unit length (lattice units)
};
struct TransportBoundaries {
  Side left, right, bottom, top;
  // Empty when consistent; otherwise a sentence (a periodic side must face a periodic side).
  std::string inconsistency() const;
};

// Balance of the last step. The conserved lattice amount is M = Σ_n Σ_i g*_i (the
// stored post-collision populations); M = Σ C + ½ Σ q_tot. Exactly (eq T5):
//   M(t+1) − M(t) = boundary_in + source,
// so residual() is round-off only.
struct MassBalance {
  double source = 0.0;          // Σ_n q_tot of the last collision (sources − sinks)
  double boundary_in = 0.0;     // net amount that entered through the sides while streaming
  double storage_change = 0.0;  // M(t+1) − M(t)
  double amount = 0.0;          // M(t+1)
  double scale = 0.0;           // Σ |g*| after the step (for a relative residual)
  double residual() const { return storage_change - source - boundary_in; }
  // |residual| / max(scale, tiny): ~1e-16 × (number of nodes)^½ expected.
  double relative_residual() const;
};

class TransportLattice {
 public:
  TransportLattice(Grid grid, Stencil stencil, TransportBoundaries boundaries);

  const Grid& grid() const { return grid_; }
  Stencil stencil() const { return stencil_; }

  // Axisymmetric geometry (docs/model.md §7b): row y at radius r_y = inner_radius + y + ½
  // (lattice units), the bottom side at inner_radius (0: the axis, which must be zero_flux; the
  // bottom and top sides cannot be periodic). Call before initialize(). From then on the
  // populations, stored_amount(), total_amount() (Σ r C), mass_balance() and face_flux() are
  // r-weighted (amounts per radian per unit axial length… in lattice units: Σ r C h²), while
  // concentration(), source(), decay_rate(), the velocity (u_z, u_r) and the side values stay
  // in C's units: the lattice weights them by r (eqs 7.7, 7.10). The velocity is axial only
  // (u_r = 0: a radial one would be first order at the axis row); D2Q5 only (D2Q9 measured
  // at order 1.6 on the axis row); not with the diffusivity tensor. Throws std::invalid_argument for a negative radius, inconsistent sides or a
  // radial velocity (also set_velocity later).
  void set_axisymmetric(double inner_radius);
  bool axisymmetric() const { return !row_radius_.empty(); }
  std::span<const double> row_radius() const { return row_radius_; }  // r_y per row; empty when planar
  // Σ_n of the weight that total_amount() gives each node: N (planar) or Σ r_y over the nodes.
  double total_weight() const;
  const TransportBoundaries& boundaries() const { return boundaries_; }
  TransportBoundaries& boundaries() { return boundaries_; }  // values may change between steps
  int q() const;  // populations per node

  // Equilibrium populations of the given concentration and the current velocity;
  // if source()/decay_rate() are already set, of C + ½ q_tot (the stored state is
  // post-collision, T4), so that a source acts time-centred from the first step: set
  // reactions first, then initialize. The concentration() before the first step is C.
  void initialize(std::span<const double> concentration);
  void initialize_uniform(double c);

  // D = c_s² (τ − ½). The uniform value; also resets an enabled per-node field.
  void set_uniform_diffusivity(double D);
  double uniform_diffusivity() const { return uniform_D_; }
  // Collision operator (Collision above); throws std::invalid_argument for Λ ≤ 0.
  void set_collision(CollisionModel c);
  const CollisionModel& collision() const { return collision_; }

  // Per-node D: allocated (filled with the uniform value) on the first call. The step
  // collides with relaxation rates computed from it once and kept until the next call
  // (or a change of the uniform D or the collision): write it before the next step.
  std::span<double> diffusivity();
  bool has_diffusivity_field() const { return !D_field_.empty(); }

  // Per-node diffusivity TENSOR (D_xx, D_yy, D_xy), eq T8 of docs/transport.md: D2Q5 with the
  // TRT collision only (step() throws std::logic_error otherwise). Allocated on the first call,
  // filled isotropically from diffusivity() (or the uniform D); once enabled it replaces the
  // scalar field everywhere (collision, source_offset_factor: c (1/D_xx + 1/D_yy)/2,
  // check_health: the smaller eigenvalue). Every node's tensor must be positive definite. The
  // node subpixel tensor of a curved diffusivity jump (subpixel_diffusivity.hpp) uses it.
  struct TensorField {
    std::span<double> xx, yy, xy;
  };
  TensorField diffusivity_tensor();
  bool has_diffusivity_tensor() const { return !Dxx_.empty(); }

  // Per-node source q (amount per node per step, i.e. concentration per step) and
  // first-order sink rate k (per step, implicit): q_tot = q − k C. Allocated, zero,
  // on the first call of either; the caller rewrites them between steps. Until the
  // first call of decay_rate() the step leaves the sink out (k = 0 exactly: the same bits).
  std::span<double> source();
  std::span<double> decay_rate();
  bool has_reaction() const { return !source_.empty(); }

  // Advecting velocity (lattice units), copied; |u| ≤ 0.1 recommended (positivity of
  // g^eq needs |u| < c_s² = 1/3 on D2Q5). clear_velocity(): still medium.
  void set_velocity(std::span<const double> ux, std::span<const double> uy);
  void set_uniform_velocity(double ux, double uy);
  void clear_velocity();
  bool has_velocity() const { return !ux_.empty(); }
  std::span<const double> velocity_x() const { return ux_; }
  std::span<const double> velocity_y() const { return uy_; }

  // One fused stream–collide step of every node; updates concentration() and mass_balance().
  void step();
  long steps_done() const { return steps_done_; }

  // C of the last collision (eq T4, source-corrected), size N.
  std::span<const double> concentration() const { return C_; }
  double total_amount() const;  // Σ_n C (axisymmetric: Σ_n r_n C_n)
  double stored_amount() const;  // M = Σ_n Σ_i g*_i
  const MassBalance& mass_balance() const { return balance_; }

  // Ĉ_n = C_n + c q_tot,n / D_n of eq T7 (c from the collision's Λ; BGK: Λ_n = (τ_n − ½)²),
  // q_tot of the last collision: the concentration the steady finite-volume scheme would have.
  double source_corrected_concentration(std::size_t n) const;
  // c(Λ_n)/D_n of eq T7 at node n (BGK: Λ_n = (τ_n − ½)²): Ĉ_n − C_n per unit q_tot,n.
  double source_offset_factor(std::size_t n) const;

  // Net amount per step crossing the east face (x+½) and the north face (y+½) of each
  // node during the next streaming (eq T6): exactly the discrete flux, including the
  // faces on the sides (as the boundary condition gives). Size N each.
  void face_flux(std::span<double> east, std::span<double> north) const;

  // C finite and within [range[0], range[1]] everywhere, and τ − ½ ≥ min_tau_margin
  // (D field): the first offending node (limit NaN for a non-finite C).
  HealthReport check_health(std::array<double, 2> range = {-std::numeric_limits<double>::infinity(),
                                                           std::numeric_limits<double>::infinity()},
                            double min_tau_margin = 1e-3) const;

  std::span<const double> populations() const { return g_; }  // [i*N + n], post-collision
  std::span<double> populations() { return g_; }

  // Checkpoint (common/state_record.hpp), under `prefix`: the populations, C of the last
  // collision, the source and sink it used (the source may hold a lagged term: Hb release,
  // face-flux correction), the velocity, the last mass balance and the step count. The
  // diffusivity fields are the owner's to rebuild (TransportPhysics::place_cells).
  void save_state(StateRecord& record, const std::string& prefix) const;
  void restore_state(const StateRecord& record, const std::string& prefix);

 private:
  Grid grid_;
  Stencil stencil_;
  TransportBoundaries boundaries_;
  double uniform_D_ = 1.0 / 6.0;  // τ = 1
  CollisionModel collision_{};
  std::vector<double> g_, g_next_, C_;
  std::vector<double> D_field_, source_, decay_, ux_, uy_;
  std::vector<double> omega_, omega_plus_;  // relaxation rates of D_field_ (eq T3')
  bool rates_stale_ = true;                 // D_field_, D or Λ changed since they were computed
  bool has_decay_ = false;                  // decay_rate() was handed out
  std::vector<double> Dxx_, Dyy_, Dxy_;  // optional tensor (eq T8)
  std::vector<double> row_source_, row_boundary_, row_amount_, row_scale_;
  // Axisymmetric (eq 7.7): radius per row, the velocity with the drift D/r and the source r q
  // handed to the kernel; the drift is rebuilt when the velocity or D changed.
  std::vector<double> row_radius_, drift_ux_, drift_uy_, weighted_source_;
  std::vector<double> source_velocity_scale_;  // Λ⁺/Λ⁻ per node with a D field (eq 7.9)
  double uniform_source_velocity_scale_ = 1.0;
  bool drift_stale_ = true;
  void refresh_drift();
  void refuse_radial_velocity() const;
  void weight_for_axisymmetry(detail::KernelArgs& a);
  MassBalance balance_;
  long steps_done_ = 0;
};

}  // namespace erythro::transport
