#include "fluid/fluid_lattice.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "fluid/node_moments.hpp"
#include "fluid/stream_collide.hpp"
#include "lattice/d2q9.hpp"

namespace erythro::fluid {

FluidLattice::FluidLattice(Grid grid, CollisionConfig collision, BoundaryConfig boundaries)
    : grid_(grid), collision_(collision), boundaries_(boundaries) {
  if (grid_.nx < 1 || grid_.ny < 1) throw std::invalid_argument("FluidLattice: empty grid");
  if (!(collision_.tau > 0.5)) throw std::invalid_argument("FluidLattice: tau must exceed 1/2");
  if (auto why = boundaries_.inconsistency(); !why.empty()) throw std::invalid_argument("FluidLattice: " + why);
  stride_ = detail::padded_stride(grid_.size());
  f_.assign(d2q9::Q * stride_, 0.0);
  initialize_uniform(1.0, 0.0, 0.0);
}

void FluidLattice::initialize(std::span<const double> rho, std::span<const double> ux,
                              std::span<const double> uy) {
  const std::size_t N = grid_.size();
  if (rho.size() != N || ux.size() != N || uy.size() != N) {
    throw std::invalid_argument("FluidLattice::initialize: field size does not match the grid");
  }
  for (std::size_t n = 0; n < N; ++n) {
    for (int i = 0; i < d2q9::Q; ++i) f_[i * stride_ + n] = d2q9::equilibrium_deviation(i, rho[n], ux[n], uy[n]);
  }
  mark_natural();
}

void FluidLattice::set_populations(std::span<const double> populations) {
  const std::size_t N = grid_.size();
  if (populations.size() != d2q9::Q * N) {
    throw std::invalid_argument("FluidLattice::set_populations: expected 9 N values");
  }
  for (int i = 0; i < d2q9::Q; ++i) {
    std::copy_n(populations.begin() + static_cast<std::ptrdiff_t>(i * N), N,
                f_.begin() + static_cast<std::ptrdiff_t>(i * stride_));
  }
  mark_natural();
}

void FluidLattice::initialize_uniform(double rho, double ux, double uy) {
  const std::size_t N = grid_.size();
  for (int i = 0; i < d2q9::Q; ++i) {
    const double feq = d2q9::equilibrium_deviation(i, rho, ux, uy);
    std::fill_n(f_.begin() + static_cast<std::ptrdiff_t>(i * stride_), N, feq);
  }
  mark_natural();
}

void FluidLattice::enable_force_field() {
  if (!force_x_.empty()) return;
  force_x_.assign(grid_.size(), 0.0);
  force_y_.assign(grid_.size(), 0.0);
  zero_row_.assign(static_cast<std::size_t>(grid_.nx), 0.0);
}

std::span<double> FluidLattice::force_x() {
  zero_cleared_rows();
  force_rows_known_ = false;
  return force_x_;
}

std::span<double> FluidLattice::force_y() {
  zero_cleared_rows();
  force_rows_known_ = false;
  return force_y_;
}

std::uint8_t FluidLattice::force_row_state(int y) const {
  return force_rows_known_ ? force_rows_[static_cast<std::size_t>(y)] : force_row::kForced;
}

void FluidLattice::clear_force_field() {
  enable_force_field();
  // Rows not known (written through force_x() or restored since the last clear): any row may
  // hold force, so every row is cleared. The field itself is zeroed later, row by row, where
  // it is written or before the step (zero_cleared_rows).
  if (!force_rows_known_)
    force_rows_.assign(static_cast<std::size_t>(grid_.ny), force_row::kCleared);
  else
    for (std::uint8_t& state : force_rows_)
      if (state == force_row::kForced) state = force_row::kCleared;
  force_rows_known_ = true;
}

void FluidLattice::zero_cleared_rows() {
  if (!force_rows_known_) return;
  const std::size_t nx = static_cast<std::size_t>(grid_.nx);
  long cleared = 0;
  for (std::uint8_t state : force_rows_) cleared += state == force_row::kCleared;
  if (cleared == 0) return;
  // Rows in parallel when many are left (zeros: the same bits for any number of threads).
  std::uint8_t* rows = force_rows_.data();
  double* fx = force_x_.data();
  double* fy = force_y_.data();
#pragma omp parallel for schedule(static) if (grid_.worth_threading() && cleared >= 64)
  for (int y = 0; y < grid_.ny; ++y) {
    if (rows[y] != force_row::kCleared) continue;
    std::fill_n(fx + static_cast<std::size_t>(y) * nx, nx, 0.0);
    std::fill_n(fy + static_cast<std::size_t>(y) * nx, nx, 0.0);
    rows[y] = force_row::kZero;
  }
}

FluidLattice::ForceRowsWriter FluidLattice::force_rows_writer() {
  enable_force_field();
  // Rows not known (written through force_x() since the last clear; none is cleared then):
  // the flags the writer sets are kept but not used, every row stays forced until the next clear.
  force_rows_.resize(static_cast<std::size_t>(grid_.ny), force_row::kForced);
  return {force_x_, force_y_, force_rows_};
}

void FluidLattice::enable_tau_field() {
  if (!tau_field_.empty()) return;
  tau_field_.assign(grid_.size(), collision_.tau);
  refresh_tau_rows();
}

std::span<double> FluidLattice::tau_field() {
  row_tau_known_ = false;
  return tau_field_;
}

void FluidLattice::refresh_tau_rows() {
  const std::size_t nx = static_cast<std::size_t>(grid_.nx);
  row_tau_.assign(static_cast<std::size_t>(grid_.ny), 0.0);
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
  for (int y = 0; y < grid_.ny; ++y) {
    const double* row = tau_field_.data() + static_cast<std::size_t>(y) * nx;
    const double first = row[0];
    int one_value = 1;  // the whole row compared, in a vector loop (an early exit kept it scalar)
#pragma omp simd reduction(& : one_value)
    for (std::size_t x = 0; x < nx; ++x) one_value &= row[x] == first ? 1 : 0;
    row_tau_[static_cast<std::size_t>(y)] = one_value != 0 ? first : 0.0;
  }
  row_tau_known_ = true;
}

void FluidLattice::step() {
  zero_cleared_rows();  // the rows no writer added to since they were cleared
  detail::KernelArgs args;
  args.grid = grid_;
  args.f = f_.data();
  args.stride = stride_;
  args.step = streamed_ ? detail::AaStep::local : detail::AaStep::pull_swap;
  args.collision = collision_;
  args.boundaries = boundaries_;
  args.tau_field = tau_field_.empty() ? nullptr : tau_field_.data();
  args.force_x = force_x_.empty() ? nullptr : force_x_.data();
  args.force_y = force_y_.empty() ? nullptr : force_y_.data();
  args.force_rows = force_rows_known_ ? force_rows_.data() : nullptr;
  args.row_tau = row_tau_known_ && !tau_field_.empty() ? row_tau_.data() : nullptr;
  args.uniform_fx = uniform_force_[0];
  args.uniform_fy = uniform_force_[1];
  args.velocity_x = velocity_request_[0];
  args.velocity_y = velocity_request_[1];
  velocity_request_ = {nullptr, nullptr};
  detail::stream_collide(args);
  applied_force_ = uniform_force_;
  streamed_ = !streamed_;
  ++steps_done_;
  velocity_written_ux_ = args.velocity_x;
  velocity_written_step_ = args.velocity_x ? steps_done_ : -1;
}

void FluidLattice::write_velocity_with_next_step(std::span<double> ux, std::span<double> uy) {
  const std::size_t N = grid_.size();
  if (ux.size() != N || uy.size() != N)
    throw std::invalid_argument("FluidLattice::write_velocity_with_next_step: arrays must have one entry per node");
  velocity_request_ = {ux.data(), uy.data()};
}

void FluidLattice::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "raw_populations", f_);
  r.put_scalar(prefix + "streamed", streamed_ ? 1.0 : 0.0);
  r.put(prefix + "uniform_force", uniform_force_);
  r.put(prefix + "applied_force", applied_force_);
  r.put_scalar(prefix + "steps_done", static_cast<double>(steps_done_));
  if (has_force_field()) {
    // As read: a row cleared but not yet zeroed is recorded as zeros.
    auto as_read = [&](const std::vector<double>& field) {
      std::vector<double> out = field;
      const std::size_t nx = static_cast<std::size_t>(grid_.nx);
      for (int y = 0; y < grid_.ny; ++y)
        if (row_cleared(y))
          std::fill_n(out.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * nx), nx, 0.0);
      return out;
    };
    r.put(prefix + "force_x", as_read(force_x_));
    r.put(prefix + "force_y", as_read(force_y_));
  }
  if (has_tau_field()) r.put(prefix + "tau", tau_field_);
}

void FluidLattice::restore_state(const StateRecord& r, const std::string& prefix) {
  r.copy_to(prefix + "raw_populations", f_);
  streamed_ = r.scalar(prefix + "streamed") != 0.0;
  natural_copy_step_ = -1;
  r.copy_to(prefix + "uniform_force", uniform_force_);
  r.copy_to(prefix + "applied_force", applied_force_);
  steps_done_ = static_cast<long>(r.scalar(prefix + "steps_done"));
  velocity_request_ = {nullptr, nullptr};
  velocity_written_step_ = -1;
  if (r.has(prefix + "force_x")) {
    enable_force_field();
    r.copy_to(prefix + "force_x", force_x_);
    r.copy_to(prefix + "force_y", force_y_);
    force_rows_.assign(static_cast<std::size_t>(grid_.ny), force_row::kForced);
    force_rows_known_ = false;  // every row may hold force until the next clear
  }
  if (r.has(prefix + "tau")) {
    enable_tau_field();
    r.copy_to(prefix + "tau", tau_field_);
    refresh_tau_rows();
  }
}

void FluidLattice::mark_natural() {
  streamed_ = false;
  natural_copy_step_ = -1;  // populations() gathers afresh
  velocity_written_step_ = -1;  // the populations changed since
}

std::size_t FluidLattice::slot_of(int x, int y, int k) const {
  if (!streamed_) return k * stride_ + grid_.index(x, y);
  if (x > 0 && x < grid_.nx - 1 && y > 0 && y < grid_.ny - 1) {  // no side crossed
    return d2q9::opposite[k] * stride_ + grid_.index(x + d2q9::cx[k], y + d2q9::cy[k]);
  }
  return detail::streamed_slot(grid_, boundaries_, stride_, x, y, k);
}

FluidLattice::RowView FluidLattice::row_view(int y) const {
  RowView v;
  if (!streamed_) {
    for (int k = 0; k < d2q9::Q; ++k) v.p[k] = f_.data() + k * stride_ + grid_.index(0, y);
    v.first = 0;
    v.last = grid_.nx;
    return v;
  }
  if (y == 0 || y == grid_.ny - 1 || grid_.nx < 3) {  // every node may cross a side
    for (int k = 0; k < d2q9::Q; ++k) v.p[k] = nullptr;
    v.first = v.last = grid_.nx;
    return v;
  }
  // Interior node (x, y): f*_k sits where (x + c_k, y + c_k) pulls along k̄ from.
  for (int k = 0; k < d2q9::Q; ++k) {
    v.p[k] = f_.data() + d2q9::opposite[k] * stride_ + grid_.index(0, y + d2q9::cy[k]) + d2q9::cx[k];
  }
  v.first = 1;
  v.last = grid_.nx - 1;
  return v;
}

void FluidLattice::gather_natural(Storage& out) const {
  const std::size_t N = grid_.size();
  out.resize(d2q9::Q * N);
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
  for (int y = 0; y < grid_.ny; ++y) {
    for (int k = 0; k < d2q9::Q; ++k) {
      double* row = out.data() + k * N + grid_.index(0, y);
      for (int x = 0; x < grid_.nx; ++x) row[x] = f_[slot_of(x, y, k)];
    }
  }
}

std::span<const double> FluidLattice::populations() const {
  if (natural_copy_step_ != steps_done_) {
    gather_natural(natural_copy_);
    natural_copy_step_ = steps_done_;
  }
  return natural_copy_;
}

namespace {
using detail::moments_of;

// moments_of for the nodes [x0, x1) of one row, from its population rows p[i], with F = A +
// field(x) when the row has a force field (kField): node by node the same operations, the
// divisions vectorised across nodes (restrict outputs, the row pointers copied to a local
// array so the loads are not gathers, the field's presence decided once per row).
template <bool kField>
void row_moments(const double* const* p, int x0, int x1, double Ax, double Ay, const double* __restrict fx,
                 const double* __restrict fy, double* __restrict rho, double* __restrict ux,
                 double* __restrict uy) {
  std::array<const double*, d2q9::Q> rows;  // a local copy: no store in the loop can change it
  for (int i = 0; i < d2q9::Q; ++i) rows[static_cast<std::size_t>(i)] = p[i];
#pragma omp simd
  for (int x = x0; x < x1; ++x) {
    double Fx = Ax, Fy = Ay;
    if constexpr (kField) {
      Fx += fx[x];
      Fy += fy[x];
    }
    moments_of([&](std::size_t i) { return rows[i][x]; }, Fx, Fy, rho[x], ux[x], uy[x]);
  }
}
}  // namespace

std::array<double, 2> FluidLattice::collision_force(std::size_t n) const {
  std::array<double, 2> F = applied_force_;
  if (has_force_field()) {
    const bool cleared = row_cleared(static_cast<int>(n / static_cast<std::size_t>(grid_.nx)));
    F[0] += cleared ? 0.0 : force_x_[n];
    F[1] += cleared ? 0.0 : force_y_[n];
  }
  return F;
}

void FluidLattice::node_moments(int x, int y, double& rho, double& ux, double& uy) const {
  double f[d2q9::Q];
  for (int i = 0; i < d2q9::Q; ++i) f[i] = f_[slot_of(x, y, i)];
  const auto F = collision_force(grid_.index(x, y));
  moments_of([&](std::size_t i) { return f[i]; }, F[0], F[1], rho, ux, uy);
}

void FluidLattice::span_moments(int y, int x0, int x1, std::span<double> rho_field, std::span<double> ux_field,
                                std::span<double> uy_field) const {
  const RowView v = row_view(y);
  const std::size_t row = grid_.index(0, y);
  double* rho = rho_field.data();
  double* ux = ux_field.data();
  double* uy = uy_field.data();
  auto edge = [&](int x) { node_moments(x, y, rho[row + x], ux[row + x], uy[row + x]); };
  // The span's part that the row view holds goes through the vector loop, the rest node by node.
  const int first = std::clamp(v.first, x0, x1), last = std::clamp(v.last, first, x1);
  for (int x = x0; x < first; ++x) edge(x);
  if (last > first) {
    const double Ax = applied_force_[0], Ay = applied_force_[1];
    if (has_force_field()) {
      const bool cleared = row_cleared(y);  // its force counts as zero
      const double* fx = cleared ? zero_row_.data() : force_x_.data() + row;
      const double* fy = cleared ? zero_row_.data() : force_y_.data() + row;
      row_moments<true>(v.p, first, last, Ax, Ay, fx, fy, rho + row, ux + row, uy + row);
    } else {
      row_moments<false>(v.p, first, last, Ax, Ay, nullptr, nullptr, rho + row, ux + row, uy + row);
    }
  }
  for (int x = last; x < x1; ++x) edge(x);
}

void FluidLattice::compute_moments(std::span<double> rho, std::span<double> ux, std::span<double> uy) const {
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
  for (int y = 0; y < grid_.ny; ++y) span_moments(y, 0, grid_.nx, rho, ux, uy);
}

Moments FluidLattice::moments() const {
  Moments m;
  m.rho.resize(grid_.size());
  m.ux.resize(grid_.size());
  m.uy.resize(grid_.size());
  compute_moments(m.rho, m.ux, m.uy);
  return m;
}

double FluidLattice::total_mass() const {
  // Row sums, then a serial sum over rows: identical for any thread count.
  std::vector<double> row_sum(static_cast<std::size_t>(grid_.ny), 0.0);
  const std::size_t N = grid_.size();
#pragma omp parallel for schedule(static) if (grid_.worth_threading())
  for (int y = 0; y < grid_.ny; ++y) {
    double s = 0.0;
    const RowView v = row_view(y);
    for (int i = 0; i < d2q9::Q; ++i) {  // x in order: edge columns, interior, edge columns
      for (int x = 0; x < v.first; ++x) s += f_[slot_of(x, y, i)];
      for (int x = v.first; x < v.last; ++x) s += v.p[i][x];
      for (int x = std::max(v.first, v.last); x < grid_.nx; ++x) s += f_[slot_of(x, y, i)];
    }
    row_sum[static_cast<std::size_t>(y)] = s;
  }
  double deviation = 0.0;
  for (double s : row_sum) deviation += s;
  return static_cast<double>(N) + deviation;  // Σ f = N·Σw + Σ f̃
}

std::array<double, 2> FluidLattice::total_momentum() const {
  const Moments m = moments();
  double px = 0.0, py = 0.0;
  for (std::size_t n = 0; n < grid_.size(); ++n) {
    px += m.rho[n] * m.ux[n];
    py += m.rho[n] * m.uy[n];
  }
  return {px, py};
}

namespace {

// The exact scan: the first offending node in row-major order, or the largest speed.
HealthReport scan_health(const Grid& grid, const Moments& m, double max_mach) {
  const double max_speed = max_mach * std::sqrt(d2q9::cs2);
  HealthReport report;
  for (int y = 0; y < grid.ny && report.healthy; ++y) {
    for (int x = 0; x < grid.nx; ++x) {
      const std::size_t n = grid.index(x, y);
      auto fail = [&](const char* quantity, double value, double limit) {
        report.healthy = false;
        report.quantity = quantity;
        report.node_x = x;
        report.node_y = y;
        report.value = value;
        report.limit = limit;
      };
      const double nan = std::numeric_limits<double>::quiet_NaN();
      if (!std::isfinite(m.rho[n])) { fail("density", m.rho[n], nan); break; }
      if (!std::isfinite(m.ux[n])) { fail("velocity_x", m.ux[n], nan); break; }
      if (!std::isfinite(m.uy[n])) { fail("velocity_y", m.uy[n], nan); break; }
      if (!(m.rho[n] > 0.0)) { fail("density", m.rho[n], 0.0); break; }
      const double speed = std::hypot(m.ux[n], m.uy[n]);
      if (speed > max_speed) { fail("mach", speed / std::sqrt(d2q9::cs2), max_mach); break; }
      report.max_speed = std::max(report.max_speed, speed);
    }
  }
  return report;
}

}  // namespace

// The same report as scan_health, most of the time without its per-node hypot and
// branches: one pass of |u|² = ux² + uy² (rounding error a few ulp) clears a state whose
// every node is finite, ρ > 0 and |u|² below the limit by a margin of 1e-12 (far beyond
// those ulp); the largest hypot then lies among the nodes within that margin of the largest
// |u|², which are the only ones it is computed for. Anything else goes to the exact scan.
HealthReport check_health(const Grid& grid, const Moments& m, double max_mach) {
  constexpr double kMargin = 1e-12;
  const double max_speed = max_mach * std::sqrt(d2q9::cs2);
  const double clear_u2 = max_speed * max_speed * (1.0 - kMargin);
  const std::size_t N = m.rho.size();
  double max_u2 = 0.0;
  bool clear = true;
  for (std::size_t n = 0; n < N; ++n) {
    const double u2 = m.ux[n] * m.ux[n] + m.uy[n] * m.uy[n];
    clear &= m.rho[n] > 0.0 && m.rho[n] <= std::numeric_limits<double>::max() && u2 <= clear_u2;
    max_u2 = std::max(max_u2, u2);
  }
  if (!clear) return scan_health(grid, m, max_mach);
  HealthReport report;
  if (max_u2 == 0.0) return report;  // at rest: every hypot is 0
  const double near_max_u2 = max_u2 * (1.0 - kMargin);
  for (std::size_t n = 0; n < N; ++n) {
    const double u2 = m.ux[n] * m.ux[n] + m.uy[n] * m.uy[n];
    if (u2 >= near_max_u2) report.max_speed = std::max(report.max_speed, std::hypot(m.ux[n], m.uy[n]));
  }
  return report;
}

}  // namespace erythro::fluid
