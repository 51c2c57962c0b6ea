#include "transport/transport_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "transport/stencils.hpp"
#include "transport/transport_kernel.hpp"

namespace erythro::transport {
namespace {

bool periodic(const Side& s) { return s.kind == SideKind::periodic; }

template <class S>
void fill_equilibrium(const Grid& grid, std::span<const double> C, std::span<const double> ux,
                      std::span<const double> uy, std::vector<double>& g) {
  const std::size_t N = grid.size();
  for (std::size_t n = 0; n < N; ++n) {
    const double u = ux.empty() ? 0.0 : ux[n], v = uy.empty() ? 0.0 : uy[n];
    for (int i = 0; i < S::Q; ++i) g[i * N + n] = equilibrium<S>(i, C[n], u, v);
  }
}

// Eq T6: amount crossing line x+½ (east) and y+½ (north) from row y's populations.
// Axisymmetric: the r-weighted amount, the sides weighted as the kernel weights them (eq 7.10).
template <class S>
void face_flux_impl(const Grid& grid, const TransportBoundaries& sides, std::span<const double> row_radius,
                    const std::vector<double>& g, std::span<double> east, std::span<double> north) {
  const std::size_t N = grid.size();
  const double bottom_r = row_radius.empty() ? 0.0 : row_radius.front() - 0.5;
  const double top_r = row_radius.empty() ? 0.0 : row_radius.back() + 0.5;
#pragma omp parallel for schedule(static) if (grid.worth_threading())
  for (int y = 0; y < grid.ny; ++y) {
    const TransportBoundaries b =
        row_radius.empty() ? sides : detail::weighted_sides(sides, row_radius[static_cast<std::size_t>(y)], bottom_r, top_r);
    for (int x = 0; x < grid.nx; ++x) {
      const std::size_t n = grid.index(x, y);
      double e = 0.0, no = 0.0, unused = 0.0;
      for (int i = 0; i < S::Q; ++i) {
        // Leaving (x, y) along +x / +y during the next streaming …
        if (S::cx[i] > 0) e += g[i * N + n];
        if (S::cy[i] > 0) no += g[i * N + n];
      }
      // … minus arriving at (x, y) from beyond its east / north face. What arrives
      // at (x, y) along i comes from x − c_i: it crossed the east face if c_x = −1.
      for (int i = 0; i < S::Q; ++i) {
        if (S::cx[i] < 0 || S::cy[i] < 0) {
          // Arrivals at (x, y) along i are what the *next* stream delivers: pull.
          const double in = detail::pull<S>(grid, b, g.data(), x, y, i, unused);
          if (S::cx[i] < 0) e -= in;
          if (S::cy[i] < 0) no -= in;
        }
      }
      east[n] = e;
      north[n] = no;
    }
  }
}

}  // namespace

double source_offset_coefficient(double magic) { return 0.25 - 2.0 * magic / 3.0; }  // eq T7

double MassBalance::relative_residual() const {
  return std::fabs(residual()) / std::max(scale, std::numeric_limits<double>::min());
}

std::string TransportBoundaries::inconsistency() const {
  if (periodic(left) != periodic(right)) return "a periodic left/right side must face a periodic side";
  if (periodic(bottom) != periodic(top)) return "a periodic bottom/top side must face a periodic side";
  return {};
}

TransportLattice::TransportLattice(Grid grid, Stencil stencil, TransportBoundaries boundaries)
    : grid_(grid), stencil_(stencil), boundaries_(boundaries) {
  if (grid_.nx < 1 || grid_.ny < 1) throw std::invalid_argument("TransportLattice: empty grid");
  if (auto why = boundaries_.inconsistency(); !why.empty()) throw std::invalid_argument("TransportLattice: " + why);
  const std::size_t N = grid_.size();
  g_.assign(static_cast<std::size_t>(q()) * N, 0.0);
  g_next_.assign(g_.size(), 0.0);
  C_.assign(N, 0.0);
  const auto ny = static_cast<std::size_t>(grid_.ny);
  row_source_.assign(ny, 0.0);
  row_boundary_.assign(ny, 0.0);
  row_amount_.assign(ny, 0.0);
  row_scale_.assign(ny, 0.0);
}

int TransportLattice::q() const { return stencil_ == Stencil::d2q5 ? D2Q5::Q : D2Q9::Q; }

void TransportLattice::initialize(std::span<const double> concentration) {
  if (concentration.size() != grid_.size()) {
    throw std::invalid_argument("TransportLattice::initialize: field size does not match the grid");
  }
  std::copy(concentration.begin(), concentration.end(), C_.begin());
  // Stored populations are post-collision: with reactions set, Σ g* = C + ½ q_tot (T4),
  // so the first step starts time-centred (without this the source lags half a step).
  std::vector<double> shifted(C_);
  if (has_reaction()) {
    for (std::size_t n = 0; n < shifted.size(); ++n) shifted[n] += 0.5 * (source_[n] - decay_[n] * C_[n]);
  }
  std::span<const double> ux = ux_, uy = uy_;
  if (axisymmetric()) {  // φ = r C with the drift velocity (eq 7.7)
    for (std::size_t n = 0; n < shifted.size(); ++n) shifted[n] *= row_radius_[n / static_cast<std::size_t>(grid_.nx)];
    refresh_drift();
    ux = drift_ux_;
    uy = drift_uy_;
  }
  if (stencil_ == Stencil::d2q5) {
    fill_equilibrium<D2Q5>(grid_, shifted, ux, uy, g_);
  } else {
    fill_equilibrium<D2Q9>(grid_, shifted, ux, uy, g_);
  }
  balance_ = MassBalance{};
  balance_.amount = stored_amount();
}

void TransportLattice::initialize_uniform(double c) {
  const std::vector<double> field(grid_.size(), c);
  initialize(field);
}

void TransportLattice::set_uniform_diffusivity(double D) {
  if (!(D > 0.0)) throw std::invalid_argument("TransportLattice: diffusivity must be positive (tau > 1/2)");
  uniform_D_ = D;
  if (!D_field_.empty()) std::fill(D_field_.begin(), D_field_.end(), D);
  rates_stale_ = true;
  drift_stale_ = true;
}

void TransportLattice::set_collision(CollisionModel c) {
  if (c.kind == Collision::trt && !(c.magic > 0.0)) {
    throw std::invalid_argument("TransportLattice: the TRT magic parameter must be positive");
  }
  collision_ = c;
  rates_stale_ = true;
  drift_stale_ = true;  // the source scaling of eq 7.9 depends on the collision
}

std::span<double> TransportLattice::diffusivity() {
  if (D_field_.empty()) D_field_.assign(grid_.size(), uniform_D_);
  rates_stale_ = true;
  drift_stale_ = true;
  return D_field_;
}

TransportLattice::TensorField TransportLattice::diffusivity_tensor() {
  if (Dxx_.empty()) {
    if (D_field_.empty()) {
      Dxx_.assign(grid_.size(), uniform_D_);
    } else {
      Dxx_ = D_field_;
    }
    Dyy_ = Dxx_;
    Dxy_.assign(grid_.size(), 0.0);
  }
  return {Dxx_, Dyy_, Dxy_};
}

std::span<double> TransportLattice::source() {
  if (source_.empty()) {
    source_.assign(grid_.size(), 0.0);
    decay_.assign(grid_.size(), 0.0);
  }
  return source_;
}

std::span<double> TransportLattice::decay_rate() {
  source();
  has_decay_ = true;
  return decay_;
}

void TransportLattice::set_velocity(std::span<const double> ux, std::span<const double> uy) {
  if (ux.size() != grid_.size() || uy.size() != grid_.size()) {
    throw std::invalid_argument("TransportLattice::set_velocity: field size does not match the grid");
  }
  ux_.assign(ux.begin(), ux.end());
  uy_.assign(uy.begin(), uy.end());
  drift_stale_ = true;
  if (axisymmetric()) refuse_radial_velocity();
}

// docs/model.md §7b: the central φ flux of a radial velocity is first order at the axis row
// (r C u_r ∝ r² there), so the axisymmetric lattice advects along the axis only.
void TransportLattice::refuse_radial_velocity() const {
  for (double v : uy_)
    if (v != 0.0)
      throw std::invalid_argument("TransportLattice: an axisymmetric lattice takes an axial velocity only (u_r = 0)");
}

void TransportLattice::set_uniform_velocity(double ux, double uy) {
  ux_.assign(grid_.size(), ux);
  uy_.assign(grid_.size(), uy);
  drift_stale_ = true;
  if (axisymmetric()) refuse_radial_velocity();
}

void TransportLattice::clear_velocity() {
  ux_.clear();
  uy_.clear();
  drift_stale_ = true;
}

void TransportLattice::set_axisymmetric(double inner_radius) {
  if (!(inner_radius >= 0.0) || !std::isfinite(inner_radius)) {
    throw std::invalid_argument("TransportLattice::set_axisymmetric: the inner radius must be finite and >= 0");
  }
  if (periodic(boundaries_.bottom)) {
    throw std::invalid_argument("TransportLattice::set_axisymmetric: the bottom (inner) and top (outer) sides cannot be periodic");
  }
  if (inner_radius == 0.0 && boundaries_.bottom.kind != SideKind::zero_flux) {
    throw std::invalid_argument("TransportLattice::set_axisymmetric: the axis (inner radius 0) must be a zero_flux side");
  }
  if (has_diffusivity_tensor()) {
    throw std::invalid_argument("TransportLattice::set_axisymmetric: not with the diffusivity tensor");
  }
  if (stencil_ != Stencil::d2q5) {  // measured: D2Q9 is of order 1.6 on the axis row (docs/model.md §7b)
    throw std::invalid_argument("TransportLattice::set_axisymmetric: D2Q5 only (second order at the axis)");
  }
  refuse_radial_velocity();
  row_radius_.resize(static_cast<std::size_t>(grid_.ny));
  for (int y = 0; y < grid_.ny; ++y) row_radius_[static_cast<std::size_t>(y)] = inner_radius + y + 0.5;
  drift_stale_ = true;
}

// Eq 7.7: the velocity the φ lattice advects with, u + (D/r) e_r (x axial, y radial), and the
// source scaling Λ⁺/Λ⁻ of TRT (eq 7.9; Λ⁻ = D/c_s², Λ⁺ = Λ/Λ⁻; 1 for BGK).
void TransportLattice::refresh_drift() {
  if (!drift_stale_) return;
  const std::size_t N = grid_.size(), nx = static_cast<std::size_t>(grid_.nx);
  const bool trt = collision_.kind == Collision::trt;
  const auto scale_for = [&](double D) {
    const double lambda_minus = kInvCs2 * D;
    return trt ? collision_.magic / (lambda_minus * lambda_minus) : 1.0;
  };
  drift_ux_.assign(N, 0.0);
  drift_uy_.assign(N, 0.0);
  source_velocity_scale_.assign(D_field_.empty() ? 0 : N, 1.0);
  for (std::size_t y = 0, n = 0; y < row_radius_.size(); ++y) {
    const double r = row_radius_[y];
    for (std::size_t x = 0; x < nx; ++x, ++n) {
      const double D = D_field_.empty() ? uniform_D_ : D_field_[n];
      drift_ux_[n] = ux_.empty() ? 0.0 : ux_[n];
      drift_uy_[n] = (uy_.empty() ? 0.0 : uy_[n]) + D / r;
      if (!D_field_.empty()) source_velocity_scale_[n] = scale_for(D);
    }
  }
  uniform_source_velocity_scale_ = scale_for(uniform_D_);
  drift_stale_ = false;
}

double TransportLattice::total_weight() const {
  if (!axisymmetric()) return static_cast<double>(grid_.size());
  double s = 0.0;
  for (double r : row_radius_) s += r * grid_.nx;
  return s;
}

void TransportLattice::step() {
  detail::KernelArgs a;
  a.grid = grid_;
  a.stencil = stencil_;
  a.boundaries = boundaries_;
  a.src = g_.data();
  a.dst = g_next_.data();
  a.C = C_.data();
  a.uniform_D = uniform_D_;
  a.trt = collision_.kind == Collision::trt;
  a.magic = collision_.magic;
  if (!D_field_.empty()) {
    if (rates_stale_) {
      detail::relaxation_rates(D_field_, a.trt, a.magic, omega_, omega_plus_);
      rates_stale_ = false;
    }
    a.omega = omega_.data();
    a.omega_plus = omega_plus_.data();
  }
  if (!Dxx_.empty()) {
    if (stencil_ != Stencil::d2q5 || collision_.kind != Collision::trt) {
      throw std::logic_error("TransportLattice: the diffusivity tensor needs D2Q5 and the TRT collision");
    }
    a.Dxx = Dxx_.data();
    a.Dyy = Dyy_.data();
    a.Dxy = Dxy_.data();
  }
  a.source = source_.empty() ? nullptr : source_.data();
  a.decay = has_decay_ ? decay_.data() : nullptr;
  a.ux = ux_.empty() ? nullptr : ux_.data();
  a.uy = uy_.empty() ? nullptr : uy_.data();
  if (axisymmetric()) weight_for_axisymmetry(a);
  a.row_source = row_source_.data();
  a.row_boundary = row_boundary_.data();
  a.row_amount = row_amount_.data();
  a.row_scale = row_scale_.data();
  detail::stream_collide(a);
  if (axisymmetric()) {  // the kernel wrote φ = r C (eq 7.7)
    const std::size_t nx = static_cast<std::size_t>(grid_.nx);
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
    for (int y = 0; y < grid_.ny; ++y) {
      const double r = row_radius_[static_cast<std::size_t>(y)];
      const std::size_t n0 = static_cast<std::size_t>(y) * nx;
      for (std::size_t x = 0; x < nx; ++x) C_[n0 + x] /= r;
    }
  }
  g_.swap(g_next_);
  ++steps_done_;
  // Serial sums over rows (eq T5): independent of the thread count.
  MassBalance b;
  for (std::size_t r = 0; r < row_source_.size(); ++r) {
    b.source += row_source_[r];
    b.boundary_in += row_boundary_[r];
    b.amount += row_amount_[r];
    b.scale += row_scale_[r];
  }
  b.storage_change = b.amount - balance_.amount;
  balance_ = b;
}

// Eq 7.7: the kernel sees the drift velocity, the source r q and the r-weighted sides.
void TransportLattice::weight_for_axisymmetry(detail::KernelArgs& a) {
  if (!Dxx_.empty()) throw std::logic_error("TransportLattice: the axisymmetric lattice has no diffusivity tensor");
  refresh_drift();
  a.ux = drift_ux_.data();
  a.uy = drift_uy_.data();
  a.source_velocity_scale = source_velocity_scale_.empty() ? nullptr : source_velocity_scale_.data();
  a.uniform_source_velocity_scale = uniform_source_velocity_scale_;
  if (!source_.empty()) {
    const std::size_t nx = static_cast<std::size_t>(grid_.nx);
    weighted_source_.resize(source_.size());
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
    for (int y = 0; y < grid_.ny; ++y) {
      const double r = row_radius_[static_cast<std::size_t>(y)];
      const std::size_t n0 = static_cast<std::size_t>(y) * nx;
      for (std::size_t x = 0; x < nx; ++x) weighted_source_[n0 + x] = r * source_[n0 + x];
    }
    a.source = weighted_source_.data();
  }
  a.row_radius = row_radius_.data();
  a.bottom_radius = row_radius_.front() - 0.5;
  a.top_radius = row_radius_.back() + 0.5;
}

double TransportLattice::source_offset_factor(std::size_t n) const {
  if (!Dxx_.empty()) {
    // eq T7 per axis chain (c/D_xx along x, c/D_yy along y; Λ of the TRT collision): their mean
    return source_offset_coefficient(collision_.magic) * 0.5 * (1.0 / Dxx_[n] + 1.0 / Dyy_[n]);
  }
  const double D = D_field_.empty() ? uniform_D_ : D_field_[n];
  const double s = kInvCs2 * D;  // τ − ½
  const double magic = collision_.kind == Collision::trt ? collision_.magic : s * s;
  return source_offset_coefficient(magic) / D;  // eq T7
}

double TransportLattice::source_corrected_concentration(std::size_t n) const {
  if (source_.empty()) return C_[n];
  const double q_tot = source_[n] - decay_[n] * C_[n];
  return C_[n] + source_offset_factor(n) * q_tot;  // eq T7
}

void TransportLattice::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "populations", g_);
  r.put(prefix + "concentration", C_);
  if (has_reaction()) {
    r.put(prefix + "source", source_);
    r.put(prefix + "decay_rate", decay_);
  }
  if (has_velocity()) {
    r.put(prefix + "ux", ux_);
    r.put(prefix + "uy", uy_);
  }
  const MassBalance& b = balance_;
  r.put(prefix + "mass_balance", std::vector<double>{b.source, b.boundary_in, b.storage_change, b.amount, b.scale});
  r.put_scalar(prefix + "steps_done", static_cast<double>(steps_done_));
}

void TransportLattice::restore_state(const StateRecord& r, const std::string& prefix) {
  r.copy_to(prefix + "populations", g_);
  r.copy_to(prefix + "concentration", C_);
  if (r.has(prefix + "source")) {
    r.copy_to(prefix + "source", source());
    r.copy_to(prefix + "decay_rate", decay_rate());
  }
  if (r.has(prefix + "ux")) set_velocity(r.get(prefix + "ux"), r.get(prefix + "uy"));
  drift_stale_ = true;
  const std::vector<double>& b = r.get(prefix + "mass_balance", 5);
  balance_ = {b[0], b[1], b[2], b[3], b[4]};
  steps_done_ = static_cast<long>(r.scalar(prefix + "steps_done"));
}

double TransportLattice::total_amount() const {
  double s = 0.0;
  if (!axisymmetric()) {
    for (double c : C_) s += c;
    return s;
  }
  const std::size_t nx = static_cast<std::size_t>(grid_.nx);
  for (std::size_t n = 0; n < C_.size(); ++n) s += row_radius_[n / nx] * C_[n];
  return s;
}

double TransportLattice::stored_amount() const {
  const std::size_t N = grid_.size();
  std::vector<double> row_sum(static_cast<std::size_t>(grid_.ny), 0.0);
  const int Q = q();
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
  for (int y = 0; y < grid_.ny; ++y) {
    double s = 0.0;
    for (int x = 0; x < grid_.nx; ++x) {
      double node = 0.0;
      for (int i = 0; i < Q; ++i) node += g_[i * N + grid_.index(x, y)];
      s += node;
    }
    row_sum[static_cast<std::size_t>(y)] = s;
  }
  double total = 0.0;
  for (double s : row_sum) total += s;
  return total;
}

void TransportLattice::face_flux(std::span<double> east, std::span<double> north) const {
  if (east.size() != grid_.size() || north.size() != grid_.size()) {
    throw std::invalid_argument("TransportLattice::face_flux: field size does not match the grid");
  }
  if (stencil_ == Stencil::d2q5) {
    face_flux_impl<D2Q5>(grid_, boundaries_, row_radius_, g_, east, north);
  } else {
    face_flux_impl<D2Q9>(grid_, boundaries_, row_radius_, g_, east, north);
  }
}

HealthReport TransportLattice::check_health(std::array<double, 2> range, double min_tau_margin) const {
  HealthReport r;
  const auto [lo, hi] = range;
  for (int y = 0; y < grid_.ny; ++y) {
    for (int x = 0; x < grid_.nx; ++x) {
      const std::size_t n = grid_.index(x, y);
      const double c = C_[n];
      if (!(c >= lo && c <= hi)) {
        const double limit = !std::isfinite(c) ? std::numeric_limits<double>::quiet_NaN() : c < lo ? lo : hi;
        return {false, "concentration", x, y, c, limit, 0.0, {}};
      }
      // tensor: the smaller eigenvalue (positive definiteness)
      const double D = !Dxx_.empty() ? 0.5 * (Dxx_[n] + Dyy_[n]) -
                                           std::hypot(0.5 * (Dxx_[n] - Dyy_[n]), Dxy_[n])
                       : D_field_.empty() ? uniform_D_
                                          : D_field_[n];
      const double margin = tau_for_diffusivity(D) - 0.5;
      if (!(margin >= min_tau_margin)) return {false, "tau_margin", x, y, margin, min_tau_margin, 0.0, {}};
    }
  }
  return r;
}

}  // namespace erythro::transport
